//! The FMU's values ↔ the physics: the slave layer's [`Model`] for the wheelset ([`WheelsetModel`],
//! whose state is a [`Wheelset`]).
//!
//! The outputs are the state (y, ψ, ẏ, ψ̇, Ω, and V): ExitInitializationMode sets them from the
//! initial-value parameters, with Ω = V/r_c (both wheels on their centred rolling radius, so the
//! run starts without longitudinal creepage, docs/wheelset.md); DoStep advances them with
//! [`physics::advance`] under the inputs held. In Model Exchange the master integrates: the
//! outputs but V are the continuous states, and every evaluation sets the locals `der(...)` to
//! [`physics::Parameters::rates`] at the current states and loads. Errors name the variable, the
//! value and the time.

use fmi2_slave::instance::{decode_run, encode_run, keep_if_finite, Evaluation, FmuState, Model};
use fmi2_slave::mode::{Mode, INITIALIZED};

use crate::model_description::{self, Causality, Inputs, Locals, Outputs, Parameters, Values, VARIABLES};
use crate::physics::{self, Loads, State, WheelsetError};

/// One wheelset's values: inputs, parameters and the outputs, which are its state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Wheelset {
    pub values: Values,
}

impl Wheelset {
    fn physics_parameters(parameters: &Parameters) -> physics::Parameters {
        let Parameters {
            mass,
            yaw_inertia,
            spin_inertia,
            longitudinal_stiffness,
            longitudinal_damping,
            lateral_stiffness,
            lateral_damping,
            lateral_semi_spacing,
            forward_speed,
            centred_rolling_radius: _,
            derailment_displacement,
            initial_lateral_displacement: _,
            initial_yaw_angle: _,
            initial_lateral_velocity: _,
            initial_yaw_rate: _,
        } = *parameters;
        physics::Parameters {
            mass,
            yaw_inertia,
            spin_inertia,
            longitudinal_stiffness,
            longitudinal_damping,
            lateral_stiffness,
            lateral_damping,
            lateral_semi_spacing,
            forward_speed,
            derailment_displacement,
        }
    }

    /// The parameters as initialize requires them, or why not (naming the variable and value);
    /// also the rolling speed Ω = V/r_c they start with must be finite.
    fn check_parameters(parameters: &Parameters) -> Result<(), String> {
        Self::physics_parameters(parameters).check().map_err(|e| e.to_string())?;
        let radius = parameters.centred_rolling_radius;
        if !(radius.is_finite() && radius > 0.0) {
            return Err(format!("centred_rolling_radius = {radius} is invalid: must be finite and > 0"));
        }
        let spin = parameters.forward_speed / radius;
        if !spin.is_finite() {
            return Err(format!(
                "centred_rolling_radius = {radius:e} m is invalid: forward_speed = {} m/s over it, the wheels' angular \
                 speed, is {spin} rad/s",
                parameters.forward_speed
            ));
        }
        Ok(())
    }

    fn state(outputs: &Outputs) -> State {
        State {
            lateral_displacement: outputs.wheelset_lateral_displacement,
            yaw_angle: outputs.wheelset_yaw_angle,
            lateral_velocity: outputs.wheelset_lateral_velocity,
            yaw_rate: outputs.wheelset_yaw_rate,
            wheel_angular_speed: outputs.wheel_angular_speed,
        }
    }

    fn outputs(state: &State, forward_speed: f64) -> Outputs {
        Outputs {
            wheelset_lateral_displacement: state.lateral_displacement,
            wheelset_yaw_angle: state.yaw_angle,
            wheelset_lateral_velocity: state.lateral_velocity,
            wheelset_yaw_rate: state.yaw_rate,
            rolling_speed: forward_speed,
            wheel_angular_speed: state.wheel_angular_speed,
        }
    }

    /// The state derivatives as the locals `der(...)`.
    fn locals(rates: &State) -> Locals {
        Locals {
            der_wheelset_lateral_displacement: rates.lateral_displacement,
            der_wheelset_yaw_angle: rates.yaw_angle,
            der_wheelset_lateral_velocity: rates.lateral_velocity,
            der_wheelset_yaw_rate: rates.yaw_rate,
            der_wheel_angular_speed: rates.wheel_angular_speed,
        }
    }

    /// The loads on the wheelset: both wheels' forces and moments summed (module doc of
    /// [`physics`]); every input finite, and each wheel pressed onto its rail (track z is down,
    /// so a wheel carrying load has track_force_z < 0; ≥ 0 is lift-off, which the model cannot
    /// go on from).
    fn loads(&self, time: f64) -> Result<Loads, String> {
        let time = readable(time);
        for input in VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
            let value = self.values.real(input.value_reference).unwrap_or(f64::NAN);
            if !value.is_finite() {
                let unit = input.unit.unwrap_or("");
                return Err(format!("{} = {value} {unit} at t = {time} s is invalid: must be finite", input.name));
            }
        }
        let Inputs {
            left_track_force_x: _,
            left_track_force_y,
            left_track_force_z,
            left_track_moment_x: _,
            left_track_moment_y,
            left_track_moment_z,
            right_track_force_x: _,
            right_track_force_y,
            right_track_force_z,
            right_track_moment_x: _,
            right_track_moment_y,
            right_track_moment_z,
        } = self.values.inputs;
        for (name, force) in [("left_track_force_z", left_track_force_z), ("right_track_force_z", right_track_force_z)]
        {
            if force >= 0.0 {
                return Err(format!(
                    "the wheel lifts off the rail at t = {time} s: {name} = {force} N (a wheel carrying load has \
                     track_force_z < 0, track z pointing down)"
                ));
            }
        }
        Ok(Loads {
            lateral_force: left_track_force_y + right_track_force_y,
            axle_moment: left_track_moment_y + right_track_moment_y,
            yaw_moment: left_track_moment_z + right_track_moment_z,
        })
    }
}

/// A master's time for a message: 12 significant digits, printed shortest, so that the
/// 1463rd step of 0.2 ms reads 0.2926 rather than its sum's rounding noise.
fn readable(time: f64) -> f64 {
    format!("{time:.11e}").parse().unwrap_or(time)
}

/// A physics error as the FMU reports it: the variable's FMU name and the time.
fn describe(error: WheelsetError, time: f64) -> String {
    let time = readable(time);
    match error {
        WheelsetError::Derailed { lateral_displacement, limit } => format!(
            "the wheelset derails at t = {time} s: wheelset_lateral_displacement = {lateral_displacement} m is beyond \
             derailment_displacement = {limit} m"
        ),
        other => format!("{other} (at t = {time} s)"),
    }
}

/// The slave layer's model of the wheelset FMU: its state is a [`Wheelset`], and it keeps nothing
/// beside it (no cache, no resources).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelsetModel;

impl Model for WheelsetModel {
    type State = Wheelset;

    const GUID: &'static str = model_description::GUID;
    const MODEL_IDENTIFIER: &'static str = model_description::MODEL_IDENTIFIER;
    const LOG_CATEGORIES: &'static [&'static str] = model_description::LOG_CATEGORIES;
    const STATE_LAYOUT_TAG: u64 = model_description::STATE_LAYOUT_TAG;
    const STATE_MAGIC: [u8; 8] = *b"WSTstate";
    /// Mode, time, stop time, then every Real ([`encode_run`]).
    const STATE_FORMAT_VERSION: u16 = 3;
    const MODEL_EXCHANGE: bool = model_description::MODEL_EXCHANGE;
    const CONTINUOUS_STATES: &'static [(u32, u32, f64)] = model_description::CONTINUOUS_STATES;
    const EVENT_INDICATORS: usize = model_description::EVENT_INDICATORS;

    fn instantiate(_resource_location: Option<&str>) -> Result<(Self, Option<String>), String> {
        Ok((WheelsetModel, None))
    }

    fn reset(&mut self) {}

    fn start() -> Wheelset {
        Wheelset::default()
    }

    fn variable(value_reference: u32) -> Option<&'static fmi2_slave::variables::Variable> {
        model_description::variable(value_reference)
    }

    fn variables() -> &'static [fmi2_slave::variables::Variable] {
        &VARIABLES
    }

    #[inline]
    fn access(value_reference: u32) -> u8 {
        model_description::access_of(value_reference)
    }

    #[inline]
    fn real(state: &Wheelset, value_reference: u32) -> Option<f64> {
        state.values.real(value_reference)
    }

    #[inline]
    fn real_mut(state: &mut Wheelset, value_reference: u32) -> Option<&mut f64> {
        state.values.real_mut(value_reference)
    }

    /// On a copy, kept only if every output is finite ([`keep_if_finite`]).
    fn evaluate(&mut self, state: &mut Wheelset, evaluation: Evaluation) -> Result<Option<String>, String> {
        match evaluation {
            Evaluation::Initialise => keep_if_finite::<Self>(state, Wheelset::initialize)?,
            Evaluation::Step { time, size } => keep_if_finite::<Self>(state, |next| next.step(time, size))?,
            // Its outputs are its state: no input acts on them; the derivatives at the loads.
            Evaluation::Feedthrough { time } => keep_if_finite::<Self>(state, |next| next.derive(time))?,
        }
        Ok(None)
    }

    /// Model Exchange's accepted point must lie within the derailment bound, where a step of
    /// Co-Simulation stops too; no step events.
    fn completed_integrator_step(&mut self, state: &Wheelset, time: f64) -> Result<bool, String> {
        let (lateral_displacement, limit) =
            (state.values.outputs.wheelset_lateral_displacement, state.values.parameters.derailment_displacement);
        if lateral_displacement.abs() > limit {
            return Err(describe(WheelsetError::Derailed { lateral_displacement, limit }, time));
        }
        Ok(false)
    }

    fn encode(state: &FmuState<Wheelset>) -> Vec<u8> {
        encode_run(state, &state.model.to_bytes())
    }

    fn decode(payload: &[u8]) -> Result<FmuState<Wheelset>, String> {
        let run = decode_run(payload)?;
        let model = Wheelset::from_bytes(run.model)?;
        Ok(FmuState { mode: run.mode, time: run.time, stop_time: run.stop_time, model })
    }

    fn check_state(state: &Wheelset, mode: Mode) -> Result<(), String> {
        state.check_state(mode)
    }
}

/// The wheelset's computations on its values.
impl Wheelset {
    /// The parameters checked, the outputs from the initial values; the start must lie within
    /// the derailment bound.
    pub fn initialize(&mut self) -> Result<(), String> {
        let parameters = self.values.parameters;
        Self::check_parameters(&parameters)?;
        let initial = [
            ("initial_lateral_displacement", parameters.initial_lateral_displacement),
            ("initial_yaw_angle", parameters.initial_yaw_angle),
            ("initial_lateral_velocity", parameters.initial_lateral_velocity),
            ("initial_yaw_rate", parameters.initial_yaw_rate),
        ];
        if let Some((name, value)) = initial.iter().find(|(_, value)| !value.is_finite()) {
            return Err(format!("{name} = {value} is invalid: must be finite"));
        }
        let limit = parameters.derailment_displacement;
        if parameters.initial_lateral_displacement.abs() > limit {
            return Err(format!(
                "initial_lateral_displacement = {} is invalid: must be within derailment_displacement = {limit}",
                parameters.initial_lateral_displacement
            ));
        }
        let state = State {
            lateral_displacement: parameters.initial_lateral_displacement,
            yaw_angle: parameters.initial_yaw_angle,
            lateral_velocity: parameters.initial_lateral_velocity,
            yaw_rate: parameters.initial_yaw_rate,
            ..State::rolling(parameters.forward_speed, parameters.centred_rolling_radius)
        };
        self.values.outputs = Self::outputs(&state, parameters.forward_speed);
        // The derivatives at the loads as they start, where those are valid (a master may set
        // the loads only after initialization; Model Exchange reads the derivatives after it).
        if self.derive(0.0).is_err() {
            self.values.locals = Locals::default();
        }
        Ok(())
    }

    /// The locals `der(...)`: the rates at the current state and loads.
    pub fn derive(&mut self, time: f64) -> Result<(), String> {
        let loads = self.loads(time)?;
        let parameters = Self::physics_parameters(&self.values.parameters);
        self.values.locals = Self::locals(&parameters.rates(&Self::state(&self.values.outputs), &loads));
        Ok(())
    }

    pub fn step(&mut self, time: f64, step: f64) -> Result<(), String> {
        let loads = self.loads(time)?;
        let parameters = Self::physics_parameters(&self.values.parameters);
        let next = physics::advance(&parameters, &Self::state(&self.values.outputs), &loads, step)
            .map_err(|error| describe(error, time + step))?;
        self.values.outputs = Self::outputs(&next, parameters.forward_speed);
        self.values.locals = Self::locals(&parameters.rates(&next, &loads));
        Ok(())
    }

    /// Every Real in the order of [`VARIABLES`], as little-endian f64: the outputs are the state,
    /// so this is all of it.
    pub fn to_bytes(&self) -> Vec<u8> {
        VARIABLES.iter().flat_map(|v| self.values.real(v.value_reference).unwrap_or(f64::NAN).to_le_bytes()).collect()
    }

    /// A restored state as this FMU can hold it in `mode`: every output finite (start values,
    /// then only what initialize and step committed, which the slave layer checks); once
    /// initialized (stepComplete, terminated: the fixed parameters can no longer be set) the
    /// parameters as initialize checked them and the lateral displacement within the derailment
    /// bound, where a step stops. Before that, parameters may hold any value, as after
    /// fmi2SetReal: ExitInitializationMode reports an invalid one.
    pub fn check_state(&self, mode: Mode) -> Result<(), String> {
        for output in VARIABLES.iter().filter(|v| v.causality == Causality::Output) {
            let value = self.values.real(output.value_reference).unwrap_or(f64::NAN);
            if !value.is_finite() {
                return Err(format!("{} = {value} is invalid: an output is always finite", output.name));
            }
        }
        if !INITIALIZED.contains(mode) {
            return Ok(());
        }
        Self::check_parameters(&self.values.parameters)?;
        let (lateral, limit) =
            (self.values.outputs.wheelset_lateral_displacement, self.values.parameters.derailment_displacement);
        if lateral.abs() > limit {
            return Err(format!(
                "wheelset_lateral_displacement = {lateral} is invalid: beyond derailment_displacement = {limit}, where \
                 the wheelset stops"
            ));
        }
        Ok(())
    }

    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        if bytes.len() != 8 * VARIABLES.len() {
            return Err(format!(
                "{} bytes of values, not the {} of this FMU's variables",
                bytes.len(),
                8 * VARIABLES.len()
            ));
        }
        let mut model = Wheelset::default();
        for (variable, chunk) in VARIABLES.iter().zip(bytes.chunks_exact(8)) {
            let value = f64::from_le_bytes(chunk.try_into().expect("8 bytes"));
            if let Some(field) = model.values.real_mut(variable.value_reference) {
                *field = value;
            }
        }
        Ok(model)
    }
}

#[cfg(test)]
mod tests {
    use fmi2_slave::instance::Model;
    use fmi2_slave::mode::Mode::{self, InitializationMode, Instantiated, StepComplete, Terminated};

    use super::{readable, Wheelset, WheelsetModel};

    /// The slave layer reads the outputs it guards (and their dependencies) from this table:
    /// the model description's, every variable in its order; and Get/Set read the generated
    /// access table, which says of each variable what the slave layer's rule says.
    #[test]
    fn the_variables_the_slave_layer_reads_are_the_model_descriptions() {
        assert_eq!(WheelsetModel::variables(), &crate::model_description::VARIABLES[..]);
        for variable in WheelsetModel::variables() {
            let bits = fmi2_slave::variables::access::of(variable, WheelsetModel::variables());
            assert_eq!(WheelsetModel::access(variable.value_reference), bits, "{}", variable.name);
        }
        assert_eq!(WheelsetModel::access(9999), 0);
    }

    fn initialized() -> Wheelset {
        let mut wheelset = Wheelset::default();
        wheelset.initialize().unwrap();
        wheelset
    }

    fn refusal(wheelset: &Wheelset, mode: Mode) -> String {
        wheelset.check_state(mode).unwrap_err()
    }

    /// What a restored state may hold depends on its mode: outputs are always finite; the fixed
    /// parameters, and the bound a step keeps, only once initialized.
    #[test]
    fn a_restored_state_is_checked_as_its_mode_allows() {
        for mode in [Instantiated, InitializationMode, StepComplete, Terminated] {
            assert_eq!(Wheelset::default().check_state(mode), Ok(()), "{mode:?}");
            assert_eq!(initialized().check_state(mode), Ok(()), "{mode:?}");
            let mut output = initialized();
            output.values.outputs.wheel_angular_speed = f64::INFINITY;
            assert_eq!(refusal(&output, mode), "wheel_angular_speed = inf is invalid: an output is always finite");
            // Inputs may hold anything, as after fmi2SetReal: the next step names them.
            let mut input = initialized();
            input.values.inputs.left_track_force_z = f64::NAN;
            assert_eq!(input.check_state(mode), Ok(()), "{mode:?}");
        }
        // A parameter set before initialization may be invalid (ExitInitializationMode says so);
        // after it, the state cannot hold one.
        let mut mass = initialized();
        mass.values.parameters.mass = -1.0;
        let mut radius = initialized();
        radius.values.parameters.centred_rolling_radius = 5e-324;
        let mut derailed = initialized();
        derailed.values.outputs.wheelset_lateral_displacement = -0.5;
        for mode in [Instantiated, InitializationMode] {
            for wheelset in [&mass, &radius, &derailed] {
                assert_eq!(wheelset.check_state(mode), Ok(()), "{mode:?}");
            }
        }
        for mode in [StepComplete, Terminated] {
            assert!(refusal(&mass, mode).starts_with("mass = -1"), "{}", refusal(&mass, mode));
            assert!(refusal(&radius, mode).starts_with("centred_rolling_radius = 5e-324 m is invalid"));
            assert_eq!(
                refusal(&derailed, mode),
                "wheelset_lateral_displacement = -0.5 is invalid: beyond derailment_displacement = 0.01, where the \
                 wheelset stops"
            );
        }
    }

    /// Defect 8: V/r_c overflowed to an infinite wheel_angular_speed for a positive r_c.
    #[test]
    fn initialize_refuses_a_rolling_radius_whose_angular_speed_overflows() {
        let mut wheelset = Wheelset::default();
        wheelset.values.parameters.centred_rolling_radius = 5e-324;
        let before = wheelset;
        assert_eq!(
            wheelset.initialize(),
            Err("centred_rolling_radius = 5e-324 m is invalid: forward_speed = 20 m/s over it, the wheels' \
                 angular speed, is inf rad/s"
                .to_owned())
        );
        assert_eq!(wheelset, before);
    }

    /// A summed time's rounding noise goes, its digits stay: 12 significant ones.
    #[test]
    fn a_time_is_printed_to_twelve_significant_digits() {
        let summed = (0..1463).fold(0.0, |time, _| time + 2e-4);
        assert_ne!(summed, 0.2926);
        assert_eq!(format!("{}", readable(summed)), "0.2926");
        assert_eq!(format!("{}", readable(0.1 + 0.2)), "0.3");
        assert_eq!(format!("{}", readable(3e-7)), "0.0000003");
        assert_eq!(format!("{}", readable(123456.789012345)), "123456.789012");
        assert_eq!(format!("{}", readable(-0.5)), "-0.5");
    }
}
