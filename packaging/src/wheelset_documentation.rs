//! `documentation/index.html` of the wheelset FMU (`wheelset.fmu`). The variable table and the
//! output dependencies are generated from the wheelset's own model description
//! ([`crate::wheelset_interface`], itself generated from `wheelset/modelDescription.xml`) with
//! the layout the contact unit's page uses ([`crate::page`]), so they cannot drift; the figure,
//! Klingel's kinematic oscillation of the free wheelset, is computed here with the core library's
//! geometry when the FMU is packaged. The equations and the integration are those of
//! `wheelset/src/physics.rs` (its module documentation), cited as docs/wheelset.md cites them.

use wheel_rail_contact::geometry::{RollingRadiusDifference, TrackDimensions, WheelOnRail, WheelSide};

use crate::page::{dependencies_list, platforms_section, variables_table, BinaryNote, STYLE};
use crate::plot::{line_plot, Series};
use crate::wheelset_interface::{UNITS, VARIABLES};

/// The figure's scene, the coupled system's Klingel check (docs/wheelset.md, "Klingel's
/// kinematic oscillation"): the free wheelset at this speed \[m/s\] …
pub const KLINGEL_SPEED: f64 = 10.0;
/// … started this far off centre \[m\], at rest in yaw …
pub const KLINGEL_START: f64 = 3e-3;
/// … over this time \[s\].
pub const KLINGEL_DURATION: f64 = 2.0;
/// The time step of the kinematic motion's RK4 integration \[s\]: 1 cm of track at 10 m/s,
/// 1/1200 of the period.
const KLINGEL_TIME_STEP: f64 = 1e-3;
/// Δr(y) is sampled every 0.1 mm (the library's default, docs/conicity.md) over ± this \[m\].
const DIFFERENCE_REACH: f64 = 4e-3;

/// Klingel's kinematic oscillation as the core library computes it: both wheels of the
/// Manchester benchmark (S1002 on UIC60 1:40, `WheelOnRail::manchester_benchmark`), their
/// rolling-radius difference Δr(y) and equivalent conicity tan γ_e(A) (`RollingRadiusDifference`,
/// docs/conicity.md), r0 and the half distance s of the running circles from the benchmark's
/// track (`TrackDimensions::MANCHESTER_BENCHMARK`: r0 = 0.46 m, s = 1.360/2 + 0.070 = 0.75 m).
pub struct Klingel {
    /// tan γ_e at [`KLINGEL_START`].
    pub conicity: f64,
    /// Klingel's wavelength λ = 2π √(r0 s / tan γ_e) \[m\].
    pub wavelength: f64,
    /// The kinematic motion ÿ = −V² Δr(y) / (2 s r0), y(0) = [`KLINGEL_START`], ẏ(0) = 0:
    /// (t \[s\], y \[m\]) every `KLINGEL_TIME_STEP`.
    pub kinematic: Vec<(f64, f64)>,
}

/// Computes [`Klingel`] (about 160 contact searches and 2000 RK4 steps: milliseconds).
pub fn klingel() -> Klingel {
    let track = TrackDimensions::MANCHESTER_BENCHMARK;
    let radius = track.nominal_radius;
    let half_distance = track.flange_back_distance / 2.0 - track.flange_back_position;
    let (right, left) =
        (WheelOnRail::manchester_benchmark(WheelSide::Right), WheelOnRail::manchester_benchmark(WheelSide::Left));
    let difference = RollingRadiusDifference::from_wheelset(&right, &left, DIFFERENCE_REACH, 1e-4)
        .expect("the benchmark's wheelset touches its rails within ±4 mm");
    let conicity = difference.equivalent_conicity(KLINGEL_START).expect("a kinematic oscillation of 3 mm");
    let wavelength = 2.0 * std::f64::consts::PI * (radius * half_distance / conicity).sqrt();
    // (y, ẏ)' = (ẏ, −V² Δr(y) / (2 s r0)).
    let rate = |(y, velocity): (f64, f64)| {
        let delta_r = difference.at(y).expect("the kinematic motion keeps its amplitude, inside the samples");
        (velocity, -KLINGEL_SPEED * KLINGEL_SPEED * delta_r / (2.0 * half_distance * radius))
    };
    let h = KLINGEL_TIME_STEP;
    let steps = (KLINGEL_DURATION / h).round() as usize;
    let mut state = (KLINGEL_START, 0.0);
    let mut kinematic = vec![(0.0, state.0)];
    for step in 1..=steps {
        let along = |(y, v): (f64, f64), factor: f64, (dy, dv): (f64, f64)| (y + factor * dy, v + factor * dv);
        let k1 = rate(state);
        let k2 = rate(along(state, h / 2.0, k1));
        let k3 = rate(along(state, h / 2.0, k2));
        let k4 = rate(along(state, h, k3));
        state = (
            state.0 + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            state.1 + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        );
        kinematic.push((step as f64 * h, state.0));
    }
    Klingel { conicity, wavelength, kinematic }
}

/// The figure: the kinematic motion and Klingel's sinusoid y = A cos(2π x / λ) over the distance
/// x = V t along the track \[m\], y in mm.
fn klingel_figure(klingel: &Klingel) -> String {
    let sinusoid = klingel
        .kinematic
        .iter()
        .map(|&(t, _)| {
            let distance = KLINGEL_SPEED * t;
            (distance, KLINGEL_START * (2.0 * std::f64::consts::PI * distance / klingel.wavelength).cos() * 1e3)
        })
        .collect();
    let series = [
        Series {
            label: "kinematic motion with the library's Δr(y)".to_owned(),
            points: klingel.kinematic.iter().map(|&(t, y)| (KLINGEL_SPEED * t, y * 1e3)).collect(),
        },
        Series {
            label: format!(
                "Klingel: λ = 2π√(r0 s / tan γe) = {:.3} m, tan γe(3 mm) = {:.4}",
                klingel.wavelength, klingel.conicity
            ),
            points: sinusoid,
        },
    ];
    line_plot(
        &format!("Free wheelset at {KLINGEL_SPEED} m/s, started {} mm off centre", KLINGEL_START * 1e3),
        "distance along the track x = V t [m]",
        "lateral displacement y [mm]",
        &series,
    )
}

/// How the wheelset's win64 binary is tested, for the Platforms section.
const WIN64_TESTED: &str = "The test command's run of both platforms' binaries under wine (scripts/test-platforms) \
     drives the contact unit's binaries, not this one's; the wheelset's tests (cargo test -p wheelset, the fmpy \
     suite of the coupled system) run on linux64.";

/// The FMU's `documentation/index.html`, describing `binaries`.
pub fn index_html(binaries: &[BinaryNote]) -> String {
    let klingel = klingel();
    format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>wheelset FMU</title><style>{STYLE}</style></head>
<body>
<h1>wheelset: a rigid wheelset on its primary suspension (FMI 2.0 Co-Simulation)</h1>

<h2>What it is</h2>
<p>A rigid railway wheelset (lateral displacement y, yaw ψ, and the wheels' common angular speed Ω about the axle)
held by a primary suspension at two axleboxes, ±b<sub>1</sub> from its centre, to a frame that moves straight along
the track at <code>forward_speed</code> V. It has no contact model of its own: it is driven by the forces and moments
of <b>two wheel_rail_contact units</b> (left and right wheel, each with <code>contact_geometry</code> = profiles). Its
<b>inputs</b> are those units' outputs — <code>left_track_force_x/y/z</code>, <code>left_track_moment_x/y/z</code> and the
<code>right_…</code> ones: forces on the wheel in track axes, moments about the wheelset's centre on its axle. Its
<b>outputs</b> carry the names of the contact units' inputs they feed — <code>wheelset_lateral_displacement</code>,
<code>wheelset_yaw_angle</code>, <code>wheelset_lateral_velocity</code>, <code>wheelset_yaw_rate</code>,
<code>rolling_speed</code> (= V) and <code>wheel_angular_speed</code> — so a master connects them one to one. The
outputs are states: no input acts on them within a step (no direct feedthrough), so the coupled system has no
algebraic loop. Track axes are the contact unit's: x forward, y to the right, z down; ψ about z.</p>
<p><b>Model Exchange.</b> The same binary is also an FMI 2.0 Model Exchange FMU: the master integrates. The
continuous states are y, ψ, their rates and Ω (the outputs but <code>rolling_speed</code>; nominals 1 mm, 1 mrad,
10 mm/s, 10 mrad/s, 10 rad/s, which CVODE-based masters scale their absolute tolerance by), their derivatives the
locals <code>der(…)</code>: the equations of motion above at the loads set at that moment. No event indicators;
fmi2CompletedIntegratorStep reports an error when |y| exceeds <code>derailment_displacement</code>, as a
Co-Simulation step does.</p>

<h2>How it is meant to be coupled</h2>
<p>The project's repository describes the system once, as an SSP 1.0 (System Structure and Parameterization):
<code>systems/wheelset_on_track/SystemStructure.ssd</code> — the components <code>wheelset</code> (this FMU),
<code>left_wheel</code> and <code>right_wheel</code> (wheel_rail_contact.fmu), the wheelset's six outputs connected to each
wheel's inputs of the same names and each wheel's <code>track_force_x/y/z</code>, <code>track_moment_x/y/z</code> to the
wheelset's <code>left_…</code>/<code>right_…</code> inputs; its parameter sets in <code>resources/*.ssv</code> (the
passenger coach, the contact units' profile geometry, and the variants <code>hunting_check</code> and
<code>klingel_check</code>). <code>scripts/ssp_master.py</code> runs it: a fixed-step master on fmpy's
<code>FMU2Slave</code> that applies the SSD's parameter bindings, sets each unit's inputs after the units feeding it
(this one first: its outputs are states), and steps all units with the inputs held (zero-order hold, Jacobi);
<code>scripts/run-wheelset</code> runs, checks and plots it. Each contact unit needs <code>contact_geometry</code> =
profiles, its <code>wheel_side</code>, <code>vertical_contact</code> = prescribed_force with
<code>vertical_force</code> = W/2 (half the axle load) and roll 0. The communication step must resolve the wheels' spin
under the creep forces, whose time constant is I<sub>s</sub> V/(Σ f<sub>11</sub> r²) ≈ 27 µs × V/(m/s): the SSD's
0.2 ms (docs/wheelset.md, "The master"; the coupling's stability: docs/coupling-stability.md). On its own (no
master connecting it) the FMU starts with each <code>track_force_z</code> at −W/2 and no creep forces, so it runs
too.</p>

<h2>Equations of motion</h2>
<p>The linear wheelset of Wickens (<i>Fundamentals of Rail Vehicle Dynamics</i>, 2003, ch. 2) and Garg &amp;
Dukkipati (<i>Dynamics of Railway Vehicle Systems</i>, 1984, ch. 6), with the contact forces taken as the contact
units compute them instead of linearised (<code>wheelset/src/physics.rs</code>; docs/wheelset.md, "The wheelset
FMU"):</p>
<pre>
m ÿ   = F_y − 2 k_y y − 2 c_y ẏ
I ψ̈   = M_z − 2 k_x b₁² ψ − 2 c_x b₁² ψ̇
I_s Ω̇ = −M_y

F_y = left_track_force_y + right_track_force_y
M_y = left_track_moment_y + right_track_moment_y
M_z = left_track_moment_z + right_track_moment_z
</pre>
<p>m <code>mass</code>, I <code>yaw_inertia</code>, I<sub>s</sub> <code>spin_inertia</code>; k<sub>x</sub>, c<sub>x</sub>,
k<sub>y</sub>, c<sub>y</sub> the longitudinal and lateral stiffness and damping per axlebox; b<sub>1</sub>
<code>lateral_semi_spacing</code>. The moments are about the wheelset's centre on its axle, so the two wheels' add
without transport. A yaw ψ moves the axleboxes by ∓b<sub>1</sub>ψ along the track, hence the yaw stiffness
2 k<sub>x</sub> b<sub>1</sub>². Ω turns about −y (positive rolling forward, Ω r = V in pure rolling), so a moment
M<sub>y</sub> about +y decelerates it: a braking creep force F<sub>x</sub> &lt; 0 at a radius r below the centre gives
M<sub>y</sub> = r F<sub>x</sub> &lt; 0 and spins the wheels up towards Ω r = V. Ω is a state, started at
V/r<sub>c</sub> (<code>centred_rolling_radius</code>): free to spin, the wheelset settles where the longitudinal creep
forces cancel, as the linear stability reference's default does (an imposed Ω lowers the kinematic frequency by
3–5 %: docs/wheelset.md, "The wheel's spin"). No drive or brake torque.</p>
<p>Left out: the longitudinal displacement (F<sub>x</sub> deflects the longitudinal springs statically, changing no
contact input: <code>track_force_x</code> and <code>track_moment_x</code> are checked to be finite and move nothing), the
vertical motion and roll (each contact unit carries its prescribed wheel load; <code>track_force_z</code> must stay
&lt; 0), and the gyroscopic moment I<sub>s</sub> Ω ψ̇, which acts about the roll axis and is carried by the
rails.</p>

<h2>Integration and steps</h2>
<p>Over a communication step of length h the inputs are held at the values the master set before fmi2DoStep
(zero-order hold), so within the step the system is linear with constant coefficients and a constant load. It is
integrated by the classical fourth-order Runge–Kutta method on n equal substeps:</p>
<pre>
n = max(1, ⌈h ρ / 0.2⌉),   ρ = the larger of √k + c for the two oscillators
    lateral: k = 2 k_y / m,       c = 2 c_y / m
    yaw:     k = 2 k_x b₁² / I,   c = 2 c_x b₁² / I
</pre>
<p>ρ bounds the largest eigenvalue magnitude (ω for an underdamped oscillator, at most c for an overdamped one), so
ρ h/n ≤ 0.2 keeps RK4 far inside its stability interval (|λh| &lt; 2.78 on the real axis, 2.83 on the imaginary one)
with a per-substep amplitude error (ρh)⁶/144 ≈ 4·10⁻⁷ and phase error (ρh)⁵/120 ≈ 3·10⁻⁶ rad. The cited
suspension's fastest mode (yaw, 237 rad/s) takes substeps of at most 0.8 ms; a free wheelset (no springs or
dampers) has ρ = 0 and is integrated in one substep, exactly (a constant load gives a motion of degree 2). An
explicit method suffices because the stiff part of the coupled system, the creep forces, is outside this model,
held over the step by the master. The step size may change from step to step
(canHandleVariableCommunicationStepSize); fmi2DoStep requires h &gt; 0 and currentCommunicationPoint equal to the end
of the previous step (relative tolerance 1e-9), and refuses a step that would need more than 10⁷ substeps. At the
step's end the state must be finite and |y| ≤ <code>derailment_displacement</code>.</p>

<h2>Variables</h2>
{table}
<p>Dependencies on the inputs declared in &lt;ModelStructure&gt; (the outputs are states: no direct feedthrough;
at initialization they follow from the parameters, which the model description's &lt;InitialUnknowns&gt;
list):</p>
{dependencies}

<h2>Parameters and their sources</h2>
<p>The start values are the <b>passenger coach of the Manchester benchmark</b> (vehicle 1: S. Iwnicki, “Manchester
benchmarks for rail vehicle simulation”, <i>Vehicle System Dynamics</i> 30 (1998) 295–313; S. Iwnicki (ed.),
<i>The Manchester Benchmarks for Rail Vehicle Simulation</i>, Swets &amp; Zeitlinger, 1999), whose S1002 wheel and
UIC60 rail the contact unit has built in. They are kept, each with its unit and source, in one file of the
project's repository, <code>data/wheelset/passenger_coach.toml</code>, which the wheelset's tests check the start
values against and the Python reference (<code>wheelset/tests/system/linear_stability.py</code>) reads. The paper itself
was not at hand: the values are as two public vehicle-model files transcribe it, and the primary dampings are
in one of them only (docs/wheelset.md, “Parameters”, says which file gave which value). The table above gives
each parameter's source in its description. <code>centred_rolling_radius</code> is the library's rolling radius
of S1002 on UIC60 1:40 with the wheelset centred under half the axle load
(<code>data/wheelset/contact_data.json</code>); <code>forward_speed</code>, <code>derailment_displacement</code> and
the initial values are chosen. The same file holds two variants for the physics checks, chosen rather than cited
and applied over the passenger coach by the SSP's <code>hunting_check.ssv</code> and <code>klingel_check.ssv</code>: a
soft primary suspension that puts the linear critical speed inside 1–80 m/s, and no suspension at all (the free
wheelset of the figure below).</p>

<h2>Klingel's kinematic oscillation</h2>
<p>The reference of the coupled system's Klingel check (docs/wheelset.md, “Klingel's kinematic oscillation”): the
free wheelset (<code>klingel_check</code>) at {speed} m/s, started {start} mm off centre, over {duration} s. A
wheelset that rolls without creepage follows the kinematic motion ÿ = −V² Δr(y)/(2 s r<sub>0</sub>), Δr(y) the
difference of the two wheels' rolling radii; Klingel's formula replaces it by the sinusoid of wavelength
λ = 2π √(r<sub>0</sub> s / tan γ<sub>e</sub>) (drawn over the distance x = V t), where the equivalent conicity tan γ<sub>e</sub>(A) is, by EN 15302's
principle, the cone wheelset's that has the same wavelength at amplitude A: the two curves share their period and
differ in shape (the pair's Δr jumps near y = 0.22 mm).</p>
{figure}
<p><i>Source: computed by <code>packaging/src/wheelset_documentation.rs</code> when this FMU was packaged, with the
core library's geometry — S1002 on UIC60 1:40 on the Manchester benchmark's track
(<code>WheelOnRail::manchester_benchmark</code>), r<sub>0</sub> = {r0} m and s = {s} m from
<code>TrackDimensions::MANCHESTER_BENCHMARK</code>, Δr(y) every 0.1 mm and tan γ<sub>e</sub> by
<code>RollingRadiusDifference</code> (docs/conicity.md) — and the kinematic equation integrated by RK4 every
{time_step} ms. It is not a run of this FMU: the coupled run of the same scene, with the contact units' creep forces
and the wheelset's inertia, is compared with Klingel's wavelength in docs/wheelset.md.</i></p>

{platforms}

<h2>Behaviour</h2>
<ul>
<li>Errors are fmi2Error with a message naming the variable, its value and, during a run, the time; the instance keeps
its state for the master to correct: a parameter out of range (inertias and <code>derailment_displacement</code>
finite and &gt; 0, stiffnesses, dampings and b<sub>1</sub> finite and ≥ 0, V finite, r<sub>c</sub> finite and
&gt; 0), a non-finite input, lift-off (a <code>track_force_z</code> ≥ 0), a derailment (|y| beyond
<code>derailment_displacement</code> at a step's end).</li>
<li>FMU state (canGetAndSetFMUstate, canSerializeFMUstate): the instance's mode, time and every variable's value; a
restored state is checked as its mode allows.</li>
<li>Not supported (declared false): directional derivatives, input interpolation, output derivatives,
asynchronous steps.</li>
</ul>
</body></html>
"#,
        table = variables_table(&VARIABLES, UNITS),
        dependencies = dependencies_list(&VARIABLES),
        figure = klingel_figure(&klingel),
        speed = KLINGEL_SPEED,
        start = KLINGEL_START * 1e3,
        duration = KLINGEL_DURATION,
        r0 = TrackDimensions::MANCHESTER_BENCHMARK.nominal_radius,
        s = TrackDimensions::MANCHESTER_BENCHMARK.flange_back_distance / 2.0
            - TrackDimensions::MANCHESTER_BENCHMARK.flange_back_position,
        time_step = KLINGEL_TIME_STEP * 1e3,
        platforms = platforms_section(binaries, WIN64_TESTED),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wheelset_interface::Kind;

    /// Every variable of the wheelset's model description has its row, with its unit (and its
    /// display unit where it declares one) and its description.
    #[test]
    fn every_variable_of_the_model_description_is_in_the_table_with_its_unit() {
        let html = index_html(&[BinaryNote::Win64 { linked_by_zig: true }]);
        for variable in &VARIABLES {
            let row = html
                .lines()
                .find(|line| line.starts_with(&format!("<tr><td><code>{}</code></td>", variable.name)))
                .unwrap_or_else(|| panic!("no row for {}", variable.name));
            let unit = variable.unit.expect("every wheelset variable has a unit");
            assert!(row.contains(&format!("<td>{}", crate::plot::escape(unit))), "{}: {row}", variable.name);
            if let Some(display) = variable.display_unit {
                assert!(row.contains(&format!("(shown in {display}:")), "{}: {row}", variable.name);
            }
            assert!(row.contains(&crate::plot::escape(variable.description)), "{}", variable.name);
            let start = match variable.kind {
                Kind::Real { start: Some(start) } => format!("<td>{start}</td>"),
                Kind::Real { start: None } => "<td>(computed)</td>".to_owned(),
                other => panic!("the wheelset has only Real variables: {other:?}"),
            };
            assert!(row.contains(&start), "{}: {row}", variable.name);
        }
        assert_eq!(html.matches("<tr><td><code>").count(), VARIABLES.len());
        // The outputs are states: each is listed as depending on no input.
        for output in VARIABLES.iter().filter(|v| v.causality == crate::wheelset_interface::Causality::Output) {
            assert!(html.contains(&format!("<li><code>{}</code> depends on no input</li>", output.name)));
        }
        assert!(html.contains("N (shown in kN: 1 N = 0.001 kN)"));
    }

    #[test]
    fn the_page_has_one_svg_plot_with_its_source() {
        let html = index_html(&[BinaryNote::Win64 { linked_by_zig: true }]);
        assert_eq!(html.matches("<svg").count(), 1);
        let svg = &html[html.find("<svg").unwrap()..html.find("</svg>").unwrap() + "</svg>".len()];
        assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
        assert_eq!(svg.matches("<polyline").count(), 2);
        assert!(html.contains("<i>Source: computed by <code>packaging/src/wheelset_documentation.rs</code>"));
    }

    #[test]
    fn the_platforms_section_states_what_the_binaries_need() {
        let html = index_html(&[
            BinaryNote::Linux64 { glibc: (2, 28), baseline_applied: true },
            BinaryNote::Win64 { linked_by_zig: true },
        ]);
        assert!(html.contains("<h2>Platforms</h2>"));
        assert!(html.contains("needs glibc ≥ 2.28 (the newest glibc symbol version it uses; built against"));
        assert!(html.contains("<b>win64</b>") && html.contains("not this one's") && !html.contains("No win64 binary"));
        let html = index_html(&[BinaryNote::Linux64 { glibc: (2, 35), baseline_applied: false }]);
        assert!(html.contains("needs glibc ≥ 2.35 (the newest glibc symbol version it uses; built with plain cargo"));
        assert!(html.contains("No win64 binary in this build"));
    }

    /// The page describes what it should: the coupling, the equations, the sources.
    #[test]
    fn the_page_names_the_coupling_the_equations_and_the_sources() {
        let html = index_html(&[BinaryNote::Win64 { linked_by_zig: true }]);
        for text in [
            "systems/wheelset_on_track/SystemStructure.ssd",
            "scripts/ssp_master.py",
            "I_s Ω̇ = −M_y",
            "classical fourth-order Runge–Kutta",
            "data/wheelset/passenger_coach.toml",
            "Manchester",
        ] {
            assert!(html.contains(text), "{text}");
        }
    }

    /// The figure's two curves agree where they must: the kinematic motion keeps its amplitude
    /// and has Klingel's wavelength (tan γ_e is defined so), the docs' tan γ_e(3 mm) ≈ 0.1803.
    #[test]
    fn the_kinematic_motion_has_klingels_wavelength() {
        let klingel = klingel();
        assert!((klingel.conicity - 0.1803).abs() < 1e-3, "{}", klingel.conicity);
        let peak = klingel.kinematic.iter().map(|&(_, y)| y.abs()).fold(0.0, f64::max);
        assert!((peak / KLINGEL_START - 1.0).abs() < 1e-3, "{peak}");
        // The downward zero crossings, linearly interpolated: their spacing is the period λ/V.
        let crossings: Vec<f64> = klingel
            .kinematic
            .windows(2)
            .filter(|w| w[0].1 > 0.0 && w[1].1 <= 0.0)
            .map(|w| w[0].0 + (w[1].0 - w[0].0) * w[0].1 / (w[0].1 - w[1].1))
            .collect();
        assert!(crossings.len() >= 2, "{crossings:?}");
        let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
        let wavelength = period * KLINGEL_SPEED;
        assert!((wavelength / klingel.wavelength - 1.0).abs() < 2e-3, "{wavelength} against {}", klingel.wavelength);
    }
}
