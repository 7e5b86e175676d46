//! The normal problem of one wheel from its contact candidates (the gap's local minima, found
//! once per lateral position, roll and yaw by [`WheelOnRail::candidates`]): which candidates the
//! wheel penetrates at a vertical position, which of them form one patch, and each patch's
//! normal force and Hertz ellipse — or the vertical position that carries a prescribed force.
//!
//! The wheelset's height shifts the gap uniformly, so a candidate with gap g_i (at z_ws = 0) is
//! in contact below z_ws = g_i, penetrating along its normal by (z_ws − g_i) cos δ. Two
//! neighbouring candidates whose interpenetration regions join — the gap between them stays
//! below z_ws, i.e. z_ws is above the highest gap sampled between them — are one patch, the
//! deeper one kept. Hertz's Q ∝ δ_n^{3/2} and a, b, p₀ ∝ Q^{1/3} scale each candidate's
//! solution under 1 N to any load, so the normal problem costs no elliptic integral.
//!
//! [`WheelOnRail::candidates`]: super::contact::WheelOnRail::candidates

use super::patch::{ContactPatch, ContactPoint, WheelSide};
use super::profile_file::ProfileError;
use super::switching::SwitchingFunctions;
use std::cell::{Cell, OnceCell};

use crate::hertz::table::unit_solution;
use crate::hertz::{HertzContact, RelativeCurvature};

/// The deepest the wheel may be pushed into the rail \[m\], at a prescribed position or to
/// carry a prescribed force: real contacts penetrate by micrometres to a tenth of a millimetre.
pub const MAX_PENETRATION: f64 = 0.1;

/// A candidate contact point (right side) with Hertz's solution under 1 N at its curvatures,
/// solved when the candidate is first loaded (most candidates never are), or why Hertz does not
/// apply there (an error only once the candidate is loaded).
#[derive(Debug, Clone)]
pub(super) struct Candidate {
    pub(super) point: ContactPoint,
    contact_modulus: f64,
    unit: OnceCell<Result<HertzContact, ProfileError>>,
}

impl Candidate {
    pub(super) fn new(point: ContactPoint, contact_modulus: f64) -> Self {
        Self { point, contact_modulus, unit: OnceCell::new() }
    }

    /// Hertz: δ ∝ Q^{2/3}, a, b, p₀ ∝ Q^{1/3}; the solution under 1 N (from the table of
    /// `crate::hertz::table`) scales to any load.
    fn unit(&self) -> Result<&HertzContact, ProfileError> {
        self.unit
            .get_or_init(|| {
                RelativeCurvature::new(self.point.curvature_rolling, self.point.curvature_lateral)
                    .and_then(|curvature| unit_solution(&curvature, self.contact_modulus))
                    .map_err(|e| {
                        ProfileError::whole(format!(
                            "Hertz does not apply at the contact point y = {:.4} mm on the rail: {e}",
                            self.point.rail_lateral * 1e3
                        ))
                    })
            })
            .as_ref()
            .map_err(Clone::clone)
    }
}

/// One wheel's contact candidates at a lateral position, roll and yaw.
///
/// Searched once, solved at any height or load: the S1002 wheel on UIC60 with the wheelset
/// centred touches at z_ws = `touch()` and carries, by Hertz, Q ∝ δ^{3/2} of its penetration
/// δ = (z_ws − touch)·cos γ along the normal:
///
/// ```
/// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
///
/// let placed = WheelOnRail::manchester_benchmark(WheelSide::Left);
/// let candidates = placed.candidates(&WheelsetPosition { lateral: -3e-3, ..WheelsetPosition::default() }).unwrap();
/// assert_eq!(candidates.points(), placed.contact_points(&WheelsetPosition { lateral: -3e-3, ..Default::default() }).unwrap());
/// let touch = candidates.touch();
/// assert!(candidates.patches_at(touch - 1e-6).unwrap().is_empty(), "above the touch: no contact");
/// let load = |depth: f64| candidates.patches_at(touch + depth).unwrap()[0].normal_force;
/// assert!((load(40e-6) / load(10e-6) - 8.0).abs() < 1e-9, "Hertz: four times deeper, eight times the load");
/// let (height, patches) = candidates.patches_for_force(10e3, |point| point.contact_angle.cos()).unwrap();
/// assert!(height > touch && (patches[0].normal_force * patches[0].point.contact_angle.cos() - 10e3).abs() < 1e-6);
/// // The left wheel mirrors the right: positions and contact angles change sign.
/// assert!(patches[0].point.rail_lateral > 0.0 && patches[0].point.contact_angle > 0.0);
/// ```
#[derive(Debug, Clone)]
pub struct ContactCandidates {
    side: WheelSide,
    /// Tread first (from the rail's field side to its gauge side), in the right side's frame.
    candidates: Vec<Candidate>,
    /// barriers[i]: the highest gap between candidates i and i + 1.
    barriers: Vec<f64>,
}

impl ContactCandidates {
    /// From the candidates and the barriers between neighbours in the order of increasing y.
    pub(super) fn new(side: WheelSide, mut candidates: Vec<Candidate>, mut barriers: Vec<f64>) -> Self {
        candidates.reverse();
        barriers.reverse();
        Self { side, candidates, barriers }
    }

    /// The candidate points on this side, tread first.
    pub fn points(&self) -> Vec<ContactPoint> {
        self.candidates.iter().map(|c| self.side.mirror_point(&c.point)).collect()
    }

    /// z_ws where the wheel first touches: the lowest gap.
    pub fn touch(&self) -> f64 {
        self.candidates.iter().map(|c| c.point.gap_at_zero).fold(f64::INFINITY, f64::min)
    }

    /// The switching functions at z_ws ([`SwitchingFunctions`]), tread first: per gap minimum its
    /// gap less z_ws (in contact below 0); per split between neighbouring minima the barrier
    /// between them less z_ws (they join below 0) and, joined, the lowest gap of their group on
    /// the split's field side less that on its gauge side (the patch sits at the field side's
    /// below 0). At the S1002 wheel's tread–flange transition on UIC60 (y_ws = 5 mm) its two
    /// interpenetrations join as the wheel sinks, where the first split's join function passes 0:
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition, SWITCHING_CONTACTS};
    ///
    /// let right = WheelOnRail::manchester_benchmark(WheelSide::Right);
    /// let candidates = right.candidates(&WheelsetPosition { lateral: 5e-3, ..Default::default() }).unwrap();
    /// let touch = candidates.touch();
    /// let barrier = candidates.switching_functions(touch).values()[SWITCHING_CONTACTS] + touch;
    /// let patches = |z: f64| candidates.patches_at(z).unwrap().len();
    /// assert_eq!((patches(barrier - 1e-9), patches(barrier + 1e-9)), (2, 1));
    /// assert!(candidates.switching_functions(barrier + 1e-9).values()[SWITCHING_CONTACTS] < 0.0);
    /// ```
    pub fn switching_functions(&self, vertical: f64) -> SwitchingFunctions {
        // In contact, and joined, as `for_each_patch` decides: the gap, or the barrier, below z_ws.
        SwitchingFunctions::new(
            self.candidates.len(),
            |k| self.candidates[k].point.gap_at_zero - vertical,
            |k| self.barriers[k] - vertical,
            |join| join < 0.0,
        )
    }

    /// The loaded patches at the wheelset's vertical position z_ws (module doc), tread first.
    /// A z_ws more than [`MAX_PENETRATION`] below the touch is refused: the wheel would be
    /// inside the rail, where no contact law holds (and Hertz's load, ∝ δ^{3/2}, overflows).
    pub fn patches_at(&self, vertical: f64) -> Result<Vec<ContactPatch>, ProfileError> {
        let depth = vertical - self.touch();
        // (NaN, from a NaN height, is refused too.)
        if !(..=MAX_PENETRATION).contains(&depth) {
            return Err(ProfileError::whole(format!(
                "wheelset_vertical_position = {vertical} m puts the wheel {depth:e} m into the rail (it touches at \
                 {} m): more than {MAX_PENETRATION} m of penetration is a wheel inside its rail, not a contact",
                self.touch()
            )));
        }
        self.patches_within_reach(vertical)
    }

    /// [`Self::patches_at`] at a z_ws known to be within [`MAX_PENETRATION`] of the touch.
    fn patches_within_reach(&self, vertical: f64) -> Result<Vec<ContactPatch>, ProfileError> {
        Ok(self.side.mirror_patches(self.right_patches(vertical)?))
    }

    fn right_patches(&self, vertical: f64) -> Result<Vec<ContactPatch>, ProfileError> {
        let mut patches = Vec::with_capacity(self.candidates.len());
        // The first refusal, as collecting the results would return it.
        let mut refusal = None;
        self.for_each_patch(vertical, |i| match loaded(&self.candidates[i], vertical) {
            Ok(patch) => patches.push(patch),
            Err(error) => {
                refusal.get_or_insert(error);
            }
        });
        refusal.map_or(Ok(patches), Err)
    }

    /// Calls `visit` with the index of each loaded candidate at z_ws, the deepest of each group
    /// whose interpenetrations join, tread first.
    fn for_each_patch(&self, vertical: f64, mut visit: impl FnMut(usize)) {
        let gap = |i: usize| self.candidates[i].point.gap_at_zero;
        let mut group: Option<usize> = None;
        // The highest barrier since the group's last member.
        let mut barrier = f64::MIN;
        for i in 0..self.candidates.len() {
            if gap(i) < vertical {
                match group {
                    Some(deepest) if barrier < vertical => {
                        if gap(i) < gap(deepest) {
                            group = Some(i);
                        }
                    }
                    Some(deepest) => {
                        visit(deepest);
                        group = Some(i);
                    }
                    None => group = Some(i),
                }
                barrier = f64::MIN;
            }
            if let Some(&next) = self.barriers.get(i) {
                barrier = barrier.max(next);
            }
        }
        if let Some(deepest) = group {
            visit(deepest);
        }
    }

    /// Prescribed vertical force on the wheel \[N\]: the wheelset's vertical position at which
    /// the patches carry it, Σ Q_i·s_i = F_z with `vertical_share` s_i the vertical force a patch
    /// carries per newton of normal force (cos δ alone; [`crate::wheel`] adds its
    /// tangential force's share; > 0), found by bisection; returns it with the patches. F_z ≤ 0
    /// is lift-off: no patch, the position where the wheel just touches.
    pub fn patches_for_force(
        &self,
        vertical_force: f64,
        vertical_share: impl Fn(&ContactPoint) -> f64,
    ) -> Result<(f64, Vec<ContactPatch>), ProfileError> {
        self.patches_for_force_near(vertical_force, vertical_share, None)
    }

    /// [`Self::patches_for_force`], its search started at `guess` (z_ws) if given: the rounds of
    /// the vertical balance change z_ws by little, and Newton's method from the last one
    /// converges in two or three steps instead of bracketing from the touch.
    pub(crate) fn patches_for_force_near(
        &self,
        vertical_force: f64,
        vertical_share: impl Fn(&ContactPoint) -> f64,
        guess: Option<f64>,
    ) -> Result<(f64, Vec<ContactPatch>), ProfileError> {
        if !vertical_force.is_finite() {
            return Err(ProfileError::whole(format!("vertical_force = {vertical_force} must be finite")));
        }
        let touch = self.touch();
        if vertical_force <= 0.0 {
            return Ok((touch, Vec::new()));
        }
        // Per candidate: its vertical share times Q/(z_ws − g)^{3/2} = (cos δ/δ₁)^{3/2}, so that
        // the carried force is Σ k_i (z_ws − g_i)^{3/2} over the patches; computed when the
        // candidate is first loaded.
        let factors: Vec<OnceCell<Result<f64, ProfileError>>> =
            self.candidates.iter().map(|_| OnceCell::new()).collect();
        let factor = |i: usize| -> Result<f64, ProfileError> {
            let candidate = &self.candidates[i];
            factors[i]
                .get_or_init(|| {
                    let share = vertical_share(&self.side.mirror_point(&candidate.point));
                    candidate.unit().map(|unit| {
                        let per_depth = candidate.point.contact_angle_sin_cos().1 / unit.approach;
                        share * per_depth * per_depth.sqrt()
                    })
                })
                .clone()
        };
        // The force carried at z_ws and its rate. The last z_ws's is remembered: Newton's method
        // starts at the bracket's end, which has just been evaluated.
        let last = Cell::new(None);
        let carried = |z: f64| -> Result<(f64, f64), ProfileError> {
            if let Some((at, carried)) = last.get() {
                if at == z {
                    return Ok(carried);
                }
            }
            let (mut force, mut rate, mut refusal) = (0.0, 0.0, None);
            self.for_each_patch(z, |i| match factor(i) {
                Ok(factor) => {
                    let depth = z - self.candidates[i].point.gap_at_zero;
                    force += factor * depth * depth.sqrt();
                    rate += 1.5 * factor * depth.sqrt();
                }
                Err(error) => refusal = Some(error),
            });
            let carried = refusal.map_or(Ok((force, rate)), Err)?;
            last.set(Some((z, carried)));
            Ok(carried)
        };
        // A bracket [low, high] of the root: from the guess, or from the touch, growing upwards
        // (carried(touch) = 0).
        let (mut low, mut high) = (touch, touch + 1e-5);
        if let Some(guess) = guess.filter(|&guess| guess > touch) {
            if carried(guess)?.0 < vertical_force {
                (low, high) = (guess, guess + 1e-3 * (guess - touch));
            } else {
                high = guess;
            }
        }
        while carried(high)?.0 < vertical_force {
            low = high;
            high = touch + 2.0 * (high - touch);
            // (NaN, without any candidate, stops here too.)
            if !(..=MAX_PENETRATION).contains(&(high - touch)) {
                // Each patch carries its vertical share of its normal force; on a steep flange
                // the creep forces' share can cancel it (Nadal's limit): the wheel climbs.
                return Err(ProfileError::whole(format!(
                    "flange climb (derailment): vertical_force = {vertical_force} N is not carried within \
                     {MAX_PENETRATION} m of penetration: at this position the creep forces lift the wheel at least \
                     as much as the normal forces carry it (Nadal's limit), or the wheel is off the rail head"
                )));
            }
        }
        // Newton's method inside the bracket, bisection where a step would leave it (joining
        // patches make the carried force jump); until the force is met to 1e-12, or the bracket
        // is 1e-13 m — or 1e-8 of the penetration where that is finer, so that a load of
        // millinewtons, a penetration of nanometres, is solved too — or can be halved no more.
        let mut z = high;
        loop {
            let (force, rate) = carried(z)?;
            if force < vertical_force {
                low = z;
            } else {
                high = z;
            }
            let middle = 0.5 * (low + high);
            let resolved = high - low <= (1e-8 * (high - touch)).min(1e-13) || middle <= low || middle >= high;
            if (force - vertical_force).abs() <= 1e-12 * vertical_force || resolved {
                break;
            }
            let newton = z - (force - vertical_force) / rate;
            z = if newton > low && newton < high { newton } else { middle };
        }
        // (The bracket lies within MAX_PENETRATION of the touch.)
        Ok((z, self.patches_within_reach(z)?))
    }
}

/// The candidate loaded at z_ws (module doc): Q = (δ_n/δ₁)^{3/2}, and a, b, p₀ scaled by
/// Q^{1/3} = (δ_n/δ₁)^{1/2} — a square root, not a cube root of Q.
fn loaded(candidate: &Candidate, vertical: f64) -> Result<ContactPatch, ProfileError> {
    let unit = candidate.unit()?;
    let point = candidate.point;
    let penetration = (vertical - point.gap_at_zero) * point.contact_angle_sin_cos().1;
    let relative = penetration / unit.approach;
    let scale = relative.sqrt();
    let normal_force = relative * scale;
    let ellipse = HertzContact {
        semi_axis_a: unit.semi_axis_a * scale,
        semi_axis_b: unit.semi_axis_b * scale,
        max_pressure: unit.max_pressure * scale,
        approach: penetration,
    };
    Ok(ContactPatch { point, penetration, normal_force, ellipse })
}
