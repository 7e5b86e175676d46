//! The figure of `contact_geometry = profiles` in the FMU's documentation: the FMU's default
//! profiles (the built-in S1002 wheel on the UIC60 rail 1:40) on its default track (the
//! Manchester benchmark's), right wheel, at a lateral displacement of the wheelset, the wheel at
//! the height that carries 10 kN, each loaded patch drawn as its width 2b along the contact
//! plane (a box, to be seen). Computed with the core, as the FMU computes it with
//! `contact_method = hertz` (the non-Hertzian patches' figures: `non_hertzian_figure.rs`).

use wheel_rail_contact::geometry::{builtin_profile, ProfilePoints, WheelOnRail, WheelSide, WheelsetPosition};
use wheel_rail_contact::scene::{Evaluation, Scene};
use wheel_rail_contact::wheel::{
    VerticalContact, WheelCache, WheelInput, WheelOutput, WheelRailContact, WheelState, WheelsetVelocity,
};
use wheel_rail_contact::{ModelChoice, Polach};

use crate::plot::{line_plot, Series};

/// The wheelset's lateral displacements drawn \[m\]: on the tread, and on the flange.
pub const DISPLACEMENTS: [f64; 2] = [2e-3, 7e-3];
/// The wheel load \[N\].
pub const LOAD: f64 = 10e3;
/// How far the figure reaches beyond the rail's gauge side, to show the wheel's flange [m].
const FLANGE_MARGIN: f64 = 0.02;
/// Half the thickness of a patch's mark across the surfaces [m]: a patch is drawn as a box
/// 2b wide along them.
const PATCH_MARK: f64 = 0.5e-3;

fn points(name: &str) -> ProfilePoints {
    builtin_profile(name).expect("a built-in profile")
}

/// The wheel's forces at `lateral` (roll and yaw 0, rolling freely at 2 m/s, μ = 0.3).
pub fn wheel_at(lateral: f64) -> WheelOutput {
    let geometry = WheelOnRail::manchester_benchmark(WheelSide::Right);
    let wheel = WheelRailContact::new(geometry, Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28));
    let input = WheelInput {
        position: WheelsetPosition { lateral, vertical: 0.0, roll: 0.0, yaw: 0.0 },
        velocity: WheelsetVelocity { rolling_speed: 2.0, wheel_angular_speed: 2.0 / 0.46, ..Default::default() },
        vertical: VerticalContact::PrescribedForce(LOAD),
        friction_coefficient: 0.3,
    };
    let (output, _) = wheel
        .evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise)
        .expect("the benchmark's wheel is in contact");
    output
}

/// The rail, the wheel and the patches of [`wheel_at`] as curves in track coordinates, y \[mm\]
/// against the height above the rail's top, −z \[mm\]; each patch a closed box 2b wide along the
/// contact plane around its point.
pub fn curves(lateral: f64) -> Vec<Series> {
    let output = wheel_at(lateral);
    // The profiles' placement, read off the first patch (without roll and yaw a wheel profile
    // point at y lies at track y_ws + offset + y, z_ws + z; a rail point at offset + y, z).
    let point = &output.patches.first().expect("a loaded patch").patch.point;
    let rail_offset = point.track_lateral - point.rail_lateral;
    let wheel_offset = point.track_lateral - lateral - point.wheel_lateral;
    let millimetres = |y: f64, z: f64| (y * 1e3, -z * 1e3);
    let rail = points("MBench_UIC60");
    // The rail head, and the wheel's flange beside its gauge face.
    let window = (rail_offset + rail.lateral[0] - FLANGE_MARGIN, rail_offset + rail.lateral[rail.lateral.len() - 1]);
    let wheel = points("MBench_S1002");
    let placed = |profile: &ProfilePoints, offset: f64, height: f64| -> Vec<(f64, f64)> {
        profile
            .lateral
            .iter()
            .zip(&profile.vertical)
            .map(|(y, z)| (offset + y, height + z))
            .filter(|(y, _)| (window.0..=window.1).contains(y))
            .map(|(y, z)| millimetres(y, z))
            .collect()
    };
    let z_ws = output.wheelset_vertical_position;
    let mut series = vec![
        Series { label: "UIC60 rail (MBench_UIC60)".into(), points: placed(&rail, rail_offset, 0.0) },
        Series {
            label: format!("S1002 wheel (MBench_S1002), y_ws = {} mm, z_ws = {:.3} mm", lateral * 1e3, z_ws * 1e3),
            points: placed(&wheel, lateral + wheel_offset, z_ws),
        },
    ];
    for (k, patch) in output.patches.iter().enumerate() {
        let point = &patch.patch.point;
        let (sin, cos) = point.contact_angle.sin_cos();
        let half = patch.patch.ellipse.semi_axis_b;
        // Along the surfaces t = (cos δ, sin δ), across them n = (−sin δ, cos δ), in (y, z).
        let corner = |along: f64, across: f64| {
            millimetres(
                point.track_lateral + along * half * cos - across * PATCH_MARK * sin,
                point.track_vertical + along * half * sin + across * PATCH_MARK * cos,
            )
        };
        series.push(Series {
            label: format!(
                "patch {}: δ = {:.3} rad, N = {:.1} kN, 2b = {:.1} mm",
                k + 1,
                point.contact_angle,
                patch.patch.normal_force / 1e3,
                2e3 * half
            ),
            points: vec![
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
                corner(-1.0, -1.0),
            ],
        });
    }
    series
}

/// The figure at `lateral` as an SVG document.
pub fn figure(lateral: f64) -> String {
    line_plot(
        &format!(
            "S1002 on UIC60 1:40, right wheel, y_ws = {} mm, 10 kN: the loaded Hertz patches (contact_method = hertz)",
            lateral * 1e3
        ),
        "track y [mm] (to the right)",
        "height above the rail top [mm]",
        &curves(lateral),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At 2 mm the wheel runs on its tread, at 7 mm on its flange (CONTACT's puts its
    /// patches there too: contact angles ≈ −0.08 and ≈ −1.06 rad); the patches lie on the drawn
    /// rail, and the drawn wheel touches it there.
    #[test]
    fn tread_at_2_mm_flange_at_7_mm_patches_on_both_profiles() {
        for (lateral, on_flange) in [(2e-3, false), (7e-3, true)] {
            let series = curves(lateral);
            let output = wheel_at(lateral);
            assert_eq!(series.len(), 2 + output.patches.len());
            let patch = &output.patches[0].patch.point;
            assert_eq!(patch.contact_angle.abs() > 0.7, on_flange, "{lateral}: {}", patch.contact_angle);
            let centre = (patch.track_lateral * 1e3, -patch.track_vertical * 1e3);
            // The nearest drawn point of each profile (points ≈ 0.35 mm apart; the wheel's
            // penetration under 10 kN is tens of microns).
            for profile in &series[..2] {
                let nearest =
                    profile.points.iter().map(|p| (p.0 - centre.0).hypot(p.1 - centre.1)).fold(f64::MAX, f64::min);
                assert!(nearest < 0.5, "{lateral}: {} is {nearest} mm from the patch", profile.label);
            }
            let svg = figure(lateral);
            assert_eq!(svg.matches("<polyline").count(), series.len());
        }
    }
}
