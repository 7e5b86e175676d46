//! FASTSIM against the published CONTACT example `examples/fastsim`
//! (core/tests/data/contact_published_cases.md, case 2): a = 8 mm, b = 4 mm, N = 82 kN, G = 82 GPa,
//! ν = 0.28, μ = 0.3, ξ = 0, η = −6.25e-4, φ = 6.25e-4 /mm, CONTACT's material model M = 3.
//!
//! CONTACT's M = 3 is three flexibilities *blended* by its `simpflex` (src/m_hertz.f90) towards
//! one combined flexibility as the creepage grows: our `Flexibility::ThreeBlended`. For this case
//! the blend weight is 0.110 and moves the converged F_y/(μN) from −0.6475 (parabolic) and
//! −0.5961 (elliptic) without the blend to −0.6397 and −0.5933.
//!
//! How our grid differs from CONTACT's: CONTACT discretises a rectangle of 1.1 × the contact
//! (44 × 44 elements, 40 × 40 of them inside the ellipse; src/m_stang.f90 `modif_fastsim`), so
//! the contact edge cuts through elements and the rows do not follow the ellipse; each row
//! starts with a full step dq = dx at its first interior element (implicit Euler), evaluates the
//! spin slip φ(x + dq/6) (src/m_sdis.f90 `srztng`, default `facphi` = 1/6, where the exact step
//! average is x + dq/2) and does not rescale the sampled pressure. Ours (`Discretisation::Strips`)
//! divides the ellipse itself into strips of equal width, each strip's own length into equal
//! elements, starts each strip exactly at the leading edge with a half step, takes the slip at
//! mid-step and normalises the discrete pressure to carry N. Both converge to the same limit,
//! ours much faster. CONTACT's scheme is available as `Discretisation::ContactGrid` and
//! reproduces the published numbers on CONTACT's grids: −0.6098 / −39.04 N·m (parabolic) and
//! −0.6008 / −48.28 N·m (elliptic) at 44 × 44, −0.6338 / −38.01 and −0.5948 / −45.29 at 220 × 220
//! (published −0.6118 / −39.00, −0.6016 / −48.29, −0.6359 / −37.98, −0.5956 / −45.30); refined
//! to 880 × 880 it reaches −0.6382 / −0.5935, approaching our converged −0.640 / −0.593. CONTACT's
//! own 220 × 220 results thus carry 0.6 % (parabolic) and 0.4 % (elliptic) discretisation error
//! in F_y, 1.6 % in the elliptic M_z; its 44 × 44 parabolic F_y carries 4.4 %.

use crate::common;

use common::fastsim;
use common::published::{FASTSIM_CASE, FASTSIM_CASE_CONTACT_FASTSIM};
use wheel_rail_contact::{CreepForceModel, Discretisation, Fastsim, Flexibility, TractionBound};

/// Asserts our F_y/(μN) within `fy_tolerance` of CONTACT's FASTSIM result with the same bound
/// and `elements_in_contact` (40 or 200), and M_z within `mz_tolerance` where given.
fn assert_matches_contact(model: &Fastsim, elements_in_contact: usize, fy_tolerance: f64, mz_tolerance: Option<f64>) {
    let published = FASTSIM_CASE_CONTACT_FASTSIM
        .iter()
        .find(|p| p.bound == model.bound() && p.elements_in_contact == elements_in_contact)
        .expect("published")
        .result;
    let forces = model.creep_forces(&FASTSIM_CASE).unwrap();
    assert_within(forces.force_lateral / FASTSIM_CASE.friction_limit(), published.force_lateral_ratio, fy_tolerance);
    if let Some(tolerance) = mz_tolerance {
        assert_within(forces.spin_moment.unwrap(), published.spin_moment, tolerance);
    }
}

fn assert_within(got: f64, published: f64, relative: f64) {
    assert!((got / published - 1.0).abs() < relative, "{got} vs published {published} (±{relative})");
}

#[test]
fn parabolic_bound_fine_grid_matches_contact_to_one_percent() {
    // Ours −0.6401 and −37.71 N·m (300 × 300) vs CONTACT's 200 × 200 in the contact.
    assert_matches_contact(&fastsim(300, TractionBound::Parabolic), 200, 0.01, Some(0.01));
}

#[test]
fn elliptic_bound_fine_grid_matches_contact_to_one_percent() {
    // Ours −0.5936 (300 × 300) vs −0.5956. Spin moment: ours −44.53 N·m vs −45.30 (1.7 %); the
    // CONTACT scheme itself moves from −45.29 to −44.93 N·m from 220 to 440 elements (see top), so
    // 2 % here is CONTACT's own discretisation error, not ours.
    assert_matches_contact(&fastsim(300, TractionBound::Elliptic), 200, 0.01, Some(0.02));
}

#[test]
fn elliptic_bound_40_by_40_matches_contact_to_two_percent() {
    // Ours −0.5951 vs −0.6016 (1.1 %).
    assert_matches_contact(&fastsim(40, TractionBound::Elliptic), 40, 0.02, None);
}

/// CONTACT's FASTSIM on its own grid of `grid` × `grid` elements over 1.1 × the contact.
fn contact_grid(grid: usize, bound: TractionBound) -> Fastsim {
    fastsim(grid, bound).with_discretisation(Discretisation::ContactGrid)
}

#[test]
fn contact_discretisation_reproduces_contacts_40_by_40_results() {
    // CONTACT's 44 × 44 grid, 40 × 40 elements in the contact. Measured −0.6098 / −39.04 N·m
    // (published −0.6118 / −39.00) and −0.6008 / −48.28 N·m (−0.6016 / −48.29). The remaining
    // 0.3 % in the parabolic F_y is not traced. The issue asks for 2 %.
    for bound in [TractionBound::Parabolic, TractionBound::Elliptic] {
        assert_matches_contact(&contact_grid(44, bound), 40, 0.005, Some(0.005));
    }
}

#[test]
fn contact_discretisation_reproduces_contacts_200_by_200_results() {
    // 220 × 220 over 1.1 × the contact. Measured −0.6338 / −38.01 N·m and −0.5948 / −45.29 N·m.
    for bound in [TractionBound::Parabolic, TractionBound::Elliptic] {
        assert_matches_contact(&contact_grid(220, bound), 200, 0.005, Some(0.005));
    }
}

#[test]
fn contact_discretisation_converges_to_ours() {
    // Both schemes discretise the same simplified theory: CONTACT's approaches our converged
    // value at first order (errors −0.0303, −0.0063, −0.0034 at 44, 220, 440; parabolic bound).
    let lateral = |model: &Fastsim| model.creep_forces(&FASTSIM_CASE).unwrap().force_lateral;
    let converged = lateral(&fastsim(300, TractionBound::Parabolic));
    let errors: Vec<f64> = [44, 220, 440]
        .iter()
        .map(|&n| (lateral(&contact_grid(n, TractionBound::Parabolic)) - converged).abs())
        .collect();
    assert!(errors[0] > 4.0 * errors[1] && errors[1] > 1.6 * errors[2], "errors {errors:?}");
    assert!(errors[2] < 0.01 * converged.abs(), "errors {errors:?}");
}

#[test]
fn unblended_three_flexibilities_elliptic_bound_matches_contact() {
    // Without the blend the elliptic bound still agrees (−0.5965 at 300, −0.5980 at 40 × 40):
    // the blend moves this case's F_y by only 0.5 % with the Hertz bound (1.2 % with the parabola).
    let three = |n| Fastsim::new(n, n, TractionBound::Elliptic, Flexibility::Three).unwrap();
    assert_matches_contact(&three(300), 200, 0.01, Some(0.02));
    assert_matches_contact(&three(40), 40, 0.02, None);
}

#[test]
fn fastsim_converges_at_first_order_in_partial_slip() {
    // Partial slip: the adhesion/slip boundary cuts elements, so the error is O(1/n).
    let lateral = |n| {
        fastsim(n, TractionBound::Parabolic).creep_forces(&FASTSIM_CASE).unwrap().force_lateral
            / FASTSIM_CASE.friction_limit()
    };
    let reference = lateral(640);
    let errors: Vec<f64> = [20, 40, 80, 160].iter().map(|&n| (lateral(n) - reference).abs()).collect();
    for pair in errors.windows(2) {
        assert!(pair[0] / pair[1] > 1.6, "errors {errors:?}");
    }
}

#[test]
fn contact_discretisation_full_slip_carries_the_sampled_load() {
    // CONTACT's scheme samples the pressure at element centres without rescaling, so in full
    // slip |F| = μ Σ p_n δA, which differs from μN by the sampling error (measured −1.6 % on
    // 9 × 14 with the elliptic bound, +0.04 % on 22 × 22 parabolic: the scheme can exceed μN,
    // which is why it is an option, not our default); the forces are odd in the creepages.
    for (rows, columns, bound) in [(9, 14, TractionBound::Elliptic), (22, 22, TractionBound::Parabolic)] {
        let model = Fastsim::new(rows, columns, bound, Flexibility::Three)
            .unwrap()
            .with_discretisation(Discretisation::ContactGrid);
        let (dx, dy) = (2.2 / columns as f64, 2.2 / rows as f64);
        let mut sampled = 0.0;
        for row in 0..rows {
            for column in 0..columns {
                let (x, y) = (-1.1 + (column as f64 + 0.5) * dx, -1.1 + (row as f64 + 0.5) * dy);
                let depth = 1.0 - x * x - y * y;
                if depth > 0.0 {
                    sampled += match bound {
                        TractionBound::Parabolic => 2.0 / std::f64::consts::PI * depth,
                        TractionBound::Elliptic => 1.5 / std::f64::consts::PI * depth.sqrt(),
                    } * dx
                        * dy;
                }
            }
        }
        let case = wheel_rail_contact::ContactInput {
            creepage_longitudinal: 0.3,
            creepage_lateral: -0.4,
            spin_creepage: 0.0,
            ..FASTSIM_CASE
        };
        let forces = model.creep_forces(&case).unwrap();
        assert!(
            (forces.adhesion_utilisation - sampled).abs() < 1e-12,
            "{} vs sampled {sampled}",
            forces.adhesion_utilisation
        );
        assert!((sampled - 1.0).abs() < 0.02 && (sampled - 1.0).abs() > 1e-4, "sampled load / N = {sampled}");
        let opposite = wheel_rail_contact::ContactInput {
            creepage_longitudinal: -0.3,
            creepage_lateral: 0.4,
            spin_creepage: 0.0,
            ..FASTSIM_CASE
        };
        let mirrored = model.creep_forces(&opposite).unwrap();
        assert_eq!(mirrored.force_longitudinal, -forces.force_longitudinal);
        assert_eq!(mirrored.force_lateral, -forces.force_lateral);
    }
}
