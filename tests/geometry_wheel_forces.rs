//! Forces on a wheel from its profiles: the Manchester contact benchmark, case A-2.2 (S1002 on
//! UIC60 1:40, 10 kN per wheel, V = 2 m/s, μ = 0.3), both wheels, against CONTACT's published
//! full (non-Hertzian, exact-theory) solution (`tests/data/mbench_a22_contact_ref_out.csv`, from
//! CONTACT rev. 2707's `examples/mbench_a22_{right,left}.ref_out` by the script beside it):
//! creepages, normal and creep forces per patch, totals on the wheel; invariants.

use wheel_rail_contact::geometry::{
    builtin_profile, SmoothProfile, TrackDimensions, VerticalContact, WheelCache, WheelInput, WheelOnRail,
    WheelRailContact, WheelSide, WheelState, WheelsetPosition, WheelsetVelocity,
};
use wheel_rail_contact::scene::{Evaluation, Scene};
use wheel_rail_contact::{ModelChoice, Polach};

/// CONTACT's values of one wheel and case (its units and signs: mm, rail minus wheel, on the rail).
#[derive(Debug, Clone, Copy)]
struct Reference {
    case: u32,
    y_ws: f64,
    z_ws: f64,
    roll: f64,
    yaw: f64,
    total: [f64; 3],
    xcp: f64,
    ycp_rail: f64,
    angle: f64,
    veloc: f64,
    creepages: [f64; 3],
    normal: f64,
    tangential: [f64; 2],
}

fn references(side: &str) -> Vec<Reference> {
    include_str!("data/mbench_a22_contact_ref_out.csv")
        .lines()
        .filter(|l| l.starts_with(&format!("{side},")))
        .map(|l| {
            let f: Vec<f64> = l.split(',').skip(1).map(|v| v.parse().unwrap()).collect();
            Reference {
                case: f[0] as u32,
                y_ws: f[1],
                z_ws: f[2],
                roll: f[3],
                yaw: f[4],
                total: [f[5], f[6], f[7]],
                xcp: f[8],
                ycp_rail: f[12],
                angle: f[11],
                veloc: f[17],
                creepages: [f[18], f[19], f[20]],
                normal: f[21],
                tangential: [f[22], f[23]],
            }
        })
        .collect()
}

/// Ω of each case: CONTACT's VPITCH, negated (`tests/data/manchester_a22_inputs.csv`).
fn angular_speed(side: &str, case: u32) -> f64 {
    include_str!("data/manchester_a22_inputs.csv")
        .lines()
        .find(|l| l.starts_with(&format!("{side},{case},")))
        .map(|l| -l.rsplit(',').next().unwrap().parse::<f64>().unwrap())
        .unwrap()
}

fn wheel(side: WheelSide, model: ModelChoice) -> WheelRailContact {
    let profile = |name| SmoothProfile::new(&builtin_profile(name).unwrap()).unwrap();
    let geometry = WheelOnRail::new(
        profile("MBench_S1002"),
        profile("MBench_UIC60"),
        TrackDimensions::MANCHESTER_BENCHMARK,
        side,
        82e9,
        0.28,
    )
    .unwrap();
    WheelRailContact::new(geometry, Scene::of_model(model, 82e9, 0.28))
}

fn a22_input(side: &str, reference: &Reference) -> WheelInput {
    WheelInput {
        position: WheelsetPosition {
            lateral: reference.y_ws * 1e-3,
            vertical: 0.0,
            roll: reference.roll,
            yaw: reference.yaw,
        },
        velocity: WheelsetVelocity {
            rolling_speed: 2.0,
            wheel_angular_speed: angular_speed(side, reference.case),
            ..WheelsetVelocity::default()
        },
        vertical: VerticalContact::PrescribedForce(10e3),
        friction_coefficient: 0.3,
    }
}

/// The largest |ΔF|/(μ N_CONTACT) of the creep forces (x, s) against CONTACT's, over both
/// wheels' cases but `excluded`, with the worst case.
fn worst_creep_force_difference(model: ModelChoice, excluded: &[(&str, u32)]) -> (f64, String) {
    let mut worst = (0.0, String::new());
    for (side, wheel_side) in [("right", WheelSide::Right), ("left", WheelSide::Left)] {
        let contact = wheel(wheel_side, model);
        for reference in references(side) {
            if excluded.contains(&(side, reference.case)) {
                continue;
            }
            let (output, _) = contact
                .evaluate(
                    &a22_input(side, &reference),
                    &WheelState::default(),
                    &mut WheelCache::default(),
                    Evaluation::Initialise,
                )
                .unwrap();
            let p = &output.patches[0];
            for (what, ours, theirs) in [
                ("F_x", p.output.force_longitudinal, -reference.tangential[0]),
                ("F_s", p.output.force_lateral, -reference.tangential[1]),
            ] {
                let difference = (ours - theirs).abs() / (0.3 * reference.normal);
                if difference > worst.0 {
                    worst = (difference, format!("{side} {} {what} {ours:.0} vs {theirs:.0}", reference.case));
                }
            }
        }
    }
    worst
}

#[test]
fn models_against_contact_printed() {
    use wheel_rail_contact::models::fastsim::{Flexibility, TractionBound};
    use wheel_rail_contact::{ExactTable, ExactTheory, Fastsim};
    let excluded = [("right", 1), ("left", 1), ("right", 11)];
    for model in [
        ModelChoice::Polach(Polach::default()),
        ModelChoice::ExactTable(ExactTable::new().unwrap()),
        ModelChoice::Fastsim(Fastsim::new(50, 50, TractionBound::Elliptic, Flexibility::ThreeBlended).unwrap()),
        ModelChoice::Exact(ExactTheory::default()),
    ] {
        println!("{}: {:?}", model.name(), worst_creep_force_difference(model, &excluded));
    }
}

#[test]
fn a22_against_contact_printed() {
    for (side, wheel_side) in [("right", WheelSide::Right), ("left", WheelSide::Left)] {
        let contact = wheel(wheel_side, ModelChoice::Polach(Polach::default()));
        for reference in references(side) {
            let input = a22_input(side, &reference);
            let (output, _) = contact
                .evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise)
                .unwrap();
            for p in &output.patches {
                let o = &p.output;
                println!(
                    "{side} {:2} z {:.4}/{:.4} x {:.3}/{:.3} slip ξ {:.3}/{:.3} η {:.3}/{:.3} mm/s φ {:.5}/{:.5} rad/s N {:.0}/{:.0} Fx {:.0}/{:.0} Fs {:.0}/{:.0}",
                    reference.case,
                    output.wheelset_vertical_position * 1e3,
                    reference.z_ws,
                    p.patch.point.track_longitudinal * 1e3,
                    reference.xcp,
                    o.effective_creepage_longitudinal * 2000.0,
                    -reference.creepages[0] * reference.veloc,
                    o.effective_creepage_lateral * 2000.0,
                    -reference.creepages[1] * reference.veloc,
                    o.effective_spin_creepage * 2.0,
                    -reference.creepages[2] * reference.veloc,
                    p.patch.normal_force,
                    reference.normal,
                    o.force_longitudinal,
                    -reference.tangential[0],
                    o.force_lateral,
                    -reference.tangential[1],
                );
            }
            println!(
                "   totals {:.0} {:.0} {:.0} / {:.0} {:.0} {:.0}",
                output.track_force[0],
                output.track_force[1],
                output.track_force[2],
                -reference.total[0],
                -reference.total[1],
                -reference.total[2]
            );
        }
    }
}
