//! A fixed-step co-simulation master for the wheelset FMU and two contact units (left and right
//! wheel, S1002 on UIC60 1:40, `contact_geometry = profiles`), driving the FMUs' binaries
//! through their C ABI (`fmu_master::binary`): the coupled run of issue 28 as
//! scripts/ssp_master.py runs it with fmpy, fast enough for a stability map
//! (docs/coupling-stability.md). Three ways to couple them, [`Master`].

use std::path::Path;

use fmu_master::binary::{file_uri, Functions, Instance, State, Status};
use fmu_master::description::Description;
use wheel_rail_contact::geometry::TrackDimensions;

/// What the wheelset gives each contact unit, by the same names on both sides.
pub const KINEMATICS: [&str; 6] = [
    "wheelset_lateral_displacement",
    "wheelset_yaw_angle",
    "wheelset_lateral_velocity",
    "wheelset_yaw_rate",
    "rolling_speed",
    "wheel_angular_speed",
];
/// The kinematics that move (`rolling_speed` is the constant V): the columns of the contact
/// Jacobian of [`Master::LinearlyImplicit`].
const MOVING: [usize; 5] = [0, 1, 2, 3, 5];
/// Indices into [`KINEMATICS`].
const LATERAL_DISPLACEMENT: usize = 0;
const ROLLING_SPEED: usize = 4;
const ANGULAR_SPEED: usize = 5;
/// What each contact unit gives the wheelset; its input is `<side>_<name>`.
pub const LOADS: [&str; 6] =
    ["track_force_x", "track_force_y", "track_force_z", "track_moment_x", "track_moment_y", "track_moment_z"];
const SIDES: [&str; 2] = ["left", "right"];
/// The wheelset's inputs: the left unit's loads, then the right's.
const LOAD_COUNT: usize = 2 * LOADS.len();

/// The comparison grid of [`Run::displacements`] \[s\]: every communication step of a map must
/// divide it, so that every run has a communication point on it (no interpolation).
pub const SAMPLE_INTERVAL: f64 = 10e-3;

/// A loaded FMU: its model description (GUID, value references, enumeration items), binary and
/// resource location.
pub struct Fmu {
    pub description: Description,
    functions: Functions,
    resource_location: String,
}

impl Fmu {
    /// The binary `library` (the cdylib that `cargo fmu package` puts into the FMU as
    /// `binaries/linux64/<modelIdentifier>.so`) with the model description `xml`, its instances
    /// given `resources` (absolute: the directory holding what the FMU's resources/ holds).
    pub fn load(library: &Path, xml: &Path, resources: &Path) -> Result<Fmu, String> {
        let text = std::fs::read_to_string(xml).map_err(|e| format!("{}: {e}", xml.display()))?;
        Ok(Fmu {
            description: Description::parse(&text)?,
            functions: Functions::load(library)?,
            resource_location: file_uri(resources),
        })
    }

    fn instantiate(&self, name: &str) -> Result<Instance<'_>, String> {
        Instance::new(&self.functions, name, &self.description.guid, &self.resource_location)
    }
}

/// How the master exchanges values at each communication point t_k (step h).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Master {
    /// All units stepped with the others' outputs at t_k, as most hand-written loops do. The
    /// contact unit's outputs at t_k, read before its inputs are set, are those its last doStep
    /// computed from the inputs held over [t_(k-1), t_k]: the wheelset feels the forces of
    /// x_(k-1), one step late. (scripts/ssp_master.py sets a feedthrough unit's inputs before it
    /// reads its outputs, which the unit then computes at them: that master is Gauss–Seidel.)
    Jacobi,
    /// The contact units first (inputs x_k), their outputs then feed the wheelset's step over
    /// [t_k, t_(k+1)]: the forces of x_k, no delay. Same cost as Jacobi.
    GaussSeidel,
    /// The forces over the step taken at the end of the step, linearised: with G(x) the contact
    /// units' outputs after a doStep from t_k with inputs x, and the wheelset's x_(k+1) =
    /// P + S (u − G(x_k)) for loads u (P its step under G(x_k)), the master solves
    /// (I − S J) Δx = P − x_k with J = ∂G/∂x, and steps the wheelset with u = G(x_k) + J Δx.
    /// J by finite differences over fmi2GetFMUstate/SetFMUstate, S once per run likewise.
    LinearlyImplicit,
    /// [`Master::LinearlyImplicit`] with J from the contact units' fmi2GetDirectionalDerivative
    /// at the inputs x_k (the outputs' derivative at the inputs, as a feedthrough read: with
    /// creep relaxation off that is ∂G/∂x; with it on, the relaxed forces' lag over the step is
    /// not in it): one call per unit and moving quantity instead of a probing step each.
    LinearlyImplicitDerivatives,
}

impl Master {
    pub const ALL: [Master; 3] = [Master::Jacobi, Master::GaussSeidel, Master::LinearlyImplicit];

    pub fn name(self) -> &'static str {
        match self {
            Master::Jacobi => "jacobi",
            Master::GaussSeidel => "gauss_seidel",
            Master::LinearlyImplicit => "linearly_implicit",
            Master::LinearlyImplicitDerivatives => "linearly_implicit_derivatives",
        }
    }
}

/// One coupled run's settings.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// The contact units' `creep_force_model` item (`kalker_linear`, `polach`, `exact_table`).
    pub rung: &'static str,
    /// The contact units' `creep_relaxation`.
    pub relaxation: bool,
    pub master: Master,
    /// Forward speed V \[m/s\].
    pub speed: f64,
    /// Communication step h \[s\]; must divide [`SAMPLE_INTERVAL`].
    pub step: f64,
    /// Simulated time \[s\].
    pub duration: f64,
    /// The wheelset's start: y0 \[m\] off centre, at rest in yaw, rolling at V/r_c.
    pub initial_displacement: f64,
}

/// A run is bounded while |y| ≤ this × y0 (below flange contact at 6.6 mm for y0 = 3 mm;
/// the tiny-step runs never exceed y0) …
pub const DISPLACEMENT_BOUND: f64 = 2.0;
/// … and the wheel's spin creepage |Ω r_c / V − 1| ≤ this: 5 times the most that a run at a
/// tiny step (10 µs) reaches, 2 % (at 1 m/s with creep relaxation: the wheelset's torsional
/// vibration on the contacts' tangential stiffness, lightly damped at low speed); an unstable
/// spin mode shows here first.
pub const SPIN_CREEPAGE_BOUND: f64 = 0.1;

/// The outcome of a run.
#[derive(Debug, Clone)]
pub struct Run {
    /// y at t = SAMPLE_INTERVAL, 2 SAMPLE_INTERVAL, … up to where the run ended \[m\].
    pub displacements: Vec<f64>,
    /// None if bounded to the end; else when and why it stopped (an FMU error, |y| beyond
    /// [`DISPLACEMENT_BOUND`] y0, or a spin creepage beyond [`SPIN_CREEPAGE_BOUND`]).
    pub unbounded: Option<String>,
    /// max |Ω r_c / V − 1| over the run (to where it ended).
    pub peak_spin_creepage: f64,
}

fn ok(what: &str, status: Status, instance: &Instance) -> Result<(), String> {
    match status {
        Status::Ok | Status::Warning => Ok(()),
        status => Err(format!("{what}: {status:?} {:?}", instance.take_messages())),
    }
}

fn names(names: &[&str], description: &Description) -> Result<Vec<u32>, String> {
    names.iter().map(|name| description.value_reference(name)).collect()
}

/// The three instances of one run, with the value references the master uses.
struct System<'a> {
    wheelset: Instance<'a>,
    contacts: [Instance<'a>; 2],
    /// The wheelset's outputs [`KINEMATICS`] = each contact unit's inputs of the same names.
    wheelset_kinematics: Vec<u32>,
    contact_kinematics: Vec<u32>,
    /// The wheelset's inputs, left loads then right ([`LOAD_COUNT`]).
    wheelset_loads: Vec<u32>,
    contact_loads: Vec<u32>,
}

impl<'a> System<'a> {
    /// Instantiated and initialised: the wheelset at y0, each contact unit carrying
    /// `wheel_load` with the wheelset's start kinematics.
    fn new(wheelset: &'a Fmu, contact: &'a Fmu, case: &Case, wheel_load: f64) -> Result<System<'a>, String> {
        let w = &wheelset.description;
        let instance = wheelset.instantiate("wheelset")?;
        let wheelset_kinematics = names(&KINEMATICS, w)?;
        ok("wheelset initialisation", instance.enter_initialization(0.0), &instance)?;
        let start = names(&["forward_speed", "initial_lateral_displacement"], w)?;
        ok("wheelset start", instance.set_real(&start, &[case.speed, case.initial_displacement]), &instance)?;
        ok("wheelset initialisation", instance.exit_initialization(), &instance)?;
        let kinematics = get(&instance, &wheelset_kinematics)?;

        let d = &contact.description;
        let contact_kinematics = names(&KINEMATICS, d)?;
        // The track the contact data of docs/wheelset.md were made on.
        let track = TrackDimensions::MANCHESTER_BENCHMARK;
        let track_references = names(
            &[
                "track_gauge",
                "gauge_measuring_height",
                "flange_back_distance",
                "flange_back_position",
                "wheel_nominal_radius",
                "rail_cant",
            ],
            d,
        )?;
        let track_values = [
            track.gauge,
            track.gauge_measuring_height,
            track.flange_back_distance,
            track.flange_back_position,
            track.nominal_radius,
            track.rail_cant,
        ];
        let [left, right] = SIDES.map(|side| contact.instantiate(&format!("{side} wheel")));
        let contacts = [left?, right?];
        for (side, unit) in SIDES.iter().zip(&contacts) {
            let choices = [
                ("contact_geometry", "profiles"),
                // The coupling map was measured with Hertz's patches (as the system's SSP sets).
                ("contact_method", "hertz"),
                ("wheel_side", side),
                ("vertical_contact", "prescribed_force"),
                ("creep_force_model", case.rung),
                ("creep_relaxation", if case.relaxation { "on" } else { "off" }),
            ];
            let references = names(&choices.map(|(name, _)| name), d)?;
            let items = choices.iter().map(|(name, item)| d.item(name, item)).collect::<Result<Vec<_>, _>>()?;
            ok("contact options", unit.set_integer(&references, &items), unit)?;
            ok("contact track", unit.set_real(&track_references, &track_values), unit)?;
            ok("contact initialisation", unit.enter_initialization(0.0), unit)?;
            ok("contact wheel load", unit.set_real(&names(&["vertical_force"], d)?, &[wheel_load]), unit)?;
            ok("contact kinematics", unit.set_real(&contact_kinematics, &kinematics), unit)?;
            ok("contact initialisation", unit.exit_initialization(), unit)?;
        }
        let wheelset_loads =
            SIDES.iter().flat_map(|side| LOADS.map(|load| format!("{side}_{load}"))).collect::<Vec<_>>();
        Ok(System {
            wheelset: instance,
            contacts,
            wheelset_loads: names(&wheelset_loads.iter().map(String::as_str).collect::<Vec<_>>(), w)?,
            wheelset_kinematics,
            contact_kinematics,
            contact_loads: names(&LOADS, d)?,
        })
    }

    fn kinematics(&self) -> Result<Vec<f64>, String> {
        get(&self.wheelset, &self.wheelset_kinematics)
    }

    /// Both contact units' outputs, left then right: the wheelset's inputs.
    fn loads(&self) -> Result<Vec<f64>, String> {
        let mut loads = get(&self.contacts[0], &self.contact_loads)?;
        loads.extend(get(&self.contacts[1], &self.contact_loads)?);
        Ok(loads)
    }

    /// Both contact units stepped over [t, t + h] with the kinematics x held.
    fn step_contacts(&self, x: &[f64], t: f64, h: f64) -> Result<(), String> {
        for unit in &self.contacts {
            ok("contact kinematics", unit.set_real(&self.contact_kinematics, x), unit)?;
            ok("contact doStep", unit.do_step(t, h), unit)?;
        }
        Ok(())
    }

    /// The wheelset stepped over [t, t + h] with the loads u held; its kinematics after.
    fn step_wheelset(&self, u: &[f64], t: f64, h: f64) -> Result<Vec<f64>, String> {
        ok("wheelset loads", self.wheelset.set_real(&self.wheelset_loads, u), &self.wheelset)?;
        ok("wheelset doStep", self.wheelset.do_step(t, h), &self.wheelset)?;
        self.kinematics()
    }

    /// G(x): the contact units' outputs after a step from their current states with x held,
    /// the states left as they were.
    fn probe_contacts(&self, states: &[State; 2], x: &[f64], t: f64, h: f64) -> Result<Vec<f64>, String> {
        self.step_contacts(x, t, h)?;
        let loads = self.loads()?;
        for state in states {
            state.restore()?;
        }
        Ok(loads)
    }

    /// ∂(loads)/∂x at the inputs x from the contact units' directional derivatives, one column
    /// per moving kinematic quantity (the units' inputs set to x, their states unmoved).
    fn contact_derivatives(&self, x: &[f64]) -> Result<Vec<Vec<f64>>, String> {
        for unit in &self.contacts {
            ok("contact kinematics", unit.set_real(&self.contact_kinematics, x), unit)?;
        }
        MOVING
            .iter()
            .map(|&i| {
                let mut column = Vec::with_capacity(LOAD_COUNT);
                for unit in &self.contacts {
                    let (status, rates) =
                        unit.directional_derivative(&self.contact_loads, &[self.contact_kinematics[i]], &[1.0]);
                    ok("fmi2GetDirectionalDerivative", status, unit)?;
                    column.extend(rates);
                }
                Ok(column)
            })
            .collect()
    }

    /// S = ∂x(t + h)/∂u of the wheelset's step from its current state (finite differences, the
    /// state restored), one column per load. The wheelset is linear in its held loads over a
    /// step (docs/wheelset.md, "Integration"), so one S serves a whole run of fixed h.
    fn wheelset_sensitivity(&self, u: &[f64], h: f64) -> Result<Vec<Vec<f64>>, String> {
        let state = self.wheelset.state()?;
        let base = self.step_wheelset(u, 0.0, h)?;
        state.restore()?;
        let mut columns = Vec::with_capacity(LOAD_COUNT);
        for j in 0..LOAD_COUNT {
            // 1 N (N m): small against the loads (≥ 10 kN), large against their round-off.
            let mut perturbed = u.to_vec();
            perturbed[j] += 1.0;
            let x = self.step_wheelset(&perturbed, 0.0, h)?;
            state.restore()?;
            columns.push(x.iter().zip(&base).map(|(a, b)| a - b).collect());
        }
        Ok(columns)
    }
}

fn get(instance: &Instance, references: &[u32]) -> Result<Vec<f64>, String> {
    let (status, values) = instance.get_real(references);
    ok("fmi2GetReal", status, instance)?;
    Ok(values)
}

/// Finite-difference increments of the moving kinematics [`MOVING`]: about 10⁻⁶ in the
/// creepages they cause (ẏ/V, ψ̇ s/V, Ω r/V − 1) and 1 µm / 1 µrad in position, so that the
/// forces change by 1–10 N (f11, f22 ≈ 10 MN): far above their round-off (~10⁻¹¹ of 50 kN) and
/// well inside the linear range (saturation near 2·10⁻³).
fn increments(speed: f64, angular_speed: f64) -> [f64; 5] {
    [1e-6, 1e-6, 1e-6 * speed, 1e-6 * speed, 1e-6 * angular_speed]
}

/// |value| > bound, or not a number.
fn beyond(value: f64, bound: f64) -> bool {
    value.is_nan() || value.abs() > bound
}

/// Solves A z = b in place (Gaussian elimination with partial pivoting; A square, regular).
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let pivot = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs())).unwrap();
        a.swap(k, pivot);
        b.swap(k, pivot);
        let (pivot_rows, rows) = a.split_at_mut(k + 1);
        let (pivot_values, values) = b.split_at_mut(k + 1);
        let (pivot_row, pivot_value) = (&pivot_rows[k], pivot_values[k]);
        for (row, value) in rows.iter_mut().zip(values) {
            let factor = row[k] / pivot_row[k];
            for (entry, pivot) in row[k..].iter_mut().zip(&pivot_row[k..]) {
                *entry -= factor * pivot;
            }
            *value -= factor * pivot_value;
        }
    }
    for k in (0..n).rev() {
        b[k] = (b[k] - (k + 1..n).map(|j| a[k][j] * b[j]).sum::<f64>()) / a[k][k];
    }
    b
}

/// Runs `case` with the wheelset FMU and the contact FMU (two instances), each contact unit
/// carrying `wheel_load` \[N\]; an error only if the system cannot even start.
/// The workspace's release binaries of the wheelset and the contact unit (after `cargo build
/// --release -p wheel-rail-contact-fmu -p wheelset`), with the repository's model descriptions
/// and data/ as the contact unit's resources/ (it holds data/exact_table.bin, as the packaged
/// FMU's does; the wheelset's holds nothing): (wheelset, contact).
pub fn release_fmus() -> Result<(Fmu, Fmu), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("lab/ is in the workspace");
    let (release, resources) = (root.join("target/release"), root.join("data"));
    let contact =
        Fmu::load(&release.join("libwheel_rail_contact_fmu.so"), &root.join("fmu/modelDescription.xml"), &resources)?;
    let wheelset = Fmu::load(&release.join("libwheelset.so"), &root.join("wheelset/modelDescription.xml"), &resources)?;
    Ok((wheelset, contact))
}

pub fn run(wheelset: &Fmu, contact: &Fmu, case: &Case, wheel_load: f64) -> Result<Run, String> {
    let system = System::new(wheelset, contact, case, wheel_load)?;
    let h = case.step;
    let steps = (case.duration / h).round() as usize;
    let per_sample = (SAMPLE_INTERVAL / h).round() as usize;
    assert!(
        ((per_sample as f64) * h - SAMPLE_INTERVAL).abs() < 1e-9 * SAMPLE_INTERVAL,
        "the step {h} s must divide {SAMPLE_INTERVAL} s"
    );
    let centred_radius = get(&system.wheelset, &names(&["centred_rolling_radius"], &wheelset.description)?)?[0];
    let mut x = system.kinematics()?;
    let sensitivity = match case.master {
        Master::LinearlyImplicit | Master::LinearlyImplicitDerivatives => {
            Some(system.wheelset_sensitivity(&system.loads()?, h)?)
        }
        _ => None,
    };
    let mut displacements = Vec::with_capacity(steps / per_sample);
    let mut peak_spin_creepage: f64 = 0.0;
    for k in 0..steps {
        let t = k as f64 * h;
        let stepped = match (case.master, &sensitivity) {
            (Master::Jacobi, _) => system.loads().and_then(|u| {
                system.step_contacts(&x, t, h)?;
                system.step_wheelset(&u, t, h)
            }),
            (Master::GaussSeidel, _) => {
                system.step_contacts(&x, t, h).and_then(|_| system.step_wheelset(&system.loads()?, t, h))
            }
            (Master::LinearlyImplicit, Some(s)) => linearly_implicit_step(&system, s, &x, t, h, Jacobian::Probed),
            (Master::LinearlyImplicitDerivatives, Some(s)) => {
                linearly_implicit_step(&system, s, &x, t, h, Jacobian::Derivatives)
            }
            (Master::LinearlyImplicit | Master::LinearlyImplicitDerivatives, None) => {
                unreachable!("the sensitivity is computed for this master")
            }
        };
        let time = t + h;
        let unbounded = match stepped {
            Err(error) => Some(error),
            Ok(next) => {
                x = next;
                let spin_creepage = x[ANGULAR_SPEED] * centred_radius / x[ROLLING_SPEED] - 1.0;
                peak_spin_creepage = peak_spin_creepage.max(spin_creepage.abs());
                if beyond(x[LATERAL_DISPLACEMENT], DISPLACEMENT_BOUND * case.initial_displacement) {
                    Some(format!("|y| = {:e} m", x[LATERAL_DISPLACEMENT].abs()))
                } else if beyond(spin_creepage, SPIN_CREEPAGE_BOUND) {
                    Some(format!("spin creepage {spin_creepage:e}"))
                } else {
                    None
                }
            }
        };
        if let Some(reason) = unbounded {
            return Ok(Run {
                displacements,
                unbounded: Some(format!("t = {time:.5} s: {reason}")),
                peak_spin_creepage,
            });
        }
        if (k + 1) % per_sample == 0 {
            displacements.push(x[LATERAL_DISPLACEMENT]);
        }
    }
    Ok(Run { displacements, unbounded: None, peak_spin_creepage })
}

/// Where [`linearly_implicit_step`] takes J from.
#[derive(Clone, Copy)]
enum Jacobian {
    /// Finite differences of probing steps over FMU states.
    Probed,
    /// The contact units' directional derivatives.
    Derivatives,
}

/// One step of [`Master::LinearlyImplicit`] (or its variant with derivatives) from kinematics x
/// at t: the wheelset's kinematics at t + h, the contact units stepped with them.
fn linearly_implicit_step(
    system: &System,
    sensitivity: &[Vec<f64>],
    x: &[f64],
    t: f64,
    h: f64,
    source: Jacobian,
) -> Result<Vec<f64>, String> {
    let states = [system.contacts[0].state()?, system.contacts[1].state()?];
    let loads = system.probe_contacts(&states, x, t, h)?;
    // J = ∂G/∂x, one column per moving kinematic quantity.
    let jacobian: Vec<Vec<f64>> = match source {
        Jacobian::Probed => MOVING
            .iter()
            .zip(increments(x[ROLLING_SPEED], x[ANGULAR_SPEED]))
            .map(|(&i, increment)| {
                let mut perturbed = x.to_vec();
                perturbed[i] += increment;
                let probed = system.probe_contacts(&states, &perturbed, t, h)?;
                Ok(probed.iter().zip(&loads).map(|(a, b)| (a - b) / increment).collect())
            })
            .collect::<Result<_, String>>()?,
        Jacobian::Derivatives => system.contact_derivatives(x)?,
    };
    let wheelset_state = system.wheelset.state()?;
    let predicted = system.step_wheelset(&loads, t, h)?;
    wheelset_state.restore()?;
    // (I − S J) Δx = P − x over the moving quantities (S J has no rolling_speed row: V is constant).
    let sj = |row: usize, column: usize| -> f64 {
        (0..LOAD_COUNT).map(|l| sensitivity[l][MOVING[row]] * jacobian[column][l]).sum()
    };
    let matrix = (0..MOVING.len())
        .map(|r| (0..MOVING.len()).map(|c| f64::from(u8::from(r == c)) - sj(r, c)).collect())
        .collect();
    let change = solve(matrix, MOVING.iter().map(|&i| predicted[i] - x[i]).collect());
    let implicit_loads: Vec<f64> = (0..LOAD_COUNT)
        .map(|l| loads[l] + (0..MOVING.len()).map(|c| jacobian[c][l] * change[c]).sum::<f64>())
        .collect();
    let next = system.step_wheelset(&implicit_loads, t, h)?;
    // The contact units' step committed with the kinematics they will be read at.
    system.step_contacts(&next, t, h)?;
    Ok(next)
}

#[cfg(test)]
mod tests {
    use super::solve;

    #[test]
    fn solve_needs_pivoting_and_finds_the_solution() {
        // A zero first pivot: without row exchange the elimination divides by zero.
        let a = vec![vec![0.0, 2.0, 1.0], vec![1.0, 1.0, 0.0], vec![4.0, 0.0, 3.0]];
        let z = [1.0, -2.0, 3.0];
        let b = a.iter().map(|row| row.iter().zip(&z).map(|(a, z)| a * z).sum()).collect();
        for (found, expected) in solve(a, b).iter().zip(z) {
            assert!((found - expected).abs() < 1e-14, "{found} against {expected}");
        }
    }
}
