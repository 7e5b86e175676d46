//! Switching functions of one wheel's patches: continuous functions of the pose whose signs
//! change exactly where the patches jump, so that an integrator can stop at the jump instead of
//! stepping across it (FMI 2.0 Model Exchange's event indicators, `fmu/src/model.rs`).
//!
//! The patches jump in three ways:
//!
//! - **Onset**: a contact comes into touch or lifts off, and the patches' numbering shifts (the
//!   first patch's outputs become another's; the forces themselves grow from 0). Hertz: a gap
//!   minimum's gap less z_ws; non-Hertzian: a region's deepest virtual penetration, negated
//!   (a region exists only while it is positive). Negative in contact.
//! - **Join**: two neighbouring contacts become one patch or part again. Hertz
//!   ([`super::ContactCandidates`]): two gap minima's interpenetrations join where the highest gap
//!   between them (the barrier b) falls below z_ws; the function is b − z_ws. Non-Hertzian
//!   ([`super::NonHertzianPose`]): two regions are one patch where their real interpenetrations
//!   lie within [`super::non_hertzian::JOIN_DISTANCE`] along the surface; the function is their
//!   distance less that (piecewise constant in z_ws, strip by strip, as the joining is).
//! - **Deepest**: a joined patch is placed at its deepest member (Hertz: the lowest gap minimum,
//!   whose ellipse it takes; non-Hertzian: the region of deepest virtual penetration, whose
//!   approach it reports). Where a patch's members on either side of a split tie, its deepest
//!   passes across the split; the function is the depth of the deepest on the field side less
//!   that on the gauge side (Hertz: their gaps; non-Hertzian: the negated virtual penetrations),
//!   negative while the field side holds it. Every change of the deepest, between any two
//!   members, crosses the splits between them.
//!
//! (A non-Hertzian region's reference point, which its pressure scale follows from, moves
//! continuously: `non_hertzian.rs`. It jumped between the region's two highest maxima of
//! virtual penetration where they tied, and had a switching function of its own until it was
//! made continuous.)
//!
//! The values: the onsets of contacts 0 … [`SWITCHING_CONTACTS`] − 1 counted from the field side
//! (tread first); then pair by pair (pair k is the split between contacts k and k + 1) its join
//! and deepest functions. A deepest function is defined
//! where its pair is joined; apart, and for contacts and pairs the wheel does not have, the
//! functions are [`NO_SWITCH`].
//!
//! They are continuous while the contacts along the profile stay the same. Where a gap minimum
//! appears or vanishes (a contact's onset, or none: a minimum appears at its barrier's height,
//! joined but not deepest), the contacts behind it are renumbered and their functions may change
//! sign without a jump (a spurious event, harmless to an integrator). A deepest function jumps
//! where its pair joins or parts, at the join function's own sign change.
//!
//! ```
//! use wheel_rail_contact::geometry::{SwitchingFunctions, NO_SWITCH, SWITCHING_FUNCTIONS};
//!
//! let lifted = SwitchingFunctions::default();
//! assert_eq!(lifted.values(), &[NO_SWITCH; SWITCHING_FUNCTIONS]);
//! ```

/// The contacts (gap minima, or regions) that get switching functions, field side first: S1002
/// on UIC60 has at most three gap minima in reach of a contact (tread, tread–flange transition,
/// flange root); the rest is room for worn profiles.
pub const SWITCHING_CONTACTS: usize = 5;

/// The splits between neighbouring contacts that get switching functions.
pub const SWITCHING_PAIRS: usize = SWITCHING_CONTACTS - 1;

/// The number of switching functions: an onset per contact, a join and a deepest function per
/// pair.
pub const SWITCHING_FUNCTIONS: usize = SWITCHING_CONTACTS + 2 * SWITCHING_PAIRS;

/// A switching function's value where it switches nothing \[m\]: apart pairs' deepest functions
/// and the contacts and pairs a wheel does not have; positive, as the onset of a contact out of
/// touch and the join function of parted contacts are.
pub const NO_SWITCH: f64 = 1.0;

/// One wheel's switching functions \[m\] (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SwitchingFunctions([f64; SWITCHING_FUNCTIONS]);

impl Default for SwitchingFunctions {
    /// No contact: nothing to switch.
    fn default() -> Self {
        Self([NO_SWITCH; SWITCHING_FUNCTIONS])
    }
}

impl SwitchingFunctions {
    /// From `contacts` contacts, numbered from the field side: contact k's depth (< 0 in
    /// contact, lower deeper) and the join function between contacts k and k + 1 (joined where
    /// `joined`). Beyond [`SWITCHING_CONTACTS`] they are left out. (Functions of the index
    /// rather than slices: a wheel step computes them without allocating.)
    pub(super) fn new(
        contacts: usize,
        depth: impl Fn(usize) -> f64,
        join: impl Fn(usize) -> f64,
        joined: impl Fn(f64) -> bool,
    ) -> Self {
        let mut values = [NO_SWITCH; SWITCHING_FUNCTIONS];
        let (onsets, pairs) = values.split_at_mut(SWITCHING_CONTACTS);
        for (k, onset) in onsets.iter_mut().take(contacts).enumerate() {
            *onset = depth(k);
        }
        let is_joined = |k: usize| joined(join(k));
        // The least depth of contacts `range`.
        let deepest = |range: std::ops::RangeInclusive<usize>| range.map(&depth).fold(f64::INFINITY, f64::min);
        for (k, pair) in pairs.chunks_exact_mut(2).take(contacts.saturating_sub(1)).enumerate() {
            pair[0] = join(k);
            if !is_joined(k) {
                continue;
            }
            // The joined group around the pair, contacts first..=last; its deepest on the field
            // side of the split less its deepest on the gauge side.
            let first = (0..k).rev().take_while(|&j| is_joined(j)).last().unwrap_or(k);
            let last = (k + 1..contacts - 1).take_while(|&j| is_joined(j)).last().map_or(k + 1, |j| j + 1);
            pair[1] = deepest(first..=k) - deepest(k + 1..=last);
        }
        Self(values)
    }

    /// The values: the contacts' onsets, then join and deepest pair by pair.
    pub fn values(&self) -> &[f64; SWITCHING_FUNCTIONS] {
        &self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const C: usize = SWITCHING_CONTACTS;

    /// The functions of contacts of these depths and joins (joined below 0).
    fn of(depths: &[f64], joins: &[f64]) -> SwitchingFunctions {
        SwitchingFunctions::new(depths.len(), |k| depths[k], |k| joins[k], |join| join < 0.0)
    }

    /// Three contacts joined into one patch: the deepest function of each split compares the
    /// deepest on either side within the group; a parted pair and the missing ones switch
    /// nothing; the onsets are the depths.
    #[test]
    fn the_deepest_function_compares_the_group_on_either_side() {
        // Contacts 0, 1, 2 joined (joins < 0), 2 and 3 apart.
        let depths = [-3.0, -1.0, -2.0, -5.0];
        let joins = [-0.5, -0.25, 0.75];
        let functions = of(&depths, &joins);
        let values = functions.values();
        assert_eq!(&values[..C], &[-3.0, -1.0, -2.0, -5.0, NO_SWITCH]);
        assert_eq!(&values[C..], &[-0.5, -1.0, -0.25, -1.0, 0.75, NO_SWITCH, NO_SWITCH, NO_SWITCH]);
        // The deepest moves from contact 0 to contact 2: both splits between them change sign.
        let depths = [-3.0, -1.0, -4.0, -5.0];
        let functions = of(&depths, &joins);
        assert_eq!(&functions.values()[C..C + 4], &[-0.5, 1.0, -0.25, 1.0]);
    }

    /// Hertz on S1002/UIC60 (right wheel, y_ws = 5 mm, two gap minima): each onset passes 0
    /// where its minimum comes into touch, the join where the two patches become one, and the
    /// deepest function, defined once joined, is the tread's gap less the flange's.
    #[test]
    fn the_hertz_functions_switch_where_the_patches_change() {
        use crate::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
        let wheel = WheelOnRail::manchester_benchmark(WheelSide::Right);
        let candidates = wheel.candidates(&WheelsetPosition { lateral: 5e-3, ..Default::default() }).unwrap();
        let at = |z: f64| *candidates.switching_functions(z).values();
        let count = |z: f64| candidates.patches_at(z).unwrap().len();
        let touch = candidates.touch();
        let [first, second] = [at(touch)[0] + touch, at(touch)[1] + touch];
        let barrier = at(touch)[C] + touch;
        assert!(first < barrier && second < barrier && (first == touch || second == touch));
        let onset = first.max(second);
        for (z, patches, signs) in [
            (onset - 1e-9, 1, [first > onset - 1e-9, second > onset - 1e-9, true]),
            (onset + 1e-9, 2, [false, false, true]),
            (barrier + 1e-9, 1, [false, false, false]),
        ] {
            let values = at(z);
            assert_eq!(count(z), patches, "z_ws = {z:e}");
            assert_eq!([values[0] > 0.0, values[1] > 0.0, values[C] > 0.0], signs, "z_ws = {z:e}: {values:?}");
        }
        let joined = at(barrier + 1e-9);
        assert!((joined[C + 1] - (first - second)).abs() < 1e-15, "{joined:?}");
        assert_eq!(at(onset + 1e-9)[C + 1], NO_SWITCH);
        assert_eq!(&joined[2..C], &[NO_SWITCH; C - 2]);
        assert_eq!(&joined[C + 2..], &[NO_SWITCH; SWITCHING_FUNCTIONS - C - 2]);
    }

    /// Non-Hertzian at the tread–flange transition (right wheel, y_ws = 5 mm, 10 kN): two
    /// regions, the tread's and the flange root's, whose real interpenetrations lie 6.1 mm apart,
    /// within JOIN_DISTANCE: one patch; the join function is that distance less 8 mm, and the
    /// deepest function the tread region's onset less the flange root's.
    #[test]
    fn the_non_hertzian_functions_of_two_joined_regions() {
        use crate::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
        let wheel = WheelOnRail::manchester_benchmark(WheelSide::Right).with_strip_table();
        let position = WheelsetPosition { lateral: 5e-3, ..Default::default() };
        let contact = wheel.non_hertzian_patches_for_force(10e3, &position).unwrap();
        let values = contact.switching.values();
        assert_eq!(contact.patches.len(), 1, "{values:?}");
        assert!(values[0] < 0.0 && values[1] < 0.0 && values[2] == NO_SWITCH, "{values:?}");
        assert!(values[C] < 0.0 && values[C] > -8e-3 && values[C + 1] == values[0] - values[1], "{values:?}");
        assert_eq!(values[C + 2], NO_SWITCH);
    }

    /// More contacts than [`SWITCHING_CONTACTS`]: the first ones are kept.
    #[test]
    fn contacts_beyond_the_room_are_left_out() {
        let depths = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let joins = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
        let functions = of(&depths, &joins);
        let values = functions.values();
        assert_eq!(&values[..C], &depths[..C]);
        assert_eq!(&values[C..], &[0.1, NO_SWITCH, 0.2, NO_SWITCH, 0.3, NO_SWITCH, 0.4, NO_SWITCH]);
    }
}
