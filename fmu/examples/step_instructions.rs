//! The instruction budget's workloads (counted under callgrind by `scripts/instruction-budget`):
//! STEPS co-simulation steps of one workload through the C ABI, as a master calls it.
//!
//! - `patch_polach`, `patch_exact_table`: one patch, model `polach` or `exact_table`: 7
//!   fmi2SetReal values (creepages, spin, load, ellipse, friction) + fmi2DoStep + 3 fmi2GetReal
//!   values, as `../shared/bench/step-vs-c` times it;
//! - `wheel_polach`, `wheel_exact_table`: a wheel on its rail from the built-in profiles
//!   (S1002 on UIC60 1:40), model `polach` or `exact_table`: the wheelset's lateral displacement
//!   and yaw angle set + fmi2DoStep + the force on the track (3 values) read; the displacement
//!   runs over 2.0–2.1 mm on the tread, a new contact search every step;
//! - `wheel_non_hertzian_polach`: the same with `contact_method = non_hertzian` (the patches from
//!   the profiles' interpenetration, its strip table built at initialisation);
//! - `wheel_non_hertzian_centred_polach`: the same at the centred wheelset (0–0.1 mm, no yaw),
//!   whose gap is flat within microns over 10 mm: the widest patch, the costliest step.
//!
//! The script runs each workload with two step counts and divides the difference of the counts
//! by the difference of the steps: the instructions of one step, without the set-up.
//!
//! usage: step_instructions WORKLOAD STEPS

use fmu_test_master::{Fmu, INPUTS, OK, OUTPUTS};
use wheel_rail_contact_fmu::ffi::*;
use wheel_rail_contact_fmu::model_description::value_reference as vr;
use wheel_rail_contact_fmu::model_description::{ContactGeometry, ContactMethod, Model};

/// The step size \[s\].
const STEP: f64 = 1e-4;

/// The wheel workloads' lateral displacement \[m\] (from; over 0.1 mm) and yaw angle \[rad\]: on the tread.
const TREAD: (f64, f64) = (2e-3, 4.8e-3);

/// Steps one patch with `model`: the same inputs as `step-vs-c`, the longitudinal creepage moving
/// a little.
fn patch(model: Model, steps: usize) -> f64 {
    let fmu = Fmu::instantiate("instruction budget, one patch", None);
    assert_eq!(fmu.set_integer(&[vr::CREEP_FORCE_MODEL], &[model as i32]), OK);
    fmu.initialise(0.0);
    let mut outputs = [0.0; 3];
    let mut sink = 0.0;
    for k in 0..steps {
        let inputs = [1e-4 + 1e-10 * k as f64, 2e-4, 0.01, 8e4, 6e-3, 6e-3, 0.3];
        // SAFETY: a live instance; 7 references with 7 values, 3 with room for 3.
        unsafe {
            assert_eq!(fmi2SetReal(fmu.c, INPUTS.as_ptr(), 7, inputs.as_ptr()), OK);
            assert_eq!(fmi2DoStep(fmu.c, k as f64 * STEP, STEP, 1), OK);
            assert_eq!(fmi2GetReal(fmu.c, OUTPUTS.as_ptr(), 3, outputs.as_mut_ptr()), OK);
        }
        sink += outputs[0];
    }
    sink
}

/// Steps a wheel on the built-in profiles with `model` and the patches of `method`, its lateral
/// displacement over `lateral` … `lateral` + 0.1 mm at the yaw angle `yaw`.
fn wheel(model: Model, method: ContactMethod, (lateral, yaw): (f64, f64), steps: usize) -> f64 {
    let fmu = Fmu::instantiate("instruction budget, wheel", None);
    assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
    assert_eq!(fmu.set_integer(&[vr::CREEP_FORCE_MODEL, vr::CONTACT_METHOD], &[model as i32, method as i32]), OK);
    assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE, vr::RAIL_PROFILE], &["MBench_S1002", "MBench_UIC60"]), OK);
    fmu.initialise(0.0);
    let (pose, forces) = (
        [vr::WHEELSET_LATERAL_DISPLACEMENT, vr::WHEELSET_YAW_ANGLE],
        [vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y, vr::TRACK_FORCE_Z],
    );
    let mut outputs = [0.0; 3];
    let mut sink = 0.0;
    for k in 0..steps {
        let inputs = [lateral + 1e-6 * (k % 100) as f64, yaw];
        // SAFETY: a live instance; 2 references with 2 values, 3 with room for 3.
        unsafe {
            assert_eq!(fmi2SetReal(fmu.c, pose.as_ptr(), 2, inputs.as_ptr()), OK);
            assert_eq!(fmi2DoStep(fmu.c, k as f64 * STEP, STEP, 1), OK);
            assert_eq!(fmi2GetReal(fmu.c, forces.as_ptr(), 3, outputs.as_mut_ptr()), OK);
        }
        sink += outputs[1];
    }
    sink
}

fn main() {
    let mut arguments = std::env::args().skip(1);
    let (Some(workload), Some(steps)) = (arguments.next(), arguments.next().and_then(|n| n.parse().ok())) else {
        eprintln!(
            "usage: step_instructions patch_polach|patch_exact_table|wheel_polach|wheel_exact_table|\
             wheel_non_hertzian_polach|wheel_non_hertzian_centred_polach STEPS"
        );
        std::process::exit(2);
    };
    let sink = match workload.as_str() {
        "patch_polach" => patch(Model::Polach, steps),
        "patch_exact_table" => patch(Model::ExactTable, steps),
        "wheel_polach" => wheel(Model::Polach, ContactMethod::Hertz, TREAD, steps),
        "wheel_exact_table" => wheel(Model::ExactTable, ContactMethod::Hertz, TREAD, steps),
        "wheel_non_hertzian_polach" => wheel(Model::Polach, ContactMethod::NonHertzian, TREAD, steps),
        "wheel_non_hertzian_centred_polach" => wheel(Model::Polach, ContactMethod::NonHertzian, (0.0, 0.0), steps),
        other => {
            eprintln!("step_instructions: unknown workload {other}");
            std::process::exit(2);
        }
    };
    println!("{workload}: {steps} steps (sum of a force {sink:e} N)");
}
