//! A C-ABI test master for the FMU's binaries of every platform: it loads the binary with
//! libloading and drives it as a co-simulation master does, printing each result in a canonical
//! text form (every f64 as its bit pattern), so that the linux64 run and the win64 run (under
//! wine) can be compared value by value (`scripts/test-platforms`).
//!
//! ```text
//! fmu-master run DIR [--save-state FILE]   DIR: the unzipped FMU; the binary of this platform
//! fmu-master restore DIR FILE              continue from a serialized FMU state (any platform's)
//! fmu-master compare A B                   equal bit for bit, else within 1e-12 relative
//! ```
//!
//! `run` covers the default scene (the README's creepage sweep), every value of the model
//! enumeration, invalid inputs (each an fmi2Error naming the value, the instance usable after),
//! lift-off, and an FMU-state serialize/deserialize round trip. It exits non-zero if the binary
//! breaks one of these rules; `compare` exits non-zero if two runs differ beyond the tolerance.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use fmu_master::binary::{file_uri, Functions, Instance, Status};
use fmu_master::compare;
use fmu_master::description::Description;

/// The model-choice parameter (an enumeration) whose every item `run` exercises.
const MODEL_PARAMETER: &str = "creep_force_model";
/// The communication step of every scenario.
const STEP: f64 = 1e-3;

/// The results of a run, one line each, and the broken rules.
#[derive(Default)]
struct Report {
    lines: String,
    failures: Vec<String>,
}

impl Report {
    fn line(&mut self, line: impl AsRef<str>) {
        self.lines.push_str(line.as_ref());
        self.lines.push('\n');
    }

    /// `<label> <name> f64:<bits> # <value>`: `compare` reads the bits; the value is for people.
    fn real(&mut self, label: &str, name: &str, value: f64) {
        self.line(format!("{label} {name} f64:{:016x} # {value:e}", value.to_bits()));
    }

    fn expect(&mut self, what: &str, holds: bool) {
        self.line(format!("{what}: {}", if holds { "yes" } else { "NO" }));
        if !holds {
            self.failures.push(what.to_owned());
        }
    }

    fn messages(&mut self, label: &str, instance: &Instance) {
        for (status, category, text) in instance.take_messages() {
            self.line(format!("{label} log {status:?} {category} {text}"));
        }
    }
}

/// The FMU opened: its description, the binary of the platform this master runs on and the
/// resource URI of its `resources/` (as this platform's masters write it: `file:///Z:/…/resources`
/// on Windows).
struct Fmu {
    description: Description,
    functions: Functions,
    resource_location: String,
}

impl Fmu {
    fn open(directory: &Path) -> Result<Fmu, String> {
        let xml = std::fs::read_to_string(directory.join("modelDescription.xml"))
            .map_err(|e| format!("{}/modelDescription.xml: {e}", directory.display()))?;
        let description = Description::parse(&xml)?;
        let (folder, extension) = if cfg!(windows) { ("win64", "dll") } else { ("linux64", "so") };
        let library: PathBuf =
            directory.join("binaries").join(folder).join(format!("{}.{extension}", description.model_identifier));
        let functions = Functions::load(&library)?;
        let resources = std::path::absolute(directory.join("resources"))
            .map_err(|e| format!("{}/resources: {e}", directory.display()))?;
        Ok(Fmu { description, functions, resource_location: file_uri(&resources) })
    }

    fn vr(&self, name: &str) -> u32 {
        self.description.value_reference(name).unwrap_or_else(|e| panic!("{e}"))
    }

    /// Instantiated, the integer parameters set (before initialisation, as `fixed` ones must be),
    /// initialised at t = 0.
    fn initialised(&self, name: &str, parameters: &[(u32, i32)], report: &mut Report) -> Result<Instance<'_>, String> {
        let instance = Instance::new(&self.functions, name, &self.description.guid, &self.resource_location)?;
        for &(reference, value) in parameters {
            report.expect(
                &format!("{name}: fmi2SetInteger {reference} = {value} is OK"),
                instance.set_integer(&[reference], &[value]) == Status::Ok,
            );
        }
        let entered = instance.enter_initialization(0.0);
        let exited = instance.exit_initialization();
        report.expect(&format!("{name}: initialisation is OK"), (entered, exited) == (Status::Ok, Status::Ok));
        report.messages(name, &instance);
        Ok(instance)
    }

    /// Every Real output, read after a step.
    fn outputs(&self, instance: &Instance, label: &str, report: &mut Report) {
        let outputs = self.description.real_outputs();
        let references: Vec<u32> = outputs.iter().map(|v| v.value_reference).collect();
        let (status, values) = instance.get_real(&references);
        report.expect(&format!("{label}: fmi2GetReal is OK"), status == Status::Ok);
        for (variable, value) in outputs.iter().zip(values) {
            report.real(label, &variable.name, value);
        }
    }

    /// Sets the three creepages, steps from `time`, prints the outputs.
    fn step_at(&self, instance: &Instance, time: f64, creepages: [f64; 3], label: &str, report: &mut Report) {
        let references = ["creepage_longitudinal", "creepage_lateral", "spin_creepage"].map(|name| self.vr(name));
        report.expect(&format!("{label}: fmi2SetReal is OK"), instance.set_real(&references, &creepages) == Status::Ok);
        report.expect(&format!("{label}: fmi2DoStep is OK"), instance.do_step(time, STEP) == Status::Ok);
        report.messages(label, instance);
        self.outputs(instance, label, report);
    }
}

/// The README's default scene: ξ = 0 … 1 % in steps of 0.05 %, everything else at its start value.
fn default_scene(fmu: &Fmu, report: &mut Report) -> Result<(), String> {
    let instance = fmu.initialised("default", &[], report)?;
    for index in 0..=20 {
        let creepage = index as f64 * 5e-4;
        fmu.step_at(&instance, index as f64 * STEP, [creepage, 0.0, 0.0], &format!("default xi={creepage:e}"), report);
    }
    Ok(())
}

/// Creepages with spin, in both directions, in and beyond the linear range.
const MIXED_CREEPAGES: [[f64; 3]; 3] = [[1e-3, 0.0, 0.0], [-2e-3, 1e-3, 0.1], [5e-3, -3e-3, -0.5]];

/// Every item of the model enumeration on the mixed creepages.
fn every_model(fmu: &Fmu, report: &mut Report) -> Result<(), String> {
    let parameter = fmu.description.variable(MODEL_PARAMETER)?;
    report.expect(&format!("{MODEL_PARAMETER} has enumeration items"), !parameter.items.is_empty());
    for (item, value) in &parameter.items {
        let label = format!("{MODEL_PARAMETER}={item}");
        let instance = fmu.initialised(&label, &[(parameter.value_reference, *value)], report)?;
        for (index, creepages) in MIXED_CREEPAGES.iter().enumerate() {
            fmu.step_at(&instance, index as f64 * STEP, *creepages, &format!("{label} point={index}"), report);
        }
    }
    Ok(())
}

/// Invalid inputs: each an fmi2Error at fmi2DoStep naming the value, the outputs kept, and the
/// instance usable again once the value is good. Lift-off (a negative normal force) is not an
/// error: zero forces.
fn bad_inputs(fmu: &Fmu, report: &mut Report) -> Result<(), String> {
    let instance = fmu.initialised("bad_inputs", &[], report)?;
    fmu.step_at(&instance, 0.0, MIXED_CREEPAGES[1], "bad_inputs good", report);
    let outputs: Vec<u32> = fmu.description.real_outputs().iter().map(|v| v.value_reference).collect();
    let mut time = STEP;
    for (name, bad) in [
        ("creepage_lateral", f64::NAN),
        ("normal_force", f64::INFINITY),
        ("semi_axis_a", 0.0),
        ("friction_coefficient", -0.1),
        ("poisson_ratio", 0.6),
    ] {
        let label = format!("bad_inputs {name}={bad}");
        let reference = fmu.vr(name);
        let (_, good) = instance.get_real(&[reference]);
        let (_, before) = instance.get_real(&outputs);
        report.expect(&format!("{label}: fmi2SetReal is OK"), instance.set_real(&[reference], &[bad]) == Status::Ok);
        report.expect(&format!("{label}: fmi2DoStep is fmi2Error"), instance.do_step(time, STEP) == Status::Error);
        let messages = instance.take_messages();
        let names_it = messages.iter().any(|(status, _, text)| *status == Status::Error && text.contains(name));
        report.expect(&format!("{label}: the error message names {name}"), names_it);
        for (status, category, text) in messages {
            report.line(format!("{label} log {status:?} {category} {text}"));
        }
        // An input the outputs depend on directly: read at the bad value they are the same error
        // (direct feedthrough), and back at the good value the ones before. A parameter acts at
        // the next step: the outputs are the last step's at once.
        let feeds_through = fmu.description.variable(name).is_ok_and(|v| v.causality == "input");
        if feeds_through {
            let (status, _) = instance.get_real(&outputs);
            report.expect(&format!("{label}: fmi2GetReal at it is fmi2Error"), status == Status::Error);
            let messages = instance.take_messages();
            let names_it = messages.iter().any(|(status, _, text)| *status == Status::Error && text.contains(name));
            report.expect(&format!("{label}: fmi2GetReal's message names {name}"), names_it);
        }
        report.expect(
            &format!("{label}: the good value sets again"),
            instance.set_real(&[reference], &good) == Status::Ok,
        );
        let (_, after) = instance.get_real(&outputs);
        let kept = before.iter().zip(&after).all(|(b, a)| b.to_bits() == a.to_bits());
        report.expect(&format!("{label}: the outputs keep their last valid values"), kept);
        report.expect(&format!("{label}: fmi2DoStep is OK again"), instance.do_step(time, STEP) == Status::Ok);
        report.messages(&label, &instance);
        time += STEP;
    }
    let normal_force = fmu.vr("normal_force");
    report.expect("lift_off: fmi2SetReal is OK", instance.set_real(&[normal_force], &[-10.0]) == Status::Ok);
    report.expect("lift_off: fmi2DoStep is OK", instance.do_step(time, STEP) == Status::Ok);
    let forces = ["force_longitudinal", "force_lateral"].map(|name| fmu.vr(name));
    let (_, values) = instance.get_real(&forces);
    report.expect("lift_off: zero forces", values == [0.0, 0.0]);
    fmu.outputs(&instance, "lift_off", report);
    Ok(())
}

/// The scene whose FMU state is saved: creep relaxation (the state carries the relaxed forces),
/// the Polach 2005 dry traction law, Hertz's ellipse.
fn stateful<'a>(fmu: &'a Fmu, name: &str, report: &mut Report) -> Result<Instance<'a>, String> {
    let description = &fmu.description;
    let parameters = [
        (fmu.vr("creep_relaxation"), description.item("creep_relaxation", "on")?),
        (fmu.vr("traction_law"), description.item("traction_law", "polach2005_dry")?),
        (fmu.vr("hertz_contact"), description.item("hertz_contact", "on")?),
    ];
    fmu.initialised(name, &parameters, report)
}

/// The steps before the state is saved, then the ones after it.
const STEPS_BEFORE_STATE: usize = 5;
const STEPS_AFTER_STATE: usize = 5;

fn state_creepages(index: usize) -> [f64; 3] {
    let ramp = index as f64 + 1.0;
    [1e-3 * ramp, -4e-4 * ramp, 0.05 * ramp]
}

/// The steps after the state was saved: printed as `continued`, whatever instance runs them.
fn continue_from_state(fmu: &Fmu, instance: &Instance, report: &mut Report) -> Vec<String> {
    let mut lines = Vec::new();
    for index in STEPS_BEFORE_STATE..STEPS_BEFORE_STATE + STEPS_AFTER_STATE {
        let mut part = Report::default();
        fmu.step_at(
            instance,
            index as f64 * STEP,
            state_creepages(index),
            &format!("continued step={index}"),
            &mut part,
        );
        report.lines.push_str(&part.lines);
        report.failures.extend(part.failures);
        lines.push(part.lines);
    }
    lines
}

/// FMU state: saved after a few steps, serialized; the instance continues; the state is
/// deserialized and set, and the same steps must give the same outputs bit for bit.
fn state_round_trip(fmu: &Fmu, save_to: Option<&Path>, report: &mut Report) -> Result<(), String> {
    let instance = stateful(fmu, "state", report)?;
    for index in 0..STEPS_BEFORE_STATE {
        fmu.step_at(&instance, index as f64 * STEP, state_creepages(index), &format!("state step={index}"), report);
    }
    let bytes = instance.serialized_state()?;
    report.line(format!("state serialized bytes={}", bytes.len()));
    if let Some(path) = save_to {
        std::fs::write(path, &bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let first = continue_from_state(fmu, &instance, report);
    instance.restore_state(&bytes)?;
    let mut again = Report::default();
    let second = continue_from_state(fmu, &instance, &mut again);
    report.failures.extend(again.failures);
    report.expect("state: the restored instance repeats the continued steps bit for bit", first == second);
    Ok(())
}

fn run(directory: &Path, save_state: Option<&Path>) -> Result<Report, String> {
    let fmu = Fmu::open(directory)?;
    let mut report = Report::default();
    let (version, types_platform) = fmu.functions.version_and_types_platform();
    report.line(format!("fmi2GetVersion {version}"));
    report.line(format!("fmi2GetTypesPlatform {types_platform}"));
    default_scene(&fmu, &mut report)?;
    every_model(&fmu, &mut report)?;
    bad_inputs(&fmu, &mut report)?;
    state_round_trip(&fmu, save_state, &mut report)?;
    Ok(report)
}

/// A fresh instance of the stateful scene takes over a serialized state (from any platform) and
/// runs the continued steps.
fn restore(directory: &Path, state: &Path) -> Result<Report, String> {
    let fmu = Fmu::open(directory)?;
    let bytes = std::fs::read(state).map_err(|e| format!("{}: {e}", state.display()))?;
    let mut report = Report::default();
    let instance = stateful(&fmu, "restore", &mut report)?;
    instance.restore_state(&bytes)?;
    let mut continued = Report::default();
    continue_from_state(&fmu, &instance, &mut continued);
    report.failures.extend(continued.failures);
    report.lines.push_str(&continued.lines);
    Ok(report)
}

fn main() -> ExitCode {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    let arguments: Vec<&str> = arguments.iter().map(String::as_str).collect();
    let result = match arguments.as_slice() {
        ["run", directory] => run(Path::new(directory), None),
        ["run", directory, "--save-state", file] => run(Path::new(directory), Some(Path::new(file))),
        ["restore", directory, file] => restore(Path::new(directory), Path::new(file)),
        ["compare", a, b] => compare::files(Path::new(a), Path::new(b)).map(|summary| {
            let mut report = Report::default();
            report.line(summary);
            report
        }),
        _ => Err("usage: fmu-master run DIR [--save-state FILE] | restore DIR FILE | compare A B".to_owned()),
    };
    match result {
        Ok(report) => {
            print!("{}", report.lines);
            if report.failures.is_empty() {
                ExitCode::SUCCESS
            } else {
                let mut text = String::new();
                for failure in &report.failures {
                    let _ = writeln!(text, "broken: {failure}");
                }
                eprint!("{text}");
                ExitCode::FAILURE
            }
        }
        Err(message) => {
            eprintln!("fmu-master: {message}");
            ExitCode::FAILURE
        }
    }
}
