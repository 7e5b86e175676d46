//! The shape cache changes nothing but the cost: results are bit-identical to the plain
//! evaluation whether the cache hits (same a/b and ν) or misses.

use crate::common;

use common::contact;
use wheel_rail_contact::{ContactInput, CreepForceModel, LargeCreepage, Polach, Polach2005, ShapeCache};

#[test]
fn cached_shapes_give_bit_identical_forces() {
    let falling =
        Polach { large_creepage: Some(LargeCreepage::new(Polach2005::WET, 15.0).unwrap()), ..Polach::default() };
    for model in [Polach::default(), falling] {
        let mut cache = ShapeCache::default();
        // Runs of one shape (hits) broken by other shapes and Poisson ratios (misses).
        let inputs = [
            contact(1.5, 0.28, 1e-3, 0.0, 0.0),
            contact(1.5, 0.28, 3e-3, -1e-3, 0.4),
            contact(1.5, 0.28, 0.0, 2e-3, -0.7),
            contact(0.4, 0.28, 1e-3, 5e-4, 0.2),
            contact(0.4, 0.25, 1e-3, 5e-4, 0.2),
            contact(1.5, 0.28, 2e-2, 1e-2, 1.0),
            contact(0.02, 0.28, 1e-4, 1e-4, 0.1),
            ContactInput { normal_force: 0.0, ..contact(1.5, 0.28, 1e-3, 0.0, 0.0) },
        ];
        for input in inputs.iter().chain(inputs.iter().rev()) {
            let plain = model.creep_forces(input).unwrap();
            let cached = model.creep_forces_with_cache(input, &mut cache).unwrap();
            assert_eq!(cached, plain, "{input:?}");
        }
        // An invalid input is rejected as always and leaves the cache usable.
        let invalid = ContactInput { semi_axis_b: -1.0, ..inputs[0] };
        assert_eq!(model.creep_forces_with_cache(&invalid, &mut cache).unwrap_err().variable, "semi_axis_b");
        assert_eq!(
            model.creep_forces_with_cache(&inputs[1], &mut cache).unwrap(),
            model.creep_forces(&inputs[1]).unwrap()
        );
    }
}
