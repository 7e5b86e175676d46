//! One co-simulation step through the C ABI — 7 fmi2SetReal + fmi2DoStep + 3 fmi2GetReal on one
//! instance, calling the exported `extern "C"` functions in-process — against the bare core
//! evaluation of the same scene, in the same run. Target: the step costs ≤ 2× the evaluation.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use wheel_rail_contact::{CreepForceModel, Polach};
use wheel_rail_contact_fmu::ffi::*;
use wheel_rail_contact_fmu::fmi2::{fmi2CallbackFunctions, fmi2Status_fmi2OK, fmi2Type_fmi2CoSimulation};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, GUID};

use wheel_rail_contact::reference_cases::BENCHMARK_WITH_SPIN as SCENE;

fn fmu_step_against_core(c: &mut Criterion) {
    let mut group = c.benchmark_group("fmu_step");
    group.bench_function("bare_core_evaluation", |b| b.iter(|| Polach::default().creep_forces(black_box(&SCENE))));

    let callbacks = fmi2CallbackFunctions {
        logger: None,
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: std::ptr::null_mut(),
    };
    let guid = std::ffi::CString::new(GUID).unwrap();
    let inputs = [
        (vr::CREEPAGE_LONGITUDINAL, SCENE.creepage_longitudinal),
        (vr::CREEPAGE_LATERAL, SCENE.creepage_lateral),
        (vr::SPIN_CREEPAGE, SCENE.spin_creepage),
        (vr::NORMAL_FORCE, SCENE.normal_force),
        (vr::SEMI_AXIS_A, SCENE.semi_axis_a),
        (vr::SEMI_AXIS_B, SCENE.semi_axis_b),
        (vr::FRICTION_COEFFICIENT, SCENE.friction_coefficient),
    ];
    let outputs = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION];
    // SAFETY: the benchmark follows the FMI 2.0 calling sequence with valid pointers throughout.
    unsafe {
        let c = fmi2Instantiate(
            c"bench".as_ptr(),
            fmi2Type_fmi2CoSimulation,
            guid.as_ptr(),
            std::ptr::null(),
            &callbacks,
            0,
            0,
        );
        assert!(!c.is_null());
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), fmi2Status_fmi2OK);
        assert_eq!(fmi2EnterInitializationMode(c), fmi2Status_fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(c), fmi2Status_fmi2OK);
        let step = 1e-3;
        let mut time = 0.0;
        group.bench_function("c_abi_step_7_set_do_step_3_get", |b| {
            b.iter(|| {
                for (reference, value) in &inputs {
                    fmi2SetReal(c, reference, 1, black_box(value));
                }
                let status = fmi2DoStep(c, time, step, 1);
                time += step;
                let mut forces = [0.0; 3];
                for (reference, force) in outputs.iter().zip(forces.iter_mut()) {
                    fmi2GetReal(c, reference, 1, force);
                }
                black_box((status, forces))
            })
        });
        fmi2FreeInstance(c);
    }
    group.finish();
}

criterion_group!(benches, fmu_step_against_core);
criterion_main!(benches);
