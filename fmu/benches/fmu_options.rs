//! The cost of each scene option per co-simulation step, in one run: one instance per option
//! (set through the FMU's own parameters), each doing set 7 inputs + DoStep + get 3 outputs
//! through the safe instance API, against the same with every option off. Options off must cost
//! nothing; the figures on are what a scene pays for switching one on. And a wheel on its
//! profiles (`fmu_profiles`) at four lateral positions, to compare with `all_off` in one run.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use wheel_rail_contact_fmu::logging::{LogSink, Status};
use wheel_rail_contact_fmu::model::{Instance, InstantiateArguments, Slave};
use wheel_rail_contact_fmu::model_description::{
    value_reference as vr, ContactGeometry, ContactMethod, Model, Switch, TractionLaw, GUID,
};

struct NoLog;

impl LogSink for NoLog {
    fn log(&mut self, _: Status, _: &str, _: &str) {}
}

fn instance(integers: &[(u32, i32)]) -> Instance {
    // The repository's data/ as the resources: `exact_table` reads its table there, as from
    // the packaged FMU's resources/ (without it that scene's initialisation failed, and with it
    // the whole benchmark).
    let resources = fmu_test_master::repository_resources();
    let arguments = InstantiateArguments {
        instance_name: "bench",
        interface: Ok(wheel_rail_contact_fmu::mode::Interface::CoSimulation),
        guid: GUID,
        resource_location: Some(&resources),
        logging_on: false,
    };
    let mut instance = Instance::instantiate(arguments, Box::new(NoLog)).expect("instantiate");
    assert_eq!(instance.setup_experiment(0.0, None), Status::Ok);
    let (references, values): (Vec<u32>, Vec<i32>) = integers.iter().copied().unzip();
    assert_eq!(instance.set_integer(&references, &values), Status::Ok);
    assert_eq!(instance.enter_initialization_mode(), Status::Ok);
    assert_eq!(instance.exit_initialization_mode(), Status::Ok);
    instance
}

/// One co-simulation step as a master does it: set the inputs, step from `time`, read the
/// outputs.
fn co_simulation_step(instance: &mut Instance, inputs: &[(&[u32], &[f64])], time: &mut f64, outputs: &[u32; 3]) {
    const STEP: f64 = 1e-3;
    for (references, values) in inputs {
        instance.set_real(references, black_box(values));
    }
    let status = instance.do_step(*time, STEP);
    *time += STEP;
    let mut read = [0.0; 3];
    instance.get_real(outputs, &mut read);
    black_box((status, read));
}

fn options(c: &mut Criterion) {
    let on = Switch::On as i32;
    let scenes: [(&str, Vec<(u32, i32)>); 8] = [
        ("all_off", vec![]),
        ("polach2005_dry", vec![(vr::TRACTION_LAW, TractionLaw::Polach2005Dry as i32)]),
        ("hertz_contact", vec![(vr::HERTZ_CONTACT, on)]),
        ("creepages_from_kinematics", vec![(vr::CREEPAGES_FROM_KINEMATICS, on)]),
        ("creep_relaxation", vec![(vr::CREEP_RELAXATION, on)]),
        (
            "all_on",
            vec![
                (vr::TRACTION_LAW, TractionLaw::Polach2005Dry as i32),
                (vr::HERTZ_CONTACT, on),
                (vr::CREEPAGES_FROM_KINEMATICS, on),
                (vr::CREEP_RELAXATION, on),
            ],
        ),
        ("fastsim_20x20", vec![(vr::CREEP_FORCE_MODEL, Model::Fastsim as i32)]),
        // issue 11's target: ≤ 1.5 × the Polach step (`all_off`).
        ("exact_table", vec![(vr::CREEP_FORCE_MODEL, Model::ExactTable as i32)]),
    ];
    let inputs = [vr::CREEPAGE_LONGITUDINAL, vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE, vr::NORMAL_FORCE];
    let values = [1.5e-3, -0.8e-3, 0.4, 80e3];
    let kinematics = [vr::ROLLING_SPEED, vr::WHEEL_ANGULAR_SPEED, vr::LATERAL_SLIP_VELOCITY];
    let kinematic_values = [20.0, 19.97 / 0.46, -0.016];
    let outputs = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION];
    let mut group = c.benchmark_group("fmu_options");
    for (name, integers) in scenes {
        let mut instance = instance(&integers);
        let mut time = 0.0;
        let set: [(&[u32], &[f64]); 2] = [(&inputs, &values), (&kinematics, &kinematic_values)];
        group.bench_function(name, |b| b.iter(|| co_simulation_step(&mut instance, &set, &mut time, &outputs)));
    }
    group.finish();
}

/// One wheel from its profiles (`contact_geometry = profiles`: the built-in S1002 on UIC60,
/// 10 kN, braking 0.15 % at 20 m/s, Polach): the contact search, the vertical balance and the
/// patches' creep forces per step, on the tread (2 mm), at the flat gap of the centred wheelset
/// (0 mm), where tread and flange share the load (5 mm) and on the flange (7 mm).
/// `fmu_profiles`: Hertz's patches (`contact_method = hertz`); `fmu_profiles_non_hertzian`: the
/// start value's.
fn profiles(c: &mut Criterion) {
    for (group_name, method) in
        [("fmu_profiles", ContactMethod::Hertz), ("fmu_profiles_non_hertzian", ContactMethod::NonHertzian)]
    {
        let mut group = c.benchmark_group(group_name);
        let inputs = [vr::WHEELSET_LATERAL_DISPLACEMENT, vr::ROLLING_SPEED, vr::WHEEL_ANGULAR_SPEED];
        let outputs = [vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y, vr::CONTACT_PATCH_COUNT];
        for (name, lateral) in
            [("tread_2mm", 2e-3), ("centred_0mm", 0.0), ("two_patches_5mm", 5e-3), ("flange_7mm", 7e-3)]
        {
            let mut instance = instance(&[
                (vr::CONTACT_GEOMETRY, ContactGeometry::Profiles as i32),
                (vr::CONTACT_METHOD, method as i32),
            ]);
            let mut time = 0.0;
            let values = [lateral, 20.0, 19.97 / 0.46];
            group.bench_function(name, |b| {
                b.iter(|| co_simulation_step(&mut instance, &[(&inputs, &values)], &mut time, &outputs))
            });
        }
        group.finish();
    }
}

/// The exact theory on 40 × 40 in a co-simulation with slowly varying creepage (issue 10's
/// target: ≤ 5 ms per step): each step moves ξ by 1e-6 and φ by 1e-4 /m, so the warm start from
/// the previous step's tractions is close; spin keeps adhesion and slip both present.
fn exact_co_simulation(c: &mut Criterion) {
    let grid = [(vr::EXACT_ELEMENTS_LONGITUDINAL, 40), (vr::EXACT_ELEMENTS_LATERAL, 40)];
    let mut instance = instance(&[(vr::CREEP_FORCE_MODEL, Model::Exact as i32), grid[0], grid[1]]);
    let inputs = [vr::CREEPAGE_LONGITUDINAL, vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE, vr::NORMAL_FORCE];
    let outputs = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::SPIN_MOMENT];
    let (mut time, mut k) = (0.0, 0_u64);
    let mut group = c.benchmark_group("fmu_exact");
    group.sample_size(20);
    group.bench_function("exact_40x40_slowly_varying_step", |b| {
        b.iter(|| {
            k += 1;
            let drift = (k % 1000) as f64;
            let values = [1.0e-3 + 1e-6 * drift, -0.4e-3, 0.4 + 1e-4 * drift, 80e3];
            co_simulation_step(&mut instance, &[(&inputs, &values)], &mut time, &outputs);
        })
    });
    group.finish();
}

criterion_group!(benches, options, profiles, exact_co_simulation);
criterion_main!(benches);
