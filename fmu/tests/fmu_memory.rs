//! No memory growth over 10⁴ co-simulation steps (issue 10): the heap an instance holds after
//! 10⁴ steps of the exact theory — warm-started from the previous step's tractions, through
//! creepage reversals, lift-offs and FMU states taken and freed — is what it held after the
//! first 100. Measured with a counting global allocator, so any allocation kept across steps
//! shows, not only a leak at the end.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicIsize, Ordering};

use fmu_test_master::{Fmu, OK};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, Model};

/// The system allocator, counting the bytes currently allocated.
struct Counting;

static LIVE_BYTES: AtomicIsize = AtomicIsize::new(0);

// SAFETY: every call is forwarded to the system allocator unchanged; only a counter is added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LIVE_BYTES.fetch_add(layout.size() as isize, Ordering::Relaxed);
        // SAFETY: the caller's contract is the system allocator's.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, pointer: *mut u8, layout: Layout) {
        LIVE_BYTES.fetch_sub(layout.size() as isize, Ordering::Relaxed);
        // SAFETY: as above.
        unsafe { System.dealloc(pointer, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

#[test]
fn ten_thousand_exact_steps_hold_no_more_memory_than_a_hundred() {
    let fmu = Fmu::instantiate("memory", None);
    let grid = [vr::CREEP_FORCE_MODEL, vr::EXACT_ELEMENTS_LONGITUDINAL, vr::EXACT_ELEMENTS_LATERAL];
    assert_eq!(fmu.set_integer(&grid, &[Model::Exact as i32, 12, 10]), OK);
    fmu.initialise(0.0);
    let inputs = [vr::CREEPAGE_LONGITUDINAL, vr::SPIN_CREEPAGE, vr::NORMAL_FORCE];
    let step = |k: usize| {
        let t = k as f64;
        let load = if k % 500 == 250 { -1.0 } else { 80e3 + 10e3 * (0.01 * t).sin() };
        assert_eq!(fmu.set_real(&inputs, &[2e-3 * (0.003 * t).sin(), 0.5 * (0.002 * t).cos(), load]), OK);
        assert_eq!(fmu.do_step(t * 1e-3, 1e-3), OK, "step {k}");
        if k % 1000 == 0 {
            let state = fmu.get_state();
            fmu.free_state(state);
        }
    };
    (0..100).for_each(step);
    let after_hundred = LIVE_BYTES.load(Ordering::Relaxed);
    (100..10_000).for_each(step);
    let after_ten_thousand = LIVE_BYTES.load(Ordering::Relaxed);
    assert_eq!(after_ten_thousand, after_hundred, "live heap bytes after 100 and after 10⁴ steps");
}
