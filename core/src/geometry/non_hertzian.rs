//! Non-Hertzian normal contact of one wheel: the patches from the interpenetration of the two
//! profiles, strip by strip in y, one patch per contact region instead of one Hertz ellipse per
//! minimum of the gap ([`super::normal_problem`]).
//!
//! Method: Kik and Piotrowski's virtual penetration (W. Kik, J. Piotrowski, "A fast, approximate
//! method to calculate normal load at contact between wheel and rail and creep forces during
//! rolling", 2nd TrC Mini Conference, Budapest, 1996; J. Piotrowski, W. Kik, "A simplified model
//! of wheel/rail contact mechanics for non-Hertzian problems and its application in rail vehicle
//! dynamic simulations", Vehicle System Dynamics 46 (2008) 27–48; below "KP"). Chosen over
//! ANALYN (Sichani, Enblom, Berg, 2014/2016), whose strip pressures follow from the gap's local
//! curvatures, and over STRIPES (Ayasse, Chollet, 2005), whose strips are Hertz contacts of the
//! local curvatures too, because KP needs only the gap's values: where the S1002/UIC60 gap is
//! flat within microns over 10 mm (the centred wheelset) or conformal (worn profiles) the
//! curvatures are near zero or change sign within the patch, and curvature-based methods are
//! ill-conditioned there; KP's region, shape and load follow from the gap itself. CONTACT's fast
//! normal solver (KPEC) is a KP variant as well. (KP's numbered equations are cited below by
//! their content; the derivation of each step is given here so that it can be checked without
//! the paper.)
//!
//! 1. Strips. The wheel profile's y is cut into strips on a fixed grid (`strip_grid.rs`: every
//!    [`TREAD_STRIP_WIDTH`] = 0.2 mm on the tread, every [`STRIP_WIDTH`] = 0.1 mm where the
//!    profile is steeper than [`TREAD_SLOPE`], multiples of 0.1 mm, so that a strip does not move
//!    with the wheelset and the patches' strips are about as many on the wide tread patches as
//!    on the narrow ones of the flange); per strip the
//!    exact geometry at its centre (the wheel's contact locus, as for a candidate point of
//!    [`WheelOnRail::candidates`]): the undeformed vertical gap g(y) at z_ws = 0, the rail's
//!    slope angle γ(y), the wheel's rolling radius R(y), the strip's position s and width ds
//!    along the rail's surface. Only the stretch where the gap lies within reach of its minimum
//!    is cut (a coarse scan of the sampled gap finds it first; with the strip table, the contact
//!    search's minima start it and it grows strip by strip).
//! 2. Virtual penetration (KP, the virtual interpenetration): the rigid approach is scaled by
//!    ε = 0.55 ([`VIRTUAL_PENETRATION_SCALE`]), because the elastic surfaces sink around the
//!    contact: the region where the undeformed gap lies less than ε δ above its minimum
//!    approximates the real contact area (for Hertz's circle, ε = 1/2 gives it exactly). The
//!    minimum is taken locally, the lowest gap m(y) within [`REFERENCE_REACH`] of the strip (KP
//!    take the region's deepest point; the running minimum gives the same for a single minimum
//!    and refers two distant interpenetrations — tread and flange — each to its own depth,
//!    continuously as they approach). A strip at z_ws penetrates virtually by
//!    v(y) = ε (z_ws − m(y)) − (g(y) − m(y)).
//! 3. Half-length along x (KP, the contact area's boundary): the wheel's circle adds x²/(2R) to
//!    the gap along the rail, so the strip is in contact for |x| < L(y) = √(2 R v).
//! 4. Pressure (KP's assumed distribution): semi-elliptic along each strip with its height
//!    proportional to the strip's half-length, p(x, y) = k √(L(y)² − x²) — Hertz's own
//!    distribution when the region is an ellipse. A region is a run of consecutive strips with
//!    v > 0. Its scale k follows from the elastic approach at its reference point (KP: the
//!    point of deepest virtual penetration; here the mean position of the strips whose v lies
//!    within [`REFERENCE_BAND`] of the region's highest, weighted by their height above that
//!    band's floor, squared: on a single peak within 0.03 strip widths of its vertex, and
//!    continuous where two maxima of v trade places, as the deepest point is not):
//!    Boussinesq's displacement of the two half-spaces under the pressure (Johnson, *Contact
//!    Mechanics*, 1985, eq. 3.20 per body; both of one material: 1/(π E*), E* = G/(1 − ν))
//!    equals the real normal approach there, (z_ws − g) cos γ. The inner integral over a strip
//!    is ∫ √(L² − x²)/√(x² + η²) dx = 2c (K(m) − E(m)) with c² = L² + η², m = L²/c² (x = L sin t),
//!    and K − E = (m/3) R_D(0, 1 − m, 1) (Carlson; DLMF 19.25.1), evaluated by the
//!    arithmetic-geometric mean (DLMF 19.8); it is log-singular at η = 0. Across a strip's width
//!    it is integrated exactly near the reference point (through its primitive, tabulated) and
//!    by the midpoint rule from 2.5 widths on (`strip_kernel.rs`), so that the displacement is
//!    continuous in the reference point's position. The regions of one
//!    patch (6) press on each other: the displacement at each reference point sums the pressure
//!    of every region of its patch, a small linear system for their scales (KP solve each
//!    region alone); a region the others would lift (k ≤ 0) is dropped. Regions of different
//!    patches do not interact, as CONTACT solves its patches apart.
//! 5. A strip's normal force is k (π/2) L² ds (p integrated over x).
//! 6. Patches: regions whose real interpenetrations (g < z_ws) lie within [`JOIN_DISTANCE`] of
//!    each other along the surface are one patch — where the tread's and the flange root's
//!    regions come near, one patch, as CONTACT solves them; apart, two. Per patch: the contact
//!    point at the pressure centroid (the strips' forces' mean of the wheel profile's y, and the
//!    exact geometry there: rail and track position) with the rail's slope there as its contact
//!    angle δ, its rolling radius the strips' force-weighted mean (where the creepages are the
//!    strips' mean: the slip is affine in the position); its normal force N such that N cos δ is the vertical force its
//!    strips carry (Σ F_j cos γ_j: the vertical balance holds exactly; the strips' lateral sum
//!    differs from N sin δ where the patch is curved, as CONTACT's planar patch does); an
//!    equivalent ellipse for the creep-force models with the patch's area (π a b = ∫ 2 L ds,
//!    with L² = 2 R v linear between the strips' centres: the area grows smoothly as a strip
//!    enters, where Σ 2 L ds grew like √v) and the shape of its pressure: a/b = σ_x/σ_s, the
//!    ratio of the pressure's spreads along x and across the surface (second moments: along a
//!    strip ∫ x² p dx / ∫ p dx = L²/4 for the semi-elliptic p; across, the line load about its
//!    centroid, linear between the strips' centres as L² is). For Hertz's ellipse
//!    both give σ² = a²/5 and b²/5, so a Hertzian patch keeps its own ellipse; where a patch
//!    has a long, lightly loaded tail (a tread lobe running out towards the flange root, A-2.2
//!    right case 2), the tail widens σ_s by its load, where the patch's extent took it at its
//!    full length. Half the patch's width between its edges as b (before 2026-12-02) stretched
//!    that patch's ellipse to a/b = 0.24 and its F_s came out 0.129 μN off CONTACT's full
//!    solution (0.081 now); on 47 poses with friction of our own (S1002/UIC60, y_ws 0–8 mm,
//!    10–100 kN, yaw 2 mrad, CONTACT's full solution: docs/geometry.md) the patches' creep
//!    forces' largest error fell from 0.133 to 0.074 μN. Each strip's force enters in
//!    proportion to v, so the ellipse is continuous as strips enter. The peak pressure is the
//!    strips' highest, the approach that at its deepest region's reference point.
//!
//! Continuity: at a prescribed z_ws the patches are continuous in the pose and z_ws but where
//! their structure changes (a region comes into contact, regions merge or part, a patch joins
//! or parts: the switching functions' events, `switching.rs`); the carried force has a kink
//! where a strip enters. With the creep forces in the vertical balance, its root is unique
//! where the area grows smoothly: the √v growth made the carried force fall as z_ws rose just
//! after a strip entered, and the balance had two roots there, which one found depending on
//! where the search started.
//!
//! Prescribed vertical position: the above at z_ws. Prescribed vertical force (frictionless,
//! Σ N cos δ = F_z): z_ws by secant steps on the carried vertical force's 2/3 power, which grows
//! with z_ws nearly linearly, then inside a bracket the secant where it converges and bisection
//! where it does not; started from a z_ws near the root where
//! one is known ([`NonHertzianPose`]: the wheel's balance, from its last step's depth, along its
//! last search's slope).
//!
//! Cost: fixed by the strips' spacing (6–111 strips in contact on S1002/UIC60 at 10–100 kN). Per pose the cut's
//! geometry: by default one exact spline point per strip (the reference); with the strip table
//! ([`WheelOnRail::with_strip_table`], `strip_table.rs`) the wheel's profile per strip read from
//! a table and the pose in closed form, the rail from its samples (within 2 nm of the exact gap;
//! 600 random poses within 0.5 nm in the contact point and 1.2e-7 in N,
//! `core/tests/library/strip_table.rs`). Per z_ws one kernel per strip in contact and region,
//! read from a table (`strip_kernel.rs`, within 1.6e-8 of the arithmetic-geometric mean), the
//! strips within 2.5 widths of the reference point integrated exactly through the kernel's
//! tabulated primitive. The wheel's balance ([`crate::wheel`]) is one root search whose every
//! evaluation includes the creep forces, from the last step's z_ws: 6–8 evaluations from a cold
//! start, one where the step repeats the last. A wheel step with a prescribed force, one criterion
//! run (`cargo bench -p wheel-rail-contact --bench geometry -- 'wheel_step_(non_hertzian_table_)?polach_'`),
//! Polach, tread 2 mm / centred / two minima 5 mm / flange 7 mm: Hertz 2.8 / 4.6 / 4.7 / 4.3 µs;
//! non-Hertzian with the strip table 9.6 / 19.2 / 12.6 / 4.0 µs (3.4 / 4.2 / 2.7 / 0.95 × Hertz)
//! where the step starts from the last one's z_ws (the benchmark repeats its step); 4–10 % less
//! than with the reference point's neighbours cut into 16 sub-strips each (the run before,
//! against the same build of Hertz). With the wheelset moving, every step a new pose (`_moving_`:
//! y_ws swinging by ±0.1 mm over 64 steps), 14.4 / 42.3 / 28.2 / 8.0 µs against Hertz's 2.8 /
//! 4.4 / 5.4 / 4.4 µs (5.2 / 9.7 / 5.2 / 1.8 ×): the root search takes more rounds from a moved
//! pose, started at the last step's depth below the touch (from the last z_ws itself, which
//! the touch leaves behind as the pose moves, the steps took 23 / 5 / 7 / 21 % longer). The
//! search's first step along the last search's slope and the secant inside its bracket (where
//! regula falsi's Illinois step overshot to the other side once a step), one run against the
//! build before: 14.3 / 34.3 / 24.0 / 7.9 µs against 14.5 / 43.5 / 28.1 / 8.0 (−2 / −21 / −14
//! / −1 %; repeated steps and Hertz unchanged); the centred step's rounds from 5.2 to about 4.
//! Without
//! the strip table (exact strips), an earlier run: 177 / 159 / 131 / 21 µs; from a cold cache
//! 31 / 83 / 55 / 19 µs (`exact_table` alike). The goal of 10 µs is met on the tread and the
//! flange with repeated steps, on the flange alone with moving ones. What remains grows with
//! the strips: the flange's patch, 5 strips in contact of 10 cut, costs 4 µs a repeated step,
//! the centred wheelset's 10 kN patch, 121 of 189, 19 µs; a profile of that step (perf on the
//! benchmark): some 40 % in the pose's cut (the strips' geometry from the table, the contact
//! search's minima that start it, the sliding minimum), the rest in the regions, the kernels
//! and the summary. The overheads of a cut and a round since (one vector per cut, tables read
//! without dividing, each strip's root computed once, unrefined minima to start the cut):
//! 14–15 % fewer instructions a repeated step, 4–10 % a moving one (docs/geometry.md).
//! The tread's strips every 0.2 mm instead of 0.1 (`strip_grid.rs`; the centred patch 61
//! strips instead of 121): 27 % fewer instructions a moving tread step, 41 % a centred one
//! (`scripts/instruction-budget`); timed against the build before, repeated 0.66 / 0.60 / 0.64 /
//! 0.82, moving 0.66 / 0.49 / 0.64 / 1.06 (docs/geometry.md, "Speed").
//!
//! Against CONTACT's full solution (`core/tests/library/geometry_non_hertzian.rs`, docs/geometry.md,
//! "Non-Hertzian contact"): 47 of 48 frictionless cases (y_ws 0–8 mm, 10–100 kN) within 1 mm /
//! 0.01 rad on the tread and 2 mm / 0.05 rad on the flange of CONTACT's pressure centroid and
//! contact angle, one patch each as CONTACT; the other (y_ws = 5 mm, 10 kN, tread and flange root
//! in one patch) 0.25 mm from the centroid but 0.014 rad off in angle. On measured worn profiles
//! (`core/tests/library/wheel_worn.rs`: a worn wheel on a worn high rail, tread to flange, 20
//! cases with friction) every patch CONTACT finds with ≥ 1 % of the load, two where it finds
//! two, within the same tolerances, but for the angle of a light patch on the worn gauge corner.

use super::contact::{LocusFrame, WheelOnRail, WheelsetPosition};
use super::normal_problem::MAX_PENETRATION;
use super::patch::{ContactPatch, WheelSide};
use super::profile_file::ProfileError;
use super::strip_kernel::strip_influence;
use super::strip_table::StripTable;
use super::switching::SwitchingFunctions;
use crate::hertz::HertzContact;
use std::collections::VecDeque;
use std::f64::consts::PI;
use std::ops::Deref;

/// KP's scale of the virtual penetration, ε (Piotrowski & Kik 2008, §3).
pub const VIRTUAL_PENETRATION_SCALE: f64 = 0.55;

pub use super::strip_grid::{STRIP_WIDTH, TREAD_SLOPE, TREAD_STRIP_WIDTH};

/// How far from a strip its reference depth, the lowest gap, is sought \[m\] (module doc, 2):
/// wider than a tread patch's half-width at 100 kN (≈ 8 mm on a flat gap), narrower than the
/// 14 mm or more between the tread's and the flange root's interpenetrations.
pub const REFERENCE_REACH: f64 = 10e-3;

/// Regions whose real interpenetrations (the gap below z_ws) lie closer than this along the
/// surface are one patch \[m\] (module doc, 6): CONTACT's separation distance D_SEP in its
/// Manchester A-2.2 decks, below which it solves neighbouring interpenetrations as one patch.
pub const JOIN_DISTANCE: f64 = 8e-3;

/// The share of a region's highest virtual penetration within which its strips place its
/// reference point (module doc, 4): wide enough that the point, on a parabolic
/// peak of v three strips or more wide, lies within 0.03 strip widths of the vertex wherever the
/// strips fall.
pub const REFERENCE_BAND: f64 = 0.5;

/// The coarse scan's step \[m\] that finds the stretch to cut into strips.
const SCAN_STEP: f64 = 2e-4;

/// How far above the gap's minimum the strips reach at least \[m\]; a deeper approach cuts
/// them again, reaching twice as far as often as needed ([`Source::reach_for`]). Above the
/// depth at 10 kN (0.016–0.15 mm on S1002/UIC60 at y_ws 0–10 mm; 0.07–0.68 mm at 100 kN) and no
/// further: the cut's exact geometry is most of a solve's cost, and strips whose gap lies above
/// z_ws are out of contact and no strip in contact's reference gap.
const FIRST_REACH: f64 = 0.25e-3;

/// [`FIRST_REACH`] for the strip table's strips \[m\]: their cut costs little next to the
/// kernels, and so the strips reach no more than twice the depth (a cold root search cuts two or
/// three times, a step from the last one's z_ws once); on the flat gap of the centred wheelset
/// at 10 kN 0.25 mm reach 335 strips, of which 120 are in contact.
const TABLE_FIRST_REACH: f64 = 0.02e-3;

/// Room for the strips beyond the contact search's minima in the strip table's cut (a cut's
/// vector is allocated once: on the flat gap of the centred wheelset some 180 strips).
const CUT_MARGIN: usize = 256;

/// Secant steps of the vertical balance's root search at most before it brackets the root
/// ([`NonHertzianPose::vertical_for_force`]): r(z_ws) is nearly linear, so a few reach the
/// balance's tolerance, and more would only follow a jump of the carried force.
const SECANT_STEPS: usize = 4;

/// A root of the vertical balance ([`NonHertzianPose::vertical_for_force`]), or where the next
/// search starts: z_ws \[m\] and, where known, the slope there of the search's residual r (the
/// carried force's 2/3 power, \[N^(2/3)/m\]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Root {
    pub(crate) vertical: f64,
    pub(crate) slope: Option<f64>,
}

/// `slope` if the search can step along it: finite and rising, as the residual does wherever
/// the patches carry more the deeper they are.
pub(crate) fn rising(slope: f64) -> Option<f64> {
    Some(slope).filter(|slope| slope.is_finite() && *slope > 0.0)
}

/// One strip of a patch, on the wheel's side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strip {
    /// Track y of the strip's centre \[m\].
    pub track_lateral: f64,
    /// y in the rail profile's coordinates \[m\].
    pub rail_lateral: f64,
    /// y in the wheel profile's coordinates \[m\].
    pub wheel_lateral: f64,
    /// Width along the rail's surface \[m\].
    pub width: f64,
    /// Half-length along x, L \[m\].
    pub half_length: f64,
    /// The pressure at x = 0, k L \[Pa\] (semi-elliptic along x).
    pub max_pressure: f64,
    /// The rail's slope angle there \[rad\] (the strip's normal).
    pub contact_angle: f64,
    /// The strip's normal force \[N\].
    pub normal_force: f64,
}

/// One patch: its strips and its summary (contact point at the pressure centroid, normal force,
/// equivalent ellipse).
#[derive(Debug, Clone, PartialEq)]
pub struct NonHertzianPatch {
    /// The strips in contact, from the rail's field side to its gauge side.
    pub strips: Vec<Strip>,
    /// Contact point, normal approach at the deepest strip, normal force and equivalent ellipse.
    pub patch: ContactPatch,
}

/// The non-Hertzian normal problem's answer for one wheel.
#[derive(Debug, Clone, PartialEq)]
pub struct NonHertzianContact {
    /// The wheelset's vertical position z_ws \[m\].
    pub vertical: f64,
    /// The patches, tread first.
    pub patches: Vec<NonHertzianPatch>,
    /// The switching functions of the regions' splits (`switching.rs`), tread first.
    pub switching: SwitchingFunctions,
}

/// One strip's geometry at its centre at z_ws = 0 (right side), from the exact splines
/// ([`WheelOnRail::surface_point`]) or the strip table (`strip_table.rs`).
#[derive(Debug, Clone, Copy)]
pub(super) struct StripPoint {
    /// The undeformed vertical gap \[m\].
    pub(super) gap: f64,
    pub(super) rolling_radius: f64,
    pub(super) track_lateral: f64,
    pub(super) rail_lateral: f64,
    /// Track z of the rail's surface \[m\].
    pub(super) track_vertical: f64,
    /// sin γ, cos γ of the rail's slope angle γ.
    pub(super) sin_cos: (f64, f64),
}

/// The geometry of one strip (right side).
#[derive(Debug, Clone, Copy)]
struct StripGeometry {
    wheel_lateral: f64,
    gap: f64,
    /// The lowest gap within [`REFERENCE_REACH`].
    reference_gap: f64,
    /// Position along the rail's surface \[m\].
    arc: f64,
    width: f64,
    rolling_radius: f64,
    track_lateral: f64,
    rail_lateral: f64,
    sin_cos: (f64, f64),
}

/// The coarse scan of one pose's gap (right side), every [`SCAN_STEP`] of the wheel profile's y
/// from `from`: what every cut of the pose's strips starts from.
struct Scan {
    from: f64,
    gaps: Vec<f64>,
    /// The lowest gap: z_ws where the wheel touches.
    touch: f64,
}

impl Scan {
    fn new(wheel: &WheelOnRail, right: &WheelsetPosition) -> Result<Self, ProfileError> {
        let (gap, (from, to)) = wheel.gap_function(right);
        let count = ((to - from) / SCAN_STEP).floor() as usize + 1;
        let gaps: Vec<f64> = (0..count).map(|i| gap(from + i as f64 * SCAN_STEP)).collect();
        let touch = gaps.iter().copied().fold(f64::INFINITY, f64::min);
        if !touch.is_finite() {
            return Err(ProfileError::whole(format!(
                "the wheel and the rail profile do not overlap laterally at wheelset_lateral_displacement = {} m",
                right.lateral
            )));
        }
        Ok(Self { from, gaps, touch })
    }
}

/// Where a pose's strips come from: the exact splines per strip over the stretch the coarse
/// scan finds (the reference), or the strip table grown from the contact search's minima
/// (`strip_table.rs`, module doc).
enum Source<'a> {
    Exact(Scan),
    Table { table: &'a StripTable, frame: LocusFrame, minima: Vec<(i64, f64)>, touch: f64 },
}

impl<'a> Source<'a> {
    /// The strip table's where the wheel has one and the contact search finds a minimum, the
    /// exact path's otherwise.
    fn new(wheel: &'a WheelOnRail, right: &WheelsetPosition) -> Result<Self, ProfileError> {
        if let Some(table) = &wheel.strip_table {
            let minima = StripTable::minima(wheel, right)?;
            let touch = minima.iter().map(|&(_, gap)| gap).fold(f64::INFINITY, f64::min);
            if touch.is_finite() {
                return Ok(Self::Table { table, frame: LocusFrame::new(right), minima, touch });
            }
        }
        Ok(Self::Exact(Scan::new(wheel, right)?))
    }

    /// The strips' reach for an approach `depth` below the touch: the first reach
    /// ([`FIRST_REACH`], [`TABLE_FIRST_REACH`]) doubled until it exceeds the depth, a function of
    /// the depth alone so that both modes cut the same strips.
    fn reach_for(&self, depth: f64) -> f64 {
        let mut reach = match self {
            Self::Exact(_) => FIRST_REACH,
            Self::Table { .. } => TABLE_FIRST_REACH,
        };
        while reach <= depth {
            reach *= 2.0;
        }
        reach
    }

    /// The lowest gap: z_ws where the wheel touches.
    fn touch(&self) -> f64 {
        match self {
            Self::Exact(scan) => scan.touch,
            Self::Table { touch, .. } => *touch,
        }
    }

    /// The strips (wheel profile y, geometry; `None` off a profile) over the stretch where the
    /// gap lies within `reach` of its minimum, with one beyond each end, from the field side.
    fn strips(&self, wheel: &WheelOnRail, right: &WheelsetPosition, reach: f64) -> Vec<(f64, Option<StripPoint>)> {
        match self {
            Self::Exact(scan) => {
                let at = |i: usize| scan.from + i as f64 * SCAN_STEP;
                let near: Vec<usize> = (0..scan.gaps.len()).filter(|&i| scan.gaps[i] < scan.touch + reach).collect();
                // One step beyond the first and last scanned sample within reach: the stretch's ends.
                let (first, last) = (at(near[0]) - SCAN_STEP, at(near[near.len() - 1]) + SCAN_STEP);
                let grid = wheel.strip_grid();
                (grid.first_from(first)..=grid.last_to(last))
                    .map(|k| {
                        let wheel_lateral = grid.lateral(k);
                        let point = wheel.surface_point(wheel_lateral, right).ok().map(|point| StripPoint {
                            gap: point.gap_at_zero,
                            rolling_radius: point.rolling_radius,
                            track_lateral: point.track_lateral,
                            rail_lateral: point.rail_lateral,
                            track_vertical: point.track_vertical,
                            sin_cos: point.contact_angle_sin_cos(),
                        });
                        (wheel_lateral, point)
                    })
                    .collect()
            }
            Self::Table { table, frame, minima, touch } => {
                let limit = touch + reach;
                let at = |k: i64| table.strip(wheel, frame, k);
                let within = |strip: &(f64, Option<StripPoint>)| strip.1.is_some_and(|point| point.gap < limit);
                // From the first to the last minimum within reach (the lowest is), then outward
                // while the gap stays within reach, one strip beyond.
                let near = || minima.iter().filter(|&&(_, gap)| gap < limit).map(|&(k, _)| k);
                let (low, high) = (near().min().unwrap_or(0), near().max().unwrap_or(0));
                // One vector (the strips are 72 bytes each, a few hundred of them: a second one
                // appended to the first was a tenth of the cut's time): downward from low − 1,
                // reversed, then up from low.
                let mut strips: Vec<(f64, Option<StripPoint>)> =
                    Vec::with_capacity(usize::try_from(high - low).unwrap_or(0) + CUT_MARGIN);
                // The strips from `from` + `step` on, every `step`, up to the first out of reach.
                let grow = |strips: &mut Vec<(f64, Option<StripPoint>)>, from: i64, step: i64| {
                    let mut k = from;
                    loop {
                        k += step;
                        strips.push(at(k));
                        if !strips.last().is_some_and(within) {
                            break;
                        }
                    }
                };
                grow(&mut strips, low, -1);
                strips.reverse();
                strips.extend((low..=high).map(at));
                grow(&mut strips, high, 1);
                strips
            }
        }
    }
}

/// The strips of one pose (right side).
struct Strips<'a> {
    wheel: &'a WheelOnRail,
    right: WheelsetPosition,
    strips: Vec<StripGeometry>,
    /// The strips cover every y where the gap lies less than this above the touch.
    reach: f64,
}

/// A region in contact at z_ws: its strips [first, end), its deepest strip, its reference
/// point (the peak of the virtual penetration between strips) and the real normal approach
/// there, and its pressure scale k.
#[derive(Clone, Copy)]
struct Region {
    first: usize,
    end: usize,
    deepest: usize,
    reference_arc: f64,
    approach: f64,
    scale: f64,
}

/// The regions a solve's patches were made of, in the strips' order, and the join functions
/// between neighbours that grouped them ([`NonHertzianPose::summaries_at`]): what their
/// switching functions are computed from, for the solve that is kept alone.
pub(crate) struct Regions {
    regions: Vec<Region>,
    joins: Vec<f64>,
}

impl<'a> Strips<'a> {
    /// Cuts the strips of the pose `right` over the stretch where the gap lies within `reach`
    /// of its minimum.
    fn new(wheel: &'a WheelOnRail, right: WheelsetPosition, source: &Source, reach: f64) -> Self {
        let cut = source.strips(wheel, &right, reach);
        let mut strips: Vec<StripGeometry> = Vec::with_capacity(cut.len());
        let mut track_vertical = Vec::with_capacity(cut.len());
        for (wheel_lateral, point) in cut {
            let geometry = match point {
                Some(point) => {
                    track_vertical.push(point.track_vertical);
                    StripGeometry {
                        wheel_lateral,
                        gap: point.gap,
                        reference_gap: 0.0,
                        arc: 0.0,
                        width: 0.0,
                        rolling_radius: point.rolling_radius,
                        track_lateral: point.track_lateral,
                        rail_lateral: point.rail_lateral,
                        sin_cos: point.sin_cos,
                    }
                }
                // Off a profile: no contact there (the stretch lies within reach of the
                // minimum, so this is at most its end).
                None => {
                    let before = strips.last().map_or((0.0, 0.0), |s| (s.track_lateral, s.rail_lateral));
                    track_vertical.push(track_vertical.last().copied().unwrap_or(0.0));
                    StripGeometry {
                        wheel_lateral,
                        gap: f64::INFINITY,
                        reference_gap: 0.0,
                        arc: 0.0,
                        width: 0.0,
                        rolling_radius: 0.0,
                        track_lateral: before.0 + STRIP_WIDTH,
                        rail_lateral: before.1 + STRIP_WIDTH,
                        sin_cos: (0.0, 1.0),
                    }
                }
            };
            strips.push(geometry);
        }
        // Arc length along the rail's surface through the strips' centres, and each strip's
        // width: half the distance between its neighbours.
        for i in 1..strips.len() {
            // (Not `hypot`: the steps are a tenth of a millimetre, far from overflow.)
            let (lateral, vertical) =
                (strips[i].track_lateral - strips[i - 1].track_lateral, track_vertical[i] - track_vertical[i - 1]);
            let step = (lateral * lateral + vertical * vertical).sqrt();
            strips[i].arc = strips[i - 1].arc + step;
        }
        // (The stretch spans at least two scan steps, 0.4 mm, four strips or more, or, from the
        // strip table, three strips or more.)
        let n = strips.len();
        for i in 0..n {
            let (before, after) = (i.saturating_sub(1), (i + 1).min(n - 1));
            strips[i].width = (strips[after].arc - strips[before].arc) / (after - before) as f64;
        }
        // The running minimum of the gap within REFERENCE_REACH (in the wheel's y), strip c's
        // over the strips whose y lies within it: a sliding-window minimum (a queue of the strips
        // whose gap no later strip in the window undercuts, lowest first), O(n) instead of O(n w)
        // with w ≈ 100 strips. (By y, not by count: the strips lie 0.2 mm apart on the tread,
        // 0.1 mm off it.)
        let mut window: VecDeque<usize> = VecDeque::with_capacity(n);
        let mut next = 0;
        for centre in 0..n {
            let y = strips[centre].wheel_lateral;
            while next < n && strips[next].wheel_lateral <= y + REFERENCE_REACH {
                while window.back().is_some_and(|&j| strips[j].gap >= strips[next].gap) {
                    window.pop_back();
                }
                window.push_back(next);
                next += 1;
            }
            while window.front().is_some_and(|&j| strips[j].wheel_lateral < y - REFERENCE_REACH) {
                window.pop_front();
            }
            strips[centre].reference_gap = window.front().map_or(f64::INFINITY, |&j| strips[j].gap);
        }
        Self { wheel, right, strips, reach }
    }

    /// The strips at z_ws = `vertical`: each one's virtual penetration and half-length computed
    /// once, for every use a solve at that z_ws makes of them.
    fn at(&self, vertical: f64) -> Loaded<'_, 'a> {
        let penetration: Vec<f64> = self
            .strips
            .iter()
            .map(|s| {
                // (module doc, 2); −∞ off the profiles, where the gap is +∞ and its running
                // minimum may be too.
                if s.gap == f64::INFINITY {
                    f64::NEG_INFINITY
                } else {
                    VIRTUAL_PENETRATION_SCALE * (vertical - s.reference_gap) - (s.gap - s.reference_gap)
                }
            })
            .collect();
        // (module doc, 3), 0 out of contact.
        let half_length = self
            .strips
            .iter()
            .zip(&penetration)
            .map(|(s, &v)| if v > 0.0 { (2.0 * s.rolling_radius * v).sqrt() } else { 0.0 })
            .collect();
        Loaded { cut: self, vertical, penetration, half_length }
    }
}

/// The strips at one z_ws ([`Strips::at`]): the regions, their loads and the patches there.
struct Loaded<'s, 'a> {
    cut: &'s Strips<'a>,
    vertical: f64,
    /// Each strip's virtual penetration v (module doc, 2).
    penetration: Vec<f64>,
    /// Each strip's half-length L along x (module doc, 3).
    half_length: Vec<f64>,
}

impl<'a> Deref for Loaded<'_, 'a> {
    type Target = Strips<'a>;

    fn deref(&self) -> &Strips<'a> {
        self.cut
    }
}

impl Loaded<'_, '_> {
    /// The virtual penetration of strip i (module doc, 2); −∞ off the profiles.
    fn virtual_penetration(&self, i: usize) -> f64 {
        self.penetration[i]
    }

    /// The half-length of strip i (module doc, 3), 0 out of contact.
    fn half_length(&self, i: usize) -> f64 {
        self.half_length[i]
    }

    /// The regions in contact at z_ws with their loads (module doc, 4–5), in the strips'
    /// order, with their joins ([`Self::joins`]); a region whose scale the others' pressure
    /// would make negative is left out.
    fn regions(&self) -> Regions {
        let n = self.strips.len();
        let mut regions = Vec::new();
        let mut i = 0;
        while i < n {
            if self.virtual_penetration(i) <= 0.0 {
                i += 1;
                continue;
            }
            let first = i;
            let mut reference = i;
            while i < n && self.virtual_penetration(i) > 0.0 {
                if self.virtual_penetration(i) > self.virtual_penetration(reference) {
                    reference = i;
                }
                i += 1;
            }
            let (reference_arc, approach) = self.reference_point(first, i, reference);
            regions.push(Region { first, end: i, deepest: reference, reference_arc, approach, scale: 0.0 });
        }
        // The approach at each reference point equals the displacement under the pressure of
        // every region of its patch there: Σ_b k_b I_ab = π E* δ_a, a small dense system; a
        // region whose k comes out ≤ 0 is lifted by the others' pressure and dropped, and the
        // rest solved again. Regions of different patches do not press on each other: CONTACT
        // solves its patches apart (their interpenetrations lie more than D_SEP apart), and a
        // light tread patch beside a loaded flange (measured worn profiles, y_ws = 13 mm,
        // 80 kN: 316 N of 80 kN) is kept, as CONTACT keeps it, not lifted by the flange's
        // far field.
        let count = regions.len();
        let modulus = self.wheel.contact_modulus();
        let joins = self.joins(&regions);
        let patch_of = patch_of_each(&joins);
        let mut influence = vec![0.0; count * count];
        for (a, region) in regions.iter().enumerate() {
            for (b, other) in regions.iter().enumerate() {
                if patch_of[a] == patch_of[b] {
                    influence[a * count + b] = self.influence(other.first, other.end, region.reference_arc);
                }
            }
        }
        let mut active = vec![true; count];
        loop {
            let members: Vec<usize> = (0..count).filter(|&a| active[a]).collect();
            let m = members.len();
            let mut matrix: Vec<f64> = members
                .iter()
                .flat_map(|&a| members.iter().map(move |&b| (a, b)))
                .map(|(a, b)| influence[a * count + b])
                .collect();
            let mut scales: Vec<f64> = members.iter().map(|&a| PI * modulus * regions[a].approach).collect();
            solve_dense(&mut matrix, &mut scales, m);
            match (0..m).filter(|&i| scales[i] <= 0.0).min_by(|&i, &j| scales[i].total_cmp(&scales[j])) {
                Some(lifted) => active[members[lifted]] = false,
                None => {
                    for (i, &a) in members.iter().enumerate() {
                        regions[a].scale = scales[i];
                    }
                    break;
                }
            }
        }
        let before = regions.len();
        regions.retain(|region| region.scale > 0.0);
        // The joins once a round (taken twice, they cost the centred wheel's moving step 3 500
        // instructions of 237 000), again only where a region was lifted.
        let joins = if regions.len() == before { joins } else { self.joins(&regions) };
        Regions { regions, joins }
    }

    /// The reference point of the region [first, end) whose deepest strip is `deepest` (module
    /// doc, 4): the mean position along the surface of its strips whose virtual penetration v
    /// lies within [`REFERENCE_BAND`] of its highest, weighted by (v − (1 − band) v_max)²; as
    /// that position and the real normal approach there, (z_ws − g) cos γ interpolated linearly
    /// between the strips around it. Continuous in the pose and z_ws: the weights grow from 0
    /// as a strip enters the band, where the strip of deepest v passing to another maximum of
    /// the region made the reference jump between them (the centred S1002/UIC60 wheelset at
    /// y_ws = 0.2143 mm, 10 kN: the approach from 12.7 to 10.5 µm).
    fn reference_point(&self, first: usize, end: usize, deepest: usize) -> (f64, f64) {
        let floor = (1.0 - REFERENCE_BAND) * self.virtual_penetration(deepest);
        let (mut total, mut moment) = (0.0, 0.0);
        for j in first..end {
            let weight = (self.virtual_penetration(j) - floor).max(0.0).powi(2);
            total += weight;
            moment += weight * self.strips[j].arc;
        }
        let arc = moment / total;
        // The strips on either side of the position (the deepest's weight is > 0: total > 0).
        let after = (first + 1..end).find(|&j| self.strips[j].arc > arc).unwrap_or(end - 1);
        let before = after.saturating_sub(1).max(first);
        let approach = |i: usize| (self.vertical - self.strips[i].gap) * self.strips[i].sin_cos.1;
        let span = self.strips[after].arc - self.strips[before].arc;
        let t = if span > 0.0 { ((arc - self.strips[before].arc) / span).clamp(0.0, 1.0) } else { 0.0 };
        (arc, (1.0 - t) * approach(before) + t * approach(after))
    }

    /// The displacement at x = 0 and the surface position `at` under the pressure √(L² − x²)
    /// (k = 1) on strips [first, end), times π E* (module doc, 4; `strip_kernel.rs`).
    fn influence(&self, first: usize, end: usize, at: f64) -> f64 {
        (first..end)
            .map(|j| {
                let s = &self.strips[j];
                strip_influence(self.half_length(j), s.width, s.arc - at)
            })
            .sum()
    }

    /// Strip j's normal force in a region of scale k.
    fn strip_force(&self, j: usize, scale: f64) -> f64 {
        let length = self.half_length(j);
        scale * 0.5 * PI * length * length * self.strips[j].width
    }

    /// The vertical force the patches carry at z_ws, Σ N cos γ over the strips.
    fn carried(&self) -> f64 {
        let mut force = 0.0;
        for region in self.regions().regions {
            for j in region.first..region.end {
                force += self.strip_force(j, region.scale) * self.strips[j].sin_cos.1;
            }
        }
        force
    }

    /// The contact area of `region` at z_ws, ∫ 2L ds along the surface with L² = 2 R v
    /// interpolated linearly between the strips' centres, out to where it falls to 0 towards
    /// the strips beside the region (module doc, 6); at the end of the cut or of a profile, to
    /// the outer side of the strip itself. Continuously differentiable in the strips' v as a
    /// strip enters: Σ 2 L w with L = √(2 R v) grew like √v, and so did the equivalent
    /// ellipse's a and with it the creep forces, so that the vertical force carried with them
    /// could fall as z_ws rose, and the wheel's balance had two roots (a flange patch at y_ws =
    /// 7.12 mm: F_y by 0.3 N of 26.7 kN, as either was found).
    ///
    /// Along the same stretches, the region's pressure is added to `moments` about the surface
    /// position `origin` (module doc, 6): its line load f = k (π/2) L² (module doc, 5), linear
    /// between the strips' centres as L² is, where the strips' own forces at their centres
    /// made the spread across a narrow flange patch of a few strips jitter with the strips'
    /// grid as the patch slid over it (the flange's F_y rose by 9.6 N over 0.05 mm of y_ws at
    /// 7 mm, `wheel_non_hertzian::forces_move_continuously_through_the_transition`).
    fn area_and_moments(&self, region: &Region, origin: f64, moments: &mut PressureMoments) -> f64 {
        // L² = 2 R v (module doc, 3) with its root L where v > 0 ([`Strips::at`]), and the
        // strip's position.
        let squared = |j: usize| {
            let strip = &self.strips[j];
            (strip.arc - origin, 2.0 * strip.rolling_radius * self.virtual_penetration(j), self.half_length(j))
        };
        let (mut area, mut of_squares) = (0.0, PressureMoments::default());
        let mut stretch = |(at, inner, inner_root): (f64, f64, f64), (to, outer, outer_root): (f64, f64, f64)| {
            area += segment_area((inner, inner_root), (outer, outer_root), (to - at).abs());
            of_squares.add((at, inner), (to, outer));
        };
        for j in region.first..region.end - 1 {
            stretch(squared(j), squared(j + 1));
        }
        for (inside, outside, sign) in
            [(region.first, region.first.checked_sub(1), -1.0), (region.end - 1, Some(region.end), 1.0)]
        {
            let end = squared(inside);
            match outside.filter(|&j| self.strips.get(j).is_some_and(|s| s.gap.is_finite())) {
                Some(j) => stretch(end, squared(j)),
                // Half the strip's width at its own L: the area L w, as the strip's own.
                None => stretch(end, (end.0 + sign * 0.5 * self.strips[inside].width, end.1, end.2)),
            }
        }
        moments.add_scaled(&of_squares, region.scale);
        area
    }

    /// The real interpenetration's extent along the surface around the region [first, end):
    /// the strips next to it where the gap lies below z_ws, to the outer edges of the last ones.
    fn interpenetration_extent(&self, first: usize, end: usize) -> (f64, f64) {
        let strips = &self.strips;
        let mut low = first;
        while low > 0 && strips[low - 1].gap < self.vertical {
            low -= 1;
        }
        let mut high = end - 1;
        while high + 1 < strips.len() && strips[high + 1].gap < self.vertical {
            high += 1;
        }
        (strips[low].arc - 0.5 * strips[low].width, strips[high].arc + 0.5 * strips[high].width)
    }

    /// The join function between each of `regions` but the first and the patch of the regions
    /// before it (`switching.rs`): the distance along the surface from that patch's real
    /// interpenetrations to the region's, less [`JOIN_DISTANCE`]; the region joins the patch
    /// where it is ≤ 0.
    fn joins(&self, regions: &[Region]) -> Vec<f64> {
        let mut joins = Vec::with_capacity(regions.len().saturating_sub(1));
        let mut patch_end = None;
        for region in regions {
            let (low, high) = self.interpenetration_extent(region.first, region.end);
            patch_end = Some(match patch_end {
                Some(end) => {
                    let join = low - end - JOIN_DISTANCE;
                    joins.push(join);
                    if join <= 0.0 {
                        high.max(end)
                    } else {
                        high
                    }
                }
                None => high,
            });
        }
        joins
    }

    /// The patches at z_ws, on the wheel's side: the regions grouped (module doc, 6); their
    /// strips listed if `with_strips`; and the regions with the joins that grouped them.
    fn patches(&self, with_strips: bool) -> Result<(Vec<NonHertzianPatch>, Regions), ProfileError> {
        let Regions { regions, joins } = self.regions();
        // A patch is a run of neighbouring regions: a region whose join is > 0 starts the next.
        let mut patches = Vec::new();
        let mut first = 0;
        for end in 1..=regions.len() {
            if joins.get(end - 1).is_none_or(|&join| join > 0.0) {
                patches.push(self.patch(&regions[first..end], with_strips)?);
                first = end;
            }
        }
        // The strips are cut along the wheel profile's y, which runs from the flange (the rail's
        // gauge side) to the field side: the patches tread first, as the Hertz ones.
        patches.reverse();
        Ok((patches, Regions { regions, joins }))
    }

    /// The switching functions (`switching.rs`) of the patches made of `regions` at z_ws, field
    /// side first: per region its onset (its deepest virtual penetration, negated); per
    /// neighbouring pair its join function and, joined, its deepest function.
    fn switching_functions(&self, Regions { regions, joins }: &Regions) -> SwitchingFunctions {
        // Field side first: the strips run from the gauge side.
        let count = regions.len();
        let region = |k: usize| &regions[count - 1 - k];
        SwitchingFunctions::new(
            count,
            |k| -self.virtual_penetration(region(k).deepest),
            |k| *joins.iter().rev().nth(k).expect("a join between each two neighbours"),
            |join| join <= 0.0,
        )
    }

    /// One patch from its regions at z_ws, on the wheel's side; its strips listed if
    /// `with_strips` (the wheel's balance reads the summary alone: a strip's contact angle is
    /// an arctangent).
    fn patch(&self, regions: &[Region], with_strips: bool) -> Result<NonHertzianPatch, ProfileError> {
        let side = self.wheel.side();
        let (mut normal, mut centroid, mut area, mut peak, mut total) = (0.0, 0.0, 0.0, 0.0f64, 0.0);
        let mut radius = 0.0;
        // The pressure's moments (the equivalent ellipse's shape, below), about the first strip
        // (no cancellation on a narrow flange patch far from the surface's origin).
        let origin = self.strips[regions[0].first].arc;
        let mut moments = PressureMoments::default();
        let mut strips = Vec::new();
        let mut deepest = regions[0];
        for region in regions {
            if self.virtual_penetration(region.deepest) > self.virtual_penetration(deepest.deepest) {
                deepest = *region;
            }
            area += self.area_and_moments(region, origin, &mut moments);
            for j in region.first..region.end {
                let s = &self.strips[j];
                let length = self.half_length(j);
                let force = self.strip_force(j, region.scale);
                normal += force * s.sin_cos.1;
                centroid += force * s.wheel_lateral;
                radius += force * s.rolling_radius;
                peak = peak.max(region.scale * length);
                total += force;
                if !with_strips {
                    continue;
                }
                let strip = Strip {
                    track_lateral: s.track_lateral,
                    rail_lateral: s.rail_lateral,
                    wheel_lateral: s.wheel_lateral,
                    width: s.width,
                    half_length: length,
                    max_pressure: region.scale * length,
                    contact_angle: s.sin_cos.0.atan2(s.sin_cos.1),
                    normal_force: force,
                };
                strips.push(match side {
                    WheelSide::Right => strip,
                    WheelSide::Left => Strip {
                        track_lateral: -strip.track_lateral,
                        rail_lateral: -strip.rail_lateral,
                        wheel_lateral: -strip.wheel_lateral,
                        contact_angle: -strip.contact_angle,
                        ..strip
                    },
                });
            }
        }
        // Field side first (cut from the gauge side, see `patches`).
        strips.reverse();
        // The contact point at the pressure centroid, with the rail's slope there as the
        // patch's contact angle; the normal force such that the patch carries the strips'
        // vertical force, N cos δ = Σ F_j cos γ_j.
        let mut point = self.wheel.surface_point(centroid / total, &self.right)?;
        // The slip velocity V + ω × r is affine in the point r, so the strips' slip, weighted by
        // their loads, is the slip at their load-weighted mean position: the creepages are
        // taken there, at the strips' mean rolling radius, which lies off the surfaces where
        // the patch is wide and curved (A-2.2 case 1, the centred wheelset: CONTACT's F_x is
        // 0.3 N; at the centroid's own radius ours was 0.123 μN off, at the mean 0.083 μN).
        let mean_radius = radius / total;
        point.track_vertical += mean_radius - point.rolling_radius;
        point.rolling_radius = mean_radius;
        let force = normal / point.contact_angle_sin_cos().1;
        // The equivalent ellipse (module doc, 6): the area's, shaped as the pressure is spread,
        // a/b = σ_x/σ_s.
        let aspect = moments.spread_ratio();
        let semi_axis_b = (area / (PI * aspect)).sqrt();
        let approach = deepest.approach;
        let ellipse = HertzContact { semi_axis_a: aspect * semi_axis_b, semi_axis_b, max_pressure: peak, approach };
        Ok(NonHertzianPatch {
            strips,
            patch: ContactPatch {
                point: side.mirror_point(&point),
                penetration: approach,
                normal_force: force,
                ellipse,
            },
        })
    }
}

/// A patch's line load f(s) (normal force per unit width of surface) in moments about an
/// origin on the surface: ∫ f ds, ∫ f s ds, ∫ f s² ds, and ∫ f L²/4 ds, the pressure's second
/// moment along x (∫ x² p dx = f L²/4 for the semi-elliptic p of a strip, module doc, 5).
/// Per region they are those of q = L² scaled by its k: f = k (π/2) q, f L²/4 = k (π/8) q².
#[derive(Default)]
struct PressureMoments {
    force: f64,
    first: f64,
    second: f64,
    along: f64,
}

impl PressureMoments {
    /// Adds the moments of q along a stretch from `(at, q)` (q > 0) to `(to, q_to)` along which
    /// it runs linearly, up to where it falls to 0 (`along` holding ∫ q² ds). The integrals of a
    /// linear q = q_a N_a + q_b N_b over [a, b] (h = |b − a|) with the hat functions' moments:
    /// ∫ q = h (q_a + q_b)/2, ∫ q s = h (q_a (2a + b) + q_b (a + 2b))/6, ∫ q s² = h (q_a (3a² +
    /// 2ab + b²) + q_b (a² + 2ab + 3b²))/12, ∫ q² = h (q_a² + q_a q_b + q_b²)/3.
    fn add(&mut self, (at, q): (f64, f64), (to, q_to): (f64, f64)) {
        let (to, q_to) = if q_to < 0.0 { (at + (to - at) * q / (q - q_to), 0.0) } else { (to, q_to) };
        let length = (to - at).abs();
        self.force += 0.5 * length * (q + q_to);
        self.first += length / 6.0 * (q * (2.0 * at + to) + q_to * (at + 2.0 * to));
        let (at_squared, cross, to_squared) = (at * at, 2.0 * at * to, to * to);
        self.second += length / 12.0
            * (q * (3.0 * at_squared + cross + to_squared) + q_to * (at_squared + cross + 3.0 * to_squared));
        self.along += length / 3.0 * (q * q + q * q_to + q_to * q_to);
    }

    /// Adds a region's moments of q = L² (`of_squares`, [`Self::add`]) as its pressure's, k its
    /// scale.
    fn add_scaled(&mut self, of_squares: &PressureMoments, scale: f64) {
        let line_load = 0.5 * PI * scale;
        self.force += line_load * of_squares.force;
        self.first += line_load * of_squares.first;
        self.second += line_load * of_squares.second;
        self.along += 0.125 * PI * scale * of_squares.along;
    }

    /// σ_x/σ_s, the ratio of the pressure's spreads along x and across the surface (module
    /// doc, 6): a/b of the equivalent ellipse (σ² = a²/5 and b²/5 for Hertz's pressure).
    fn spread_ratio(&self) -> f64 {
        let mean = self.first / self.force;
        (self.along / (self.second - mean * self.first)).sqrt()
    }
}

/// The patch of each of the regions whose `joins` these are ([`Loaded::joins`], in the strips'
/// order), numbered from 0: regions whose real interpenetrations lie within [`JOIN_DISTANCE`]
/// of each other are one patch (module doc, 6).
fn patch_of_each(joins: &[f64]) -> Vec<usize> {
    let mut patch = 0;
    let later = joins.iter().map(|&join| {
        patch += usize::from(join > 0.0);
        patch
    });
    std::iter::once(0).chain(later).collect()
}

/// ∫ 2 √max(q, 0) ds over a segment `length` long along which q (a strip's L²) runs linearly
/// from `from` to `to`: (4/3) h (a² + ab + b²)/(a + b) with a, b the roots of the ends where both
/// are in contact (the form of (a³ − b³)/(a² − b²) without its cancellation), and over the part
/// in contact, a fraction q_in/(q_in − q_out), (4/3) h a times it where one is. Each end is
/// given as q and its root where q > 0 (a strip's L², L: the root computed once per strip, not
/// twice per segment, where the square roots and the division chained were a tenth of a wide
/// patch's round).
fn segment_area((from, from_root): (f64, f64), (to, to_root): (f64, f64), length: f64) -> f64 {
    let ((inner, a), (outer, b)) =
        if from >= to { ((from, from_root), (to, to_root)) } else { ((to, to_root), (from, from_root)) };
    if inner <= 0.0 {
        return 0.0;
    }
    if outer <= 0.0 {
        return 4.0 / 3.0 * length * a * inner / (inner - outer);
    }
    4.0 / 3.0 * length * (inner + a * b + outer) / (a + b)
}

/// Solves the n × n system `matrix` x = `rhs` (row-major) in place by Gaussian elimination with
/// partial pivoting; x is left in `rhs`.
fn solve_dense(matrix: &mut [f64], rhs: &mut [f64], n: usize) {
    for column in 0..n {
        let pivot = (column..n).max_by(|&i, &j| matrix[i * n + column].abs().total_cmp(&matrix[j * n + column].abs()));
        let pivot = pivot.unwrap_or(column);
        if pivot != column {
            for k in 0..n {
                matrix.swap(pivot * n + k, column * n + k);
            }
            rhs.swap(pivot, column);
        }
        for row in column + 1..n {
            let factor = matrix[row * n + column] / matrix[column * n + column];
            for k in column..n {
                matrix[row * n + k] -= factor * matrix[column * n + k];
            }
            rhs[row] -= factor * rhs[column];
        }
    }
    for row in (0..n).rev() {
        let known: f64 = (row + 1..n).map(|k| matrix[row * n + k] * rhs[k]).sum();
        rhs[row] = (rhs[row] - known) / matrix[row * n + row];
    }
}

impl WheelOnRail {
    /// The non-Hertzian patches (module doc) at the wheelset's vertical position (prescribed
    /// position), tread first. A z_ws more than [`MAX_PENETRATION`] below the touch is refused.
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
    ///
    /// let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
    /// let at = |vertical| placed.non_hertzian_patches_at(&WheelsetPosition { vertical, ..Default::default() }).unwrap();
    /// let light = at(0.19e-3);
    /// let heavy = at(0.23e-3);
    /// assert_eq!((light.patches.len(), heavy.patches.len()), (1, 1));
    /// // Deeper: more load, on more strips.
    /// assert!(heavy.patches[0].patch.normal_force > light.patches[0].patch.normal_force);
    /// assert!(heavy.patches[0].strips.len() > light.patches[0].strips.len());
    /// ```
    pub fn non_hertzian_patches_at(&self, position: &WheelsetPosition) -> Result<NonHertzianContact, ProfileError> {
        self.non_hertzian_pose(position)?.patches_at(position.vertical)
    }

    /// The non-Hertzian patches (module doc) carrying the vertical force F_z \[N\] on the wheel
    /// (frictionless: Σ N cos δ = F_z), with the wheelset's vertical position that carries it
    /// (`position.vertical` is not used). F_z ≤ 0 is lift-off: no patch, at the touch.
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
    ///
    /// let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
    /// // The centred wheelset at 10 kN: one wide tread patch, its pressure centroid at −8.49 mm
    /// // on the rail, near CONTACT's (−9.09 mm; its contact reference −8.66 mm); the gap's
    /// // minimum, the Hertz patch's point, lies at −7.28 mm.
    /// let contact = placed.non_hertzian_patches_for_force(10e3, &WheelsetPosition::default()).unwrap();
    /// assert_eq!(contact.patches.len(), 1);
    /// let patch = &contact.patches[0].patch;
    /// assert!((patch.point.rail_lateral + 9.09e-3).abs() < 0.65e-3, "{}", patch.point.rail_lateral);
    /// assert!((patch.normal_force * patch.point.contact_angle.cos() - 10e3).abs() < 1e-6);
    /// // Both modes agree.
    /// let at = placed.non_hertzian_patches_at(&WheelsetPosition { vertical: contact.vertical, ..Default::default() });
    /// assert_eq!(at.unwrap(), contact);
    /// ```
    pub fn non_hertzian_patches_for_force(
        &self,
        vertical_force: f64,
        position: &WheelsetPosition,
    ) -> Result<NonHertzianContact, ProfileError> {
        self.non_hertzian_pose(position)?.patches_for_force(vertical_force, None)
    }

    /// The non-Hertzian normal problem of the pose `position` (its lateral position, roll and
    /// yaw; `vertical` is not used), to be solved at several vertical positions or forces: the
    /// strips' geometry is computed once for them all.
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
    ///
    /// let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
    /// let position = WheelsetPosition { lateral: 5e-3, ..Default::default() };
    /// let mut pose = placed.non_hertzian_pose(&position).unwrap();
    /// let first = pose.patches_for_force(10e3, None).unwrap();
    /// // A load near the last one, started from its z_ws: the same as solved alone.
    /// let near = pose.patches_for_force(10.1e3, Some(first.vertical)).unwrap();
    /// let alone = placed.non_hertzian_patches_for_force(10.1e3, &position).unwrap();
    /// assert!((near.vertical - alone.vertical).abs() < 1e-12);
    /// // At its z_ws, the prescribed position gives the same patches.
    /// assert_eq!(pose.patches_at(near.vertical).unwrap(), near);
    /// ```
    pub fn non_hertzian_pose(&self, position: &WheelsetPosition) -> Result<NonHertzianPose<'_>, ProfileError> {
        let right = self.right_pose(position)?;
        let source = Source::new(self, &right)?;
        Ok(NonHertzianPose { wheel: self, right, source, cuts: Vec::new() })
    }
}

/// One pose's non-Hertzian normal problem ([`WheelOnRail::non_hertzian_pose`]): its coarse scan
/// and the strips cut so far, kept for the next solve at the same pose.
pub struct NonHertzianPose<'a> {
    wheel: &'a WheelOnRail,
    right: WheelsetPosition,
    source: Source<'a>,
    /// One cut per reach used ([`Source::reach_for`]): a depth is always solved on its own reach's
    /// strips, so that a solve gives the same answer whatever was solved before it.
    cuts: Vec<Strips<'a>>,
}

impl<'a> NonHertzianPose<'a> {
    /// The strips reaching `reach` above the touch, cut when first needed.
    fn strips(&mut self, reach: f64) -> &Strips<'a> {
        let index = match self.cuts.iter().position(|cut| cut.reach == reach) {
            Some(index) => index,
            None => {
                self.cuts.push(Strips::new(self.wheel, self.right, &self.source, reach));
                self.cuts.len() - 1
            }
        };
        &self.cuts[index]
    }

    /// The vertical force carried at z_ws, on the strips of its depth's reach.
    fn carried(&mut self, vertical: f64) -> f64 {
        let touch = self.source.touch();
        self.strips(self.source.reach_for(vertical - touch)).at(vertical).carried()
    }

    /// The patches at z_ws = `vertical` ([`WheelOnRail::non_hertzian_patches_at`]). A z_ws more
    /// than [`MAX_PENETRATION`] below the touch is refused.
    pub fn patches_at(&mut self, vertical: f64) -> Result<NonHertzianContact, ProfileError> {
        let strips = self.strips_at(vertical)?;
        let loaded = strips.at(vertical);
        let (patches, regions) = loaded.patches(true)?;
        Ok(NonHertzianContact { vertical, patches, switching: loaded.switching_functions(&regions) })
    }

    /// z_ws where the wheel first touches the rail at this pose: the gap's lowest (what a
    /// balance started from the last step's depth below it adds that depth to).
    pub(crate) fn touch(&self) -> f64 {
        self.source.touch()
    }

    /// The patches' summaries at z_ws = `vertical` (contact point, normal force, equivalent
    /// ellipse; [`Self::patches_at`] without the strips): what the wheel's creep forces are
    /// computed on; with the regions they were made of ([`Self::switching_functions`]).
    pub(crate) fn summaries_at(&mut self, vertical: f64) -> Result<(Vec<ContactPatch>, Regions), ProfileError> {
        let (patches, regions) = self.strips_at(vertical)?.at(vertical).patches(false)?;
        Ok((patches.into_iter().map(|patch| patch.patch).collect(), regions))
    }

    /// The switching functions of the patches of [`Self::summaries_at`] at the same z_ws, from
    /// the regions it returned: computed for the one solve a wheel step keeps, not for each
    /// round of its balance.
    pub(crate) fn switching_functions(
        &mut self,
        vertical: f64,
        regions: &Regions,
    ) -> Result<SwitchingFunctions, ProfileError> {
        Ok(self.strips_at(vertical)?.at(vertical).switching_functions(regions))
    }

    /// The strips z_ws = `vertical` is solved on; a z_ws more than [`MAX_PENETRATION`] below the
    /// touch is refused.
    fn strips_at(&mut self, vertical: f64) -> Result<&Strips<'a>, ProfileError> {
        let touch = self.source.touch();
        let depth = vertical - touch;
        // (NaN, from a NaN height, is refused too.)
        if !(..=MAX_PENETRATION).contains(&depth) {
            return Err(ProfileError::whole(format!(
                "wheelset_vertical_position = {vertical} m puts the wheel {depth:e} m into the rail (it touches at \
                 {touch} m): more than {MAX_PENETRATION} m of penetration is a wheel inside its rail, not a contact"
            )));
        }
        Ok(self.strips(self.source.reach_for(depth)))
    }

    /// The patches carrying the vertical force F_z \[N\] ([`WheelOnRail::non_hertzian_patches_for_force`]),
    /// the root's search started from `near`, a z_ws close to it (the last solve's for a load
    /// close to this one), if given.
    pub fn patches_for_force(
        &mut self,
        vertical_force: f64,
        near: Option<f64>,
    ) -> Result<NonHertzianContact, ProfileError> {
        let near = near.map(|vertical| Root { vertical, slope: None });
        let vertical =
            self.vertical_for_force(vertical_force, near, 1e-12, |pose, vertical| Ok(pose.carried(vertical)))?.vertical;
        if vertical_force <= 0.0 {
            return Ok(NonHertzianContact { vertical, patches: Vec::new(), switching: SwitchingFunctions::default() });
        }
        let strips = self.strips(self.source.reach_for(vertical - self.source.touch()));
        let loaded = strips.at(vertical);
        let (patches, regions) = loaded.patches(true)?;
        Ok(NonHertzianContact { vertical, patches, switching: loaded.switching_functions(&regions) })
    }

    /// z_ws where `carried(z_ws)`, the vertical force the patches at z_ws carry (the normal
    /// forces' share alone, or with the creep forces': the wheel's balance), meets F_z within
    /// `tolerance` of it (the frictionless problem's 1e-12, the wheel's balance's
    /// [`crate::wheel::BALANCE_TOLERANCE`]), the search started from `start` if given; the touch
    /// for F_z ≤ 0 (lift-off). Where `carried` jumps across F_z (a strip entering a narrow flange
    /// patch moves the creep forces' share), the bracket closes on the jump and the side nearer
    /// to F_z is the answer. Every z_ws returned is one `carried` was evaluated at, but the touch;
    /// its slope is the residual's between the last two z_ws evaluated (`start`'s where fewer
    /// were): the next search's, at a pose and load close to this one's.
    pub(crate) fn vertical_for_force<E: From<ProfileError>>(
        &mut self,
        vertical_force: f64,
        start: Option<Root>,
        tolerance: f64,
        mut carried: impl FnMut(&mut Self, f64) -> Result<f64, E>,
    ) -> Result<Root, E> {
        if !vertical_force.is_finite() {
            return Err(ProfileError::whole(format!("vertical_force = {vertical_force} must be finite")).into());
        }
        let touch = self.source.touch();
        let hint = start.and_then(|start| start.slope).and_then(rising);
        if vertical_force <= 0.0 {
            return Ok(Root { vertical: touch, slope: hint });
        }
        // The residual on the scale of the force's 2/3 power, r(z) = carried(z)^(2/3) − F_z^(2/3),
        // which grows with z_ws: a patch's force grows about as its approach's 3/2 power (Hertz,
        // Johnson 1985, eq. 4.23; KP's strips sum such terms), so r is nearly linear in z_ws and
        // the secant lines below nearly meet its root; its slope does not depend on F_z (on a
        // Hertz patch it is that of the constant F^(2/3)/δ), so that a search at a new load
        // starts from the last one's.
        let target = vertical_force.powf(2.0 / 3.0);
        let residual = |carried: f64| carried.powf(2.0 / 3.0) - target;
        let met = |carried: f64| (carried - vertical_force).abs() <= tolerance * vertical_force;
        let root = |vertical: f64, (z_a, f_a): (f64, f64), (z_b, f_b): (f64, f64)| Root {
            vertical,
            slope: rising((f_b - f_a) / (z_b - z_a)),
        };
        // From `start` (or 10 µm into the rail from the touch), secant steps first: the first
        // along the slope given (the last search's), else along the line through the touch (r =
        // −F_z^(2/3) there), then along the line through the last two points, so that a solve
        // started from the last step's z_ws meets the force in a few evaluations. They go on
        // while each at least halves |r|; one that passes the root brackets it.
        let start = start
            .map(|start| start.vertical)
            .filter(|&z| z > touch && z - touch <= MAX_PENETRATION)
            .unwrap_or(touch + 1e-5);
        let at_start = carried(self, start)?;
        if met(at_start) {
            return Ok(Root { vertical: start, slope: hint });
        }
        let (mut z, mut at_z, mut f) = (start, at_start, residual(at_start));
        let (mut before, mut f_before) = (touch, -target);
        let mut secant_steps = 0;
        // Once the secant steps end (their limit, a step out of range, one that did not halve
        // |r|): a bracket from z, first to the root of the line through the touch and z, half as
        // far again so that it passes the root, then on with doubled steps; the touch bounds it
        // below.
        let mut step: Option<f64> = None;
        let ((mut low, mut high, mut f_low, mut f_high), mut previous, mut last) = loop {
            let secant = match hint.filter(|_| secant_steps == 0) {
                Some(slope) => z - f / slope,
                None => z - f * (z - before) / (f - f_before),
            };
            let next = if step.is_none()
                && secant_steps < SECANT_STEPS
                && secant > touch
                && secant <= touch + MAX_PENETRATION
                && secant != z
            {
                secant_steps += 1;
                secant
            } else {
                let size = step.map_or_else(
                    || {
                        if at_z > 0.0 {
                            1.5 * (z - touch) * ((vertical_force / at_z).powf(2.0 / 3.0) - 1.0).abs()
                        } else {
                            z - touch
                        }
                    },
                    |last| 2.0 * last,
                );
                step = Some(size);
                let next = if f < 0.0 { (z + size).min(touch + MAX_PENETRATION) } else { (z - size).max(touch) };
                if next == z {
                    return Err(ProfileError::whole(format!(
                        "vertical_force = {vertical_force} N is not carried within {MAX_PENETRATION} m of penetration"
                    ))
                    .into());
                }
                next
            };
            let at_next = carried(self, next)?;
            let f_next = residual(at_next);
            if met(at_next) {
                return Ok(root(next, (z, f), (next, f_next)));
            }
            if (f_next >= 0.0) != (f >= 0.0) {
                let bracket = if f < 0.0 { (z, next, f, f_next) } else { (next, z, f_next, f) };
                break (bracket, (z, f), (next, f_next));
            }
            let converging = f_next.abs() <= 0.5 * f.abs();
            if !converging {
                secant_steps = SECANT_STEPS; // on by bracketing
            }
            (before, f_before, z, at_z, f) = (z, f, next, at_next, f_next);
        };
        // Inside the bracket: the secant through the last two points where it falls inside the
        // bracket and steps at most half as far as the step before it (near a smooth root it
        // converges as the secant steps before the bracket did); else the bracket's midpoint,
        // which a jump of `carried` cannot stall; until the force is met or the bracket can be
        // halved no more. (Regula falsi's Illinois variant in place of the midpoint took as many
        // evaluations on the counted cases and more on a jump, 54 against 50.)
        for _ in 0..200 {
            let ((z_previous, f_previous), (z_last, f_last)) = (previous, last);
            let secant = z_last - f_last * (z_last - z_previous) / (f_last - f_previous);
            let z = if secant > low && secant < high && (secant - z_last).abs() <= 0.5 * (z_last - z_previous).abs() {
                secant
            } else {
                0.5 * (low + high)
            };
            if z <= low || z >= high {
                break;
            }
            let at_z = carried(self, z)?;
            let f = residual(at_z);
            if met(at_z) {
                return Ok(root(z, last, (z, f)));
            }
            if f < 0.0 {
                (low, f_low) = (z, f);
            } else {
                (high, f_high) = (z, f);
            }
            (previous, last) = (last, (z, f));
        }
        let vertical = if f_high.abs() < f_low.abs() { high } else { low };
        Ok(root(vertical, previous, last))
    }
}

#[cfg(test)]
mod tests {
    use super::{
        patch_of_each, segment_area, NonHertzianPose, PressureMoments, Root, StripGeometry, Strips, JOIN_DISTANCE,
        MAX_PENETRATION, REFERENCE_BAND, VIRTUAL_PENETRATION_SCALE,
    };
    use crate::geometry::{ProfileError, WheelOnRail, WheelSide, WheelsetPosition};
    use std::f64::consts::PI;

    /// The width of [`synthetic`]'s strips \[m\].
    const WIDTH: f64 = 1e-4;

    /// A cut made by hand (right side): strip j at wheel y and surface position j·[`WIDTH`],
    /// [`WIDTH`] wide, rolling radius 0.46 m, the rail level (normal vertical), its undeformed gap
    /// `gaps[j]` (+∞: off a profile), its reference depth the lowest gap of all (every strip lies
    /// within [`super::REFERENCE_REACH`] of every other).
    fn synthetic<'a>(wheel: &'a WheelOnRail, gaps: &[f64]) -> Strips<'a> {
        let lowest = gaps.iter().copied().fold(f64::INFINITY, f64::min);
        let strips = gaps
            .iter()
            .enumerate()
            .map(|(j, &gap)| {
                let at = j as f64 * WIDTH;
                StripGeometry {
                    wheel_lateral: at,
                    gap,
                    reference_gap: lowest,
                    arc: at,
                    width: WIDTH,
                    rolling_radius: 0.46,
                    track_lateral: at,
                    rail_lateral: at,
                    sin_cos: (0.0, 1.0),
                }
            })
            .collect();
        Strips { wheel, right: WheelsetPosition::default(), strips, reach: 1.0 }
    }

    /// A region that reaches the end of the cut, or of a profile (the next strip off it), ends
    /// half its last strip's width beyond that strip's centre, at the strip's own L (module doc,
    /// 6): on a flat gap, where every strip's L is the same, the area is 2 L n w exactly and the
    /// line load is even over n w, so a/b = σ_x/σ_s = (L/2)/(n w/√12). (No pose of the
    /// profiles reaches this: the cut grows until the gap is out of reach.)
    #[test]
    fn a_region_at_the_end_of_the_cut_ends_half_a_strip_beyond_it() {
        let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
        let vertical = 20e-6;
        let half_length = (2.0 * 0.46 * VIRTUAL_PENETRATION_SCALE * vertical).sqrt();
        let count = 12;
        let flat = vec![0.0; count];
        let off_both_ends: Vec<f64> =
            [f64::INFINITY].into_iter().chain(flat.iter().copied()).chain([f64::INFINITY]).collect();
        for gaps in [flat, off_both_ends] {
            let cut = synthetic(&placed, &gaps);
            let loaded = cut.at(vertical);
            let regions = loaded.regions().regions;
            assert_eq!(regions.len(), 1, "{gaps:?}");
            let region = regions[0];
            assert_eq!(region.end - region.first, count, "{gaps:?}");
            let mut moments = PressureMoments::default();
            let area = loaded.area_and_moments(&region, 0.0, &mut moments);
            let span = count as f64 * WIDTH;
            assert!((area / (2.0 * half_length * span) - 1.0).abs() < 1e-12, "area {area}, {gaps:?}");
            let expected = (half_length / 2.0) / (span / 12f64.sqrt());
            let ratio = moments.spread_ratio();
            assert!((ratio / expected - 1.0).abs() < 1e-12, "a/b {ratio} against {expected}, {gaps:?}");
        }
    }

    /// A region of a patch that the others' pressure would lift (its scale solved ≤ 0) is left
    /// out, and the rest are as if it were not there: a light region 0.2 mm beside a loaded
    /// flat one (its real approach half the loaded one's, where the loaded one's pressure sinks
    /// the surface further) is dropped, the loaded one keeps the scale it has alone, and no join
    /// is left for the dropped one. (No pose of the profiles lifts a region since regions of
    /// different patches stopped pressing on each other: this path is defensive.)
    #[test]
    fn a_region_the_others_lift_is_left_out() {
        let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
        let vertical = 20e-6;
        let far = 1e-3;
        let loaded_alone: Vec<f64> = [0.0; 20].into_iter().chain([far; 5]).collect();
        let mut with_light = loaded_alone.clone();
        with_light[22] = 0.5 * vertical;
        with_light[23] = 0.5 * vertical;
        let alone = synthetic(&placed, &loaded_alone);
        let alone = alone.at(vertical).regions();
        let both = synthetic(&placed, &with_light);
        let both = both.at(vertical);
        // Both regions are in contact and one patch: the light one's virtual penetration is > 0
        // and their interpenetrations 0.2 mm apart, within JOIN_DISTANCE.
        assert!(both.virtual_penetration(22) > 0.0 && both.virtual_penetration(21) < 0.0);
        let (loaded_end, light_start) = (both.interpenetration_extent(0, 20).1, both.interpenetration_extent(22, 24).0);
        assert!((light_start - loaded_end - 2.0 * WIDTH).abs() < 1e-15 && 2.0 * WIDTH < JOIN_DISTANCE);
        let regions = both.regions();
        assert_eq!(alone.regions.len(), 1);
        assert_eq!(regions.regions.len(), 1, "the light region is lifted and left out");
        let (kept, reference) = (regions.regions[0], alone.regions[0]);
        assert_eq!((kept.first, kept.end), (0, 20));
        assert_eq!(kept.scale, reference.scale, "the loaded region's scale as it is alone");
        assert!(regions.joins.is_empty(), "no join for the region left out: {:?}", regions.joins);
    }

    /// z_ws carrying `force` within 1e-10 (the wheel's balance tolerance) with its slope, started
    /// from `start`, and how many times the carried force was evaluated.
    fn counted_solve(pose: &mut NonHertzianPose, force: f64, start: Option<Root>) -> (Root, usize) {
        let (root, evaluations) = counted_search(pose, force, start, |pose, z| {
            // (The wheel's rounds refuse a z_ws deeper than this: `strips_at`.)
            assert!(z - pose.touch() <= MAX_PENETRATION, "evaluated at {z}, deeper than MAX_PENETRATION");
            pose.carried(z)
        });
        assert!((pose.carried(root.vertical) - force).abs() <= 1e-10 * force);
        (root, evaluations)
    }

    /// The root search for `force` within 1e-10 on the carried force `carried`, started from
    /// `start`, and how many times `carried` was evaluated.
    fn counted_search(
        pose: &mut NonHertzianPose,
        force: f64,
        start: Option<Root>,
        mut carried: impl FnMut(&mut NonHertzianPose, f64) -> f64,
    ) -> (Root, usize) {
        let mut evaluations = 0;
        let root = pose
            .vertical_for_force::<ProfileError>(force, start, 1e-10, |pose, z| {
                evaluations += 1;
                Ok(carried(pose, z))
            })
            .unwrap();
        (root, evaluations)
    }

    /// The vertical balance's root search meets the force in few evaluations of the carried
    /// force, counted (deterministic): on A-2.2's right wheel at y_ws = 0, 2, 5, 7 mm, a cold
    /// solve of 10 kN, then from its z_ws 10.1, 10.5 and 60 kN: 78 evaluations for the 16 solves
    /// (89 with regula falsi alone inside the bracket, 104 with the bracketing alone), each
    /// meeting 1e-10 of the force.
    #[test]
    fn the_vertical_balance_meets_the_force_in_few_evaluations() {
        let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
        let mut total = 0;
        for lateral in [0.0, 2e-3, 5e-3, 7e-3] {
            let mut pose = placed.non_hertzian_pose(&WheelsetPosition { lateral, ..Default::default() }).unwrap();
            let (first, cold) = counted_solve(&mut pose, 10e3, None);
            total += cold;
            for force in [10.1e3, 10.5e3, 60e3] {
                total += counted_solve(&mut pose, force, Some(Root { slope: None, ..first })).1;
            }
        }
        assert!(total <= 78, "{total} evaluations for 16 solves, 78 when this test was written");
    }

    /// A search started at the last one's depth below the touch, the pose moved by 10 µm (a
    /// wheel step's): along the last search's slope it needs fewer evaluations than along the
    /// line through the touch, and finds the same z_ws. At y_ws = 0, 2, 5, 7 mm, 10 kN: 15
    /// evaluations against 17 when this test was written.
    #[test]
    fn the_last_searchs_slope_starts_the_next_one() {
        let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
        let pose_at =
            |lateral: f64| placed.non_hertzian_pose(&WheelsetPosition { lateral, ..Default::default() }).unwrap();
        let (mut along_slope, mut along_touch) = (0, 0);
        for lateral in [0.0, 2e-3, 5e-3, 7e-3] {
            let mut pose = pose_at(lateral);
            let (last, _) = counted_solve(&mut pose, 10e3, None);
            let depth = last.vertical - pose.touch();
            assert!(last.slope.is_some_and(|slope| slope > 0.0), "{last:?}");
            let mut moved = pose_at(lateral + 1e-5);
            let vertical = moved.touch() + depth;
            let (with_slope, count) = counted_solve(&mut moved, 10e3, Some(Root { vertical, ..last }));
            along_slope += count;
            let (without, count) = counted_solve(&mut moved, 10e3, Some(Root { vertical, slope: None }));
            along_touch += count;
            assert!((with_slope.vertical - without.vertical).abs() < 1e-12, "{with_slope:?} {without:?}");
        }
        assert!(along_slope < along_touch, "{along_slope} evaluations along the slope, {along_touch} without");
        // A slope that does not rise (0, negative, not finite) is not used, and a start out of
        // range (above the touch, deeper than MAX_PENETRATION) not either: the search is the one
        // without them, evaluation for evaluation.
        let mut pose = pose_at(2e-3);
        let (cold, cold_count) = counted_solve(&mut pose, 10e3, None);
        let touch = pose.touch();
        // A start 2 µm off the root, which the slope's first step would take.
        let vertical = cold.vertical + 2e-6;
        let (plain, plain_count) = counted_solve(&mut pose, 10e3, Some(Root { vertical, slope: None }));
        assert!(plain_count > 1);
        for slope in [0.0, -1.0, f64::INFINITY, f64::NAN] {
            let (root, count) = counted_solve(&mut pose, 10e3, Some(Root { vertical, slope: Some(slope) }));
            assert_eq!((root.vertical, count), (plain.vertical, plain_count), "slope {slope}");
        }
        // (Along a rising slope, the search differs: it is taken.)
        let along = counted_solve(&mut pose, 10e3, Some(Root { vertical, slope: cold.slope }));
        assert_ne!((along.0.vertical, along.1), (plain.vertical, plain_count));
        for vertical in [touch - 1e-6, touch, touch + MAX_PENETRATION * 1.01] {
            let (root, count) = counted_solve(&mut pose, 10e3, Some(Root { vertical, slope: None }));
            assert_eq!((root.vertical, count), (cold.vertical, cold_count), "start {vertical}");
        }
        assert!(along_slope <= 15, "{along_slope} evaluations, 15 when this test was written");
    }

    /// Where the carried force jumps across F_z the search closes its bracket on the jump and
    /// answers the side that carries F_z more closely; where the residual is far from linear
    /// (a force growing as the depth's cube, r = d² − d₀² instead of ∝ d) it still meets the
    /// force. Synthetic forces of the depth d below the touch (Hertz's F ∝ d^1.5 with a step of
    /// 30 % or 35 % of F_z at d = 20 µm, F_z inside the step, nearer its lower or its upper
    /// side): counted evaluations, 50 and 9 when this test was written.
    #[test]
    fn the_search_closes_on_a_jump_and_meets_a_curved_residual() {
        let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
        let mut pose = placed.non_hertzian_pose(&WheelsetPosition::default()).unwrap();
        let touch = pose.touch();
        let (force, jump_at) = (10e3, touch + 20e-6);
        let hertz = |z: f64| force * ((z - touch).max(0.0) / 20e-6).powf(1.5);
        let stepped = |z: f64| if z < jump_at { 0.9 * hertz(z) } else { 0.9 * hertz(z) + 0.3 * force };
        let (root, evaluations) = counted_search(&mut pose, force, None, |_, z| stepped(z));
        // Below the step 0.9 F_z is carried, above it 1.2 F_z: the lower side is nearer.
        assert!(root.vertical < jump_at && jump_at - root.vertical < 1e-15, "{root:?} against {jump_at}");
        assert!(evaluations <= 50, "{evaluations} evaluations, 50 when this test was written");
        // Below it 0.7 F_z, above it 1.05 F_z: the upper side.
        let upper = |z: f64| if z < jump_at { 0.7 * hertz(z) } else { 0.7 * hertz(z) + 0.35 * force };
        let (root, _) = counted_search(&mut pose, force, None, |_, z| upper(z));
        assert!(root.vertical >= jump_at && root.vertical - jump_at < 1e-15, "{root:?} against {jump_at}");
        let cubic = |z: f64| force * ((z - touch).max(0.0) / 20e-6).powi(3);
        let (root, evaluations) = counted_search(&mut pose, force, None, |_, z| cubic(z));
        assert!((cubic(root.vertical) / force - 1.0).abs() <= 1e-10, "{root:?}");
        assert!(evaluations <= 9, "{evaluations} evaluations, 9 when this test was written");
    }

    /// ∫ 2 √max(q, 0) ds over a segment with q linear between its ends, against the midpoint
    /// rule on 10⁶ parts: both ends in contact, one (either), none; and continuously
    /// differentiable where an end's q passes 0 (the one-sided slopes there agree).
    #[test]
    fn a_segments_area_is_its_integral() {
        let numeric = |from: f64, to: f64, length: f64| {
            let n = 1_000_000;
            let h = length / f64::from(n);
            (0..n)
                .map(|i| {
                    let q = from + (to - from) * (f64::from(i) + 0.5) / f64::from(n);
                    2.0 * q.max(0.0).sqrt() * h
                })
                .sum::<f64>()
        };
        // An end: q and its root, 0 out of contact (as a strip's L and its half-length).
        let end = |q: f64| (q, if q > 0.0 { q.sqrt() } else { 0.0 });
        for (from, to) in [(4e-6, 1e-6), (1e-6, 4e-6), (9e-6, 9e-6), (4e-6, -2e-6), (-2e-6, 4e-6), (-1e-6, -3e-6)] {
            let (exact, reference) = (segment_area(end(from), end(to), 1e-4), numeric(from, to, 1e-4));
            assert!(
                (exact - reference).abs() <= 1e-7 * reference.max(1e-12),
                "{from} → {to}: {exact} against {reference}"
            );
        }
        // One-sided slopes at q = 0 (the slope above approaches it as √q: within 1e-4 at 1e-14).
        let at_zero = segment_area(end(4e-6), end(0.0), 1e-4);
        let below = (at_zero - segment_area(end(4e-6), end(-1e-14), 1e-4)) / 1e-14;
        let above = (segment_area(end(4e-6), end(1e-14), 1e-4) - at_zero) / 1e-14;
        assert!((below / above - 1.0).abs() < 1e-3, "{below} against {above}");
    }

    /// A stretch's moments are the integrals of its linear q over the part where q > 0: against
    /// the midpoint rule on 10⁶ parts, both ends in contact (either way along the surface),
    /// one, and with a region's scale k: f = k (π/2) q, f L²/4 = k (π/8) q².
    #[test]
    fn a_stretchs_moments_are_its_integrals() {
        let numeric = |(at, q): (f64, f64), (to, q_to): (f64, f64)| {
            let n = 1_000_000;
            let h = (to - at) / f64::from(n);
            let mut sums = [0.0; 4];
            for i in 0..n {
                let t = (f64::from(i) + 0.5) / f64::from(n);
                let (s, q) = (at + (to - at) * t, (q + (q_to - q) * t).max(0.0));
                for (sum, value) in sums.iter_mut().zip([q, q * s, q * s * s, q * q]) {
                    *sum += value * h.abs();
                }
            }
            sums
        };
        for (from, to) in [
            ((3e-4, 4e-6), (5e-4, 1e-6)),
            ((-2e-4, 1e-6), (-4e-4, 9e-6)),
            ((1e-3, 4e-6), (1.2e-3, -2e-6)),
            ((1e-3, 4e-6), (0.8e-3, -6e-6)),
        ] {
            let mut moments = PressureMoments::default();
            moments.add(from, to);
            let exact = [moments.force, moments.first, moments.second, moments.along];
            for (k, (value, reference)) in exact.iter().zip(numeric(from, to)).enumerate() {
                assert!(
                    (value - reference).abs() <= 1e-9 * reference.abs(),
                    "{from:?} → {to:?}, moment {k}: {value} against {reference}"
                );
            }
            let mut scaled = PressureMoments::default();
            scaled.add_scaled(&moments, 3e9);
            let line_load = 0.5 * PI * 3e9;
            let scaled = [scaled.force, scaled.first, scaled.second, scaled.along];
            let expected =
                [line_load * exact[0], line_load * exact[1], line_load * exact[2], PI / 8.0 * 3e9 * exact[3]];
            for (value, expected) in scaled.iter().zip(expected) {
                assert!((value / expected - 1.0).abs() < 1e-15, "{value} against {expected}");
            }
        }
        // Added twice, the moments double (they accumulate).
        let mut twice = PressureMoments::default();
        twice.add((0.0, 2e-6), (1e-4, 3e-6));
        let once = twice.force;
        twice.add((0.0, 2e-6), (1e-4, 3e-6));
        assert_eq!(twice.force, 2.0 * once);
    }

    /// Hertz's pressure over an ellipse (a = 3 mm along x, b = 2 mm across, centred at s = 5 mm:
    /// L² = a² (1 − ((s − 5 mm)/b)²), as KP's strips of a quadratic gap) in 400 stretches: the
    /// spreads' ratio σ_x/σ_s is a/b (σ² = a²/5 and b²/5: ∫(1 − u²)² du / ∫(1 − u²) du = 4/5
    /// along, ∫ u² (1 − u²) du / ∫(1 − u²) du = 1/5 across), within the stretches' linear q
    /// (2e-5), whatever the region's scale.
    #[test]
    fn hertzs_pressure_spreads_as_its_ellipse() {
        let (a, b, centre) = (3e-3, 2e-3, 5e-3);
        let node = |i: i32| {
            let s = centre - b + 2.0 * b * f64::from(i) / 400.0;
            (s, a * a * (1.0 - ((s - centre) / b).powi(2)))
        };
        let mut of_squares = PressureMoments::default();
        for i in 0..400 {
            of_squares.add(node(i), node(i + 1));
        }
        for scale in [7e9, 3e11] {
            let mut moments = PressureMoments::default();
            moments.add_scaled(&of_squares, scale);
            assert!((moments.spread_ratio() / (a / b) - 1.0).abs() < 2e-5, "{}", moments.spread_ratio());
        }
    }

    /// Regions are numbered by patch from their joins: a join ≤ 0 keeps the next region in the
    /// patch, one > 0 starts the next patch.
    #[test]
    fn regions_are_grouped_by_their_joins() {
        assert_eq!(patch_of_each(&[]), vec![0]);
        assert_eq!(patch_of_each(&[-1e-3, 2e-3, 0.0, 5e-3]), vec![0, 0, 1, 1, 2]);
    }

    /// The reference point (module doc, 4) on A-2.2's right wheel at 10 kN: on the tread's single
    /// peak of virtual penetration (y_ws = 3 mm) within 0.1 strip widths of the vertex of the
    /// parabola through the deepest strip and its neighbours (0.09 measured: the peak is no
    /// parabola over the band's strips), and between the region's two
    /// highest maxima where they nearly tie (the centred wheelset, y_ws = 0.2143 mm), moving
    /// continuously from one towards the other as y_ws passes the tie; its approach the real
    /// one interpolated linearly between the strips around it.
    #[test]
    fn the_reference_point_is_the_peak_or_between_two_tied_maxima() {
        let placed = WheelOnRail::manchester_benchmark(WheelSide::Right).with_strip_table();
        let reference = |lateral: f64| {
            let position = WheelsetPosition { lateral, ..Default::default() };
            let vertical = placed.non_hertzian_patches_for_force(10e3, &position).unwrap().vertical;
            let mut pose = placed.non_hertzian_pose(&position).unwrap();
            let strips = pose.strips_at(vertical).unwrap().at(vertical);
            let regions = strips.regions().regions;
            assert_eq!(regions.len(), 1, "y_ws {lateral}");
            let region = regions[0];
            let v = strips.penetration.clone();
            let arcs: Vec<f64> = strips.strips.iter().map(|s| s.arc).collect();
            // The real approach there, (z_ws − g) cos γ, linear between the strips around it.
            let after = arcs.iter().position(|&arc| arc > region.reference_arc).unwrap();
            let approach = |j: usize| (vertical - strips.strips[j].gap) * strips.strips[j].sin_cos.1;
            let t = (region.reference_arc - arcs[after - 1]) / (arcs[after] - arcs[after - 1]);
            let expected = (1.0 - t) * approach(after - 1) + t * approach(after);
            assert!((region.approach - expected).abs() < 1e-12 * expected, "{} against {expected}", region.approach);
            (region.reference_arc, region.first, region.end, region.deepest, v, arcs)
        };
        let (arc, _, _, deepest, v, arcs) = reference(3e-3);
        let (before, peak, after) = (v[deepest - 1], v[deepest], v[deepest + 1]);
        let offset = 0.5 * (before - after) / (before - 2.0 * peak + after);
        let vertex = arcs[deepest] + offset * (arcs[deepest + 1] - arcs[deepest - 1]) / 2.0;
        let width = (arcs[deepest + 1] - arcs[deepest - 1]) / 2.0;
        assert!((arc - vertex).abs() < 0.1 * width, "{arc} against the vertex {vertex}");
        // Two maxima near the tie: the reference between them, off both by more than a strip.
        let (arc, first, end, _, v, arcs) = reference(0.2143e-3);
        let maxima: Vec<usize> = (first + 1..end - 1).filter(|&j| v[j] > v[j - 1] && v[j] >= v[j + 1]).collect();
        let mut highest = maxima.clone();
        highest.sort_by(|&a, &b| v[b].total_cmp(&v[a]));
        let (a, b) = (arcs[highest[0]].min(arcs[highest[1]]), arcs[highest[0]].max(arcs[highest[1]]));
        assert!(v[highest[1]] > (1.0 - REFERENCE_BAND) * v[highest[0]], "{maxima:?}");
        assert!(arc > a + 1e-4 && arc < b - 1e-4, "{arc} not between the maxima at {a} and {b}");
        // Across the tie it moves continuously, not from one maximum to the other: ten times
        // less over a ten times shorter step of y_ws.
        let moved = |step: f64| (reference(0.2143e-3 + step).0 - reference(0.2143e-3 - step).0).abs();
        let (long, short) = (moved(1e-9), moved(1e-10));
        assert!(long < 1e-3 * (b - a) && short < 0.2 * long, "{long} over 2 nm, {short} over 0.2 nm");
    }
}
