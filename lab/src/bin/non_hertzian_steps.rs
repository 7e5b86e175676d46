//! The non-Hertzian wheel step of the geometry benchmark (`core/benches/geometry.rs`: A-2.2's
//! right wheel with its strip table, Polach, 10 kN, V = 2 m/s), outside criterion, for the two
//! measurements of docs/geometry.md ("Where a step's instructions go"):
//!
//! - `steps PLACE N [moving]`: N steps at PLACE (`tread`, `centred`, `two_minima`, `flange`: the
//!   benchmark's poses), repeated or, with `moving`, y_ws swinging by ±0.1 mm over 64 steps as the
//!   benchmark's `_moving_` steps. Its instructions a step under callgrind: the count of N₂ steps
//!   less that of N₁, over N₂ − N₁, e.g. `valgrind --tool=callgrind
//!   target/release/non_hertzian_steps steps centred 600` against `… 100`, and `callgrind_annotate`
//!   of both for where they go.
//! - `start`: whether the balance could start nearer its root, 192 moving steps a pose (the first
//!   period left out): the largest relative error of the depth below the touch taken as the last
//!   step's (what the balance does, `BalanceStart`) and as extrapolated linearly from the last two.
//!
//! Run: `cargo run --release -p lab --bin non_hertzian_steps -- start`.

use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
use wheel_rail_contact::scene::{Evaluation, Scene};
use wheel_rail_contact::wheel::{
    ContactMethod, VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity,
};
use wheel_rail_contact::{ModelChoice, Polach};

/// The benchmark's poses: name, y_ws \[m\], yaw \[rad\].
const PLACES: [(&str, f64, f64); 4] =
    [("tread", 0.002, 0.0048), ("centred", 0.0, 0.0), ("two_minima", 0.005, 0.0), ("flange", 0.007, 0.0168)];

/// The wheel step at `place`, its y_ws moved by ±0.1 mm over 64 steps where `moving`.
fn input(place: &str, step: usize, moving: bool) -> WheelInput {
    let (_, lateral, yaw) = *PLACES.iter().find(|(name, ..)| *name == place).expect("a place of the benchmark");
    let swing = if moving { 0.1e-3 * (2.0 * std::f64::consts::PI * step as f64 / 64.0).sin() } else { 0.0 };
    WheelInput {
        position: WheelsetPosition { lateral: lateral + swing, yaw, ..WheelsetPosition::default() },
        velocity: WheelsetVelocity { rolling_speed: 2.0, wheel_angular_speed: 4.3478, ..Default::default() },
        vertical: VerticalContact::PrescribedForce(10e3),
        friction_coefficient: 0.3,
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let contact = WheelRailContact::new(
        WheelOnRail::manchester_benchmark(WheelSide::Right),
        Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28),
    )
    .with_method(ContactMethod::NonHertzian)
    .with_strip_table();
    let usage = "usage: non_hertzian_steps steps PLACE N [moving] | start";
    // The depth below the touch after each of `count` steps at `place`.
    let run = |place: &str, count: usize, moving: bool| -> Result<Vec<f64>, Box<dyn std::error::Error>> {
        let (mut state, mut cache) = (WheelState::default(), WheelCache::default());
        let mut depths = Vec::with_capacity(count);
        for step in 0..count {
            let (_, next) =
                contact.evaluate(&input(place, step, moving), &state, &mut cache, Evaluation::Step(1e-3))?;
            state = next;
            let balance = state.balance.ok_or("no balance")?;
            depths.push(balance.vertical - balance.touch);
        }
        Ok(depths)
    };
    match args.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["steps", place, count, ref rest @ ..] => {
            let depths = run(place, count.parse()?, rest == ["moving"])?;
            println!("{} steps, last depth below the touch {:.6e} m", depths.len(), depths.last().unwrap_or(&0.0));
        }
        ["start"] => {
            println!("place: largest relative error of the start's depth, the last step's / extrapolated");
            for (place, ..) in PLACES {
                let depths = run(place, 192, true)?;
                let (mut held, mut extrapolated) = (0.0f64, 0.0f64);
                for k in 64..depths.len() {
                    let depth = depths[k];
                    held = held.max(((depth - depths[k - 1]) / depth).abs());
                    extrapolated = extrapolated.max(((depth - (2.0 * depths[k - 1] - depths[k - 2])) / depth).abs());
                }
                println!("{place}: {held:.1e} / {extrapolated:.1e}");
            }
        }
        _ => return Err(usage.into()),
    }
    Ok(())
}
