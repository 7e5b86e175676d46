//! The cost of each scene option per co-simulation step, in one run: one instance per option
//! (set through the FMU's own parameters), each doing set 7 inputs + DoStep + get 3 outputs
//! through the safe instance API, against the same with every option off. Options off must cost
//! nothing; the figures on are what a scene pays for switching one on.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use wheel_rail_contact_fmu::instance::{Instance, InstantiateArguments};
use wheel_rail_contact_fmu::logging::{LogSink, Status};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, Model, Switch, TractionLaw, GUID};

struct NoLog;

impl LogSink for NoLog {
    fn log(&mut self, _: Status, _: &str, _: &str) {}
}

fn instance(integers: &[(u32, i32)]) -> Instance {
    let arguments = InstantiateArguments {
        instance_name: "bench",
        co_simulation: true,
        guid: GUID,
        resource_location: None,
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

fn options(c: &mut Criterion) {
    let on = Switch::On as i32;
    let scenes: [(&str, Vec<(u32, i32)>); 7] = [
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
    ];
    let inputs = [vr::CREEPAGE_LONGITUDINAL, vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE, vr::NORMAL_FORCE];
    let values = [1.5e-3, -0.8e-3, 0.4, 80e3];
    let kinematics = [vr::ROLLING_SPEED, vr::WHEEL_ANGULAR_SPEED, vr::LATERAL_SLIP_VELOCITY];
    let kinematic_values = [20.0, 19.97 / 0.46, -0.016];
    let outputs = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION];
    let mut group = c.benchmark_group("fmu_options");
    for (name, integers) in scenes {
        let mut instance = instance(&integers);
        let step = 1e-3;
        let mut time = 0.0;
        group.bench_function(name, |b| {
            b.iter(|| {
                instance.set_real(&inputs, black_box(&values));
                instance.set_real(&kinematics, black_box(&kinematic_values));
                let status = instance.do_step(time, step);
                time += step;
                let mut forces = [0.0; 3];
                instance.get_real(&outputs, &mut forces);
                black_box((status, forces))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, options);
criterion_main!(benches);
