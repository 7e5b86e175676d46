//! `documentation/index.html` of the FMU. The variable table is generated from the adapter's
//! own table (itself generated from `modelDescription.xml`, laid out by [`crate::page`], which the
//! wheelset's page shares), so it cannot drift; the plot is computed with the core library at the
//! default scene.

use std::fmt::Write as _;

use wheel_rail_contact::{ContactInput, CreepForceModel, ModelChoice, Polach};
use wheel_rail_contact_fmu::model_description::{Kind, Values, UNITS, VARIABLES};
use wheel_rail_contact_fmu::options;
use wheel_rail_contact_fmu::scene::contact_input;

use crate::page::{dependencies_list, platforms_section, variables_table, BinaryNote, STYLE};
use crate::plot::{line_plot, Series};
use crate::{non_hertzian_figure, profile_figure};

/// The core's input at the FMU's start values (the default scene).
pub fn default_contact_input() -> ContactInput {
    contact_input(&Values::default())
}

/// Creepages of the default curve plot: 0 … 1 %.
fn creepage_grid() -> impl Iterator<Item = f64> {
    (0..=100).map(|i| i as f64 * 1e-4)
}

/// F_x(ξ) and F_y(η) in kN at the default scene, computed with the core.
fn default_curves() -> Vec<Series> {
    let base = default_contact_input();
    let curve =
        |label: &str, set: fn(&mut ContactInput, f64), pick: fn(&wheel_rail_contact::CreepForces) -> f64| Series {
            label: label.to_owned(),
            points: creepage_grid()
                .map(|s| {
                    let mut input = ContactInput { creepage_longitudinal: 0.0, ..base };
                    set(&mut input, s);
                    let forces = Polach::default().creep_forces(&input).expect("the default scene is valid");
                    (s * 100.0, pick(&forces) / 1e3)
                })
                .collect(),
        };
    vec![
        curve("F_x, pure longitudinal creepage ξ", |i, s| i.creepage_longitudinal = s, |f| f.force_longitudinal),
        curve("F_y, pure lateral creepage η", |i, s| i.creepage_lateral = s, |f| f.force_lateral),
    ]
}

/// The table of [`options::option_uses`] (declared once, in the adapter and the rungs) as HTML.
fn option_table_html() -> String {
    let line = |tag: &str, cells: &[String]| {
        let cells: String = cells.iter().map(|cell| format!("<{tag}>{cell}</{tag}>")).collect();
        format!("<tr>{cells}</tr>\n")
    };
    let mut html = String::from("<table>\n");
    html.push_str(&line("th", &options::COLUMNS.map(str::to_owned)));
    for row in options::rows(|name| format!("<code>{name}</code>")) {
        html.push_str(&line("td", &row));
    }
    html.push_str("</table>");
    html
}

/// Each rung's paragraph (declared beside its code, `ModelChoice::RUNGS`), as a list; the start
/// value of `creep_force_model` marked as the default.
fn model_list_html() -> String {
    let default = VARIABLES.iter().find_map(|v| match v.kind {
        Kind::Enumeration { declared_type: "Model", start, .. } => Some(start),
        _ => None,
    });
    let mut html = String::from("<ul>\n");
    for rung in ModelChoice::RUNGS {
        let marker = if Some(rung.fmu_value) == default { " (default)" } else { "" };
        writeln!(html, "<li><code>{}</code>{marker}: {}</li>", rung.name, rung.documentation).unwrap();
    }
    html.push_str("</ul>");
    html
}

/// The model choice and the scene options: what each does, its variables, equations and sources.
const OPTIONS_HTML: &str = r#"<h2>Models (parameter <code>creep_force_model</code>)</h2>
<p>All models take the same inputs and give the same outputs; the one chosen is built once when the
parameters are fixed (fmi2ExitInitializationMode) and again only if a parameter changes, so the models not
chosen cost nothing per step. <code>creep_force_model</code> and every option switch are <i>fixed</i> parameters: set them
before fmi2ExitInitializationMode. Their validity is checked there (fmi2Error naming the variable and value);
parameters of an option that is off, and of models not chosen, are not used and not checked.</p>
{model_list}

<h2>Option: Polach 2005 traction law (parameter <code>traction_law</code>)</h2>
<p>Polách, “Creep forces in simulations of traction vehicles running on adhesion limit”, Wear 258 (2005)
992–1000 (project errata E8). Friction falls with the slip velocity and the contact stiffness is reduced:</p>
<pre>
μ(w) = μ0 ((1 − A) e^(−B w) + A),      w = s_C · V_s                       (slip velocity)
F    = (2 Q μ(w) / π) (k_A ε / (1 + (k_A ε)²) + arctan(k_S ε)),   ε with μ(w)
</pre>
<p>with 0 &lt; k_S ≤ k_A ≤ 1 and A = μ∞/μ0. <code>coulomb</code> (default) is the constant μ of the method above.
Presets: <code>polach2005_dry</code> k_A = 1, k_S = 0.4, A = 0.4, B = 0.6 s/m; <code>polach2005_wet</code>
k_A = 0.3, k_S = 0.1, A = 0.4, B = 0.2 s/m; <code>polach2005_user</code> takes
<code>adhesion_reduction_factor</code> (k_A), <code>slip_reduction_factor</code> (k_S),
<code>friction_limit_ratio</code> (A) and <code>friction_decay_rate</code> (B, s/m). <b>With Polach 2005 the input
<code>friction_coefficient</code> is μ0</b>, the maximum friction at zero slip velocity; Polach recommends
μ0 = 0.55 with the dry set and μ0 = 0.30 with the wet set (the FMU does not override the input). V<sub>s</sub> is
|<code>rolling_speed</code>|, or D = √(V² + v_c²) when <code>creepages_from_kinematics</code> = on (then s_C·D is the
slip velocity exactly, down to standstill). Outputs: <code>current_friction_coefficient</code> = μ(w),
<code>slip_velocity</code> = w. Polach 2005 extends Polach's method only: with another <code>creep_force_model</code> a
Polach 2005 <code>traction_law</code> is rejected with fmi2Error (rather than silently ignored); so is
<code>stiffness_source</code> = measured_curve.</p>

<h2>Option: Hertz normal contact (parameter <code>hertz_contact</code>)</h2>
<p>When on, the ellipse is Hertz's, from <code>normal_force</code> Q, the relative curvatures and E* = G/(1 − ν)
(two bodies of one material: 1/E* = 2(1 − ν²)/E, E = 2G(1 + ν)); the inputs <code>semi_axis_a</code> and
<code>semi_axis_b</code> are ignored. Curvatures: A = 1/(2r) in the rolling direction (r the input
<code>wheel_rolling_radius</code>; the rail is straight along the track), B = (κ<sub>w</sub> + κ<sub>r</sub>)/2
laterally from the parameters <code>wheel_profile_curvature</code> and <code>rail_profile_curvature</code> (signed:
&gt; 0 convex, &lt; 0 concave, 0 straight such as a conical tread). B must be &gt; 0 (a convex gap). The exact
elliptic-integral solution (Hertz 1882; Johnson, <i>Contact Mechanics</i>, 1985, ch. 3 and §4.2) with Carlson's
symmetric integrals:</p>
<pre>
A = Q R_D(0, b², a²) / (2π E*),   B = Q R_D(0, a², b²) / (2π E*)      → a, b
p0 = 3Q / (2π a b),               δ = 3Q R_F(0, a², b²) / (2π E*)
</pre>
<p>Outputs <code>contact_semi_axis_a</code>, <code>contact_semi_axis_b</code>, <code>max_pressure</code> p0 and
<code>approach</code> δ. Q ≤ 0 (lift-off) gives zero forces and a = b = p0 = δ = 0 before any Hertz computation.
When off, <code>contact_semi_axis_a/b</code> echo the inputs, <code>max_pressure</code> is p0 = 3Q/(2πab) of the
given ellipse (0 for Q ≤ 0) and <code>approach</code> is 0 (it needs the curvatures). The start values (a conical
920 mm wheel on a 300 mm rail crown at 100 kN) give a = 7.2 mm, b = 5.4 mm: the default scene.</p>

<h2>Option: creepages from kinematics (parameter <code>creepages_from_kinematics</code>)</h2>
<p>When on, the creepages come from the inputs <code>rolling_speed</code> V, <code>wheel_angular_speed</code> ω,
<code>wheel_rolling_radius</code> r, <code>lateral_slip_velocity</code> v<sub>y</sub> and
<code>spin_angular_velocity</code> ω<sub>z</sub>, and the creepage inputs are ignored:</p>
<pre>
ξ = (V − ω r) / D,   η = v_y / D,   φ = ω_z V / D²,     D = √(V² + v_c²)
</pre>
<p>Kalker's definitions (creepage = rigid slip velocity / rolling speed, signed so that the forces reverse with the
direction of travel) with |V| replaced by the smooth D ≥ v_c (parameter <code>regularisation_speed</code>, default
0.01 m/s): nothing divides by zero at V = 0 or ωr = 0, and the forces are bounded and continuous through
standstill; for |V| ≫ v_c the creepages are Kalker's to a relative v_c²/(2V²). Below v_c the contact acts as a
stiff damper; for low-speed transients switch on the relaxation. Outputs: <code>effective_creepage_longitudinal</code>,
<code>effective_creepage_lateral</code>, <code>effective_spin_creepage</code> (the creepage inputs when off) and
<code>slip_velocity</code>.</p>

<h2>Option: creep relaxation (parameter <code>creep_relaxation</code>)</h2>
<p>When on, <code>force_longitudinal</code> and <code>force_lateral</code> build up over a rolling distance
(first-order relaxation-length model; Pacejka, <i>Tire and Vehicle Dynamics</i>; Knothe &amp; Gross-Thebing,
VSD 15, 1986):</p>
<pre>
dF/dt = (V_r / L) (F_ss − F),     F(t + h) = F_ss + (F(t) − F_ss) e^(−V_r h / L)
</pre>
<p>F<sub>ss</sub> is the chosen model's steady-state force for the inputs set before the step and V<sub>r</sub>
the speed at which the contact's material is renewed: |V| (<code>rolling_speed</code>) with the creepages as
inputs, and (|V| + |ωr|)/2 with <code>creepages_from_kinematics</code> — each body carries its half of the
elastic displacement out of the contact at its own surface speed (Kalker's rolling speed in magnitude) — so a
wheel spinning or braking at standstill builds up its force over a few relaxation lengths of its own rolling,
while a contact at rest (V = ω = 0) holds its force like a spring. Both are held over the step (the
co-simulation's zero-order hold), so the exact exponential update is used: stable for any step size, never
overshooting, the same after one step of h as after n steps of h/n. The relaxed forces are the FMU's state: set to the steady state at
fmi2ExitInitializationMode, advanced by every fmi2DoStep, cleared by fmi2Reset, and set to zero at lift-off or
μ = 0 (no contact, no elastic deformation). <code>relaxation_length</code> L = 0 (default) derives it from the
contact: L<sub>x</sub> = √(ab) C11 (2 − ν)/4, L<sub>y</sub> = √(ab) C22 (2 − ν)/4 (Kalker's creep stiffness over
Mindlin's tangential stiffness; ≈ 1.8a and 1.6a for a circle), else L is used for both directions.
<code>adhesion_utilisation</code> is then that of the relaxed forces; <code>spin_moment</code> is the steady
state's. After a sudden drop of μQ the relaxed force may exceed the new limit for about L/|V| (utilisation &gt; 1),
as in any first-order relaxation model.</p>

<h2>Contact from profiles (parameter <code>contact_geometry</code>)</h2>
<p><code>contact_geometry</code> = ellipse (1, the default) is the one patch of the sections above, its creepages, load
and ellipse given (or from the kinematics and Hertz). With <code>contact_geometry</code> = profiles (2) one instance
is <b>one wheel on its rail</b> (issue 25): the contact patches follow from the wheel and rail profiles and the
wheelset's position and motion, as CONTACT's module 1 computes them.</p>
<ul>
<li><b>Profiles</b>: the String parameters <code>wheel_profile</code> and <code>rail_profile</code>, each a file path
(SIMPACK <code>.prw</code>/<code>.prr</code>, MiniProf <code>.whl</code>/<code>.ban</code>, the format from the extension; a
relative path is looked up in the FMU's <code>resources/</code> first, where a profile packed into the FMU
is found wherever the master unzips it, then in the master's working directory) or a built-in name (<code>MBench_S1002</code>,
<code>MBench_UIC60</code>: the Manchester benchmark's S1002 wheel and UIC60 rail inclined 1:40, the defaults). Both are
given for the right side, y lateral and z downward in their own coordinates; the left wheel
(<code>wheel_side</code> = left, 0) uses them mirrored, as CONTACT does, and reports lateral positions and contact
angles mirrored back. They are read and placed when the instance leaves initialisation (and again if a profile
parameter changes before it does); a missing, unreadable or malformed file is fmi2Error naming the variable, the
file and the reason (the line, for a malformed one).</li>
<li><b>Track</b>: the rail's gauge face (at <code>gauge_measuring_height</code> below its top) at
<code>track_gauge</code>/2, the wheel's flange back (at <code>flange_back_position</code> in its profile) at
<code>flange_back_distance</code>/2, the wheel profile's z = 0 at <code>wheel_nominal_radius</code> r0 below the axle;
defaults the benchmark's 1.435 m, 14 mm, 1.360 m, −70 mm, 0.46 m. <code>rail_cant</code> turns the rail profile
about its origin towards the track's centre (as CONTACT's CANT, within ±0.1 rad) on top of any inclination its
points have: the built-in UIC60 is already inclined 1:40 (cant 0).</li>
<li><b>Inputs</b>: the wheelset's <code>wheelset_lateral_displacement</code> y<sub>ws</sub> (to the right),
<code>wheelset_roll_angle</code>, <code>wheelset_yaw_angle</code> (each within ±0.1 rad), <code>rolling_speed</code> V,
<code>wheel_angular_speed</code> Ω (positive rolling forward; CONTACT's VPITCH is −Ω),
<code>wheelset_lateral_velocity</code>, <code>wheelset_yaw_rate</code>, <code>friction_coefficient</code>, and with
<code>vertical_contact</code> = prescribed_force (1) the wheel load <code>vertical_force</code> (≤ 0: lift-off), with
prescribed_position (2) the height <code>wheelset_vertical_position</code> z<sub>ws</sub> (downward; 0: the wheel's
datum at the rail top's level). The single patch's inputs (creepages, <code>normal_force</code>, semi-axes,
<code>wheel_rolling_radius</code>, <code>lateral_slip_velocity</code>, <code>spin_angular_velocity</code>) are not
read, and its outputs are 0.</li>
<li><b>Per patch</b>: with <code>contact_method</code> = non_hertzian (the default) one patch per contact region of
the profiles' interpenetration (below); with hertz the contact points are the local minima of the undeformed gap
(tread and flange), each in contact where the gap closes, the normal force from the penetration by Hertz, with
Hertz's ellipse from the profiles' curvatures. The creepages from the slip of the wheel's point at the patch over the rolling speed
(regularised through standstill by <code>regularisation_speed</code>); the creep forces by the chosen
<code>creep_force_model</code>, <code>traction_law</code> and <code>creep_relaxation</code> (each patch carries its own
relaxed forces). With a prescribed force the wheelset's height is solved so that the rail carries the load through
the normal and the creep forces together.</li>
<li><b>Outputs</b>: <code>track_force_x</code>, <code>track_force_y</code>, <code>track_force_z</code>: the total force
on the wheel in track coordinates (x along the track in the rolling direction, y to the right, z down; the negative
of CONTACT's “total forces on rail”, so <code>track_force_z</code> = −<code>vertical_force</code>);
<code>track_moment_x/y/z</code>: their moment, with the patches' spin moments, about the wheelset's centre on its
axle; <code>contact_patch_count</code>; <code>wheelset_vertical_position_solved</code>; and for patches 1 and 2,
ordered by lateral position on the rail from its field side, tread first: <code>patchK_contact_angle</code> δ
(CONTACT's DELTCP), <code>patchK_rail_lateral_position</code> (in the rail profile's coordinates),
<code>patchK_rolling_radius</code>, <code>patchK_normal_force</code>, <code>patchK_force_longitudinal</code>,
<code>patchK_force_lateral</code> (on the wheel, in the patch's tangent plane: the negatives of CONTACT's FX, FS on
the rail), <code>patchK_creepage_longitudinal</code>, <code>patchK_creepage_lateral</code>,
<code>patchK_spin_creepage</code> (wheel minus rail: the negatives of CONTACT's CKSI, CETA, CPHI),
<code>patchK_semi_axis_a</code>, <code>patchK_semi_axis_b</code>. An absent patch gives zeros; a third patch (rare) is
in the totals only. Directional derivatives: by central differences (Behaviour, below).</li>
</ul>
{profile_figures}
<p>On the benchmark's case A-2.2 (both wheels, 21 lateral positions with yaw and roll) the Hertz patch
(<code>contact_method</code> = hertz) is within
1 mm of CONTACT's published full solution on the rail and its contact angle within 0.01 rad on the tread and 0.02
on the flange; with <code>creep_force_model</code> = exact_table its normal force is within 0.1 % and its creep forces
within 0.041 μN, with Polach's method within 10 % and 0.2 μN (but on the flange at 6.5 mm, under large spin,
Polach's lateral force is short and its share of the vertical balance leaves the normal force 10.5 % high) — except
where the gap is flat or has two nearby minima (y<sub>ws</sub> = 0; the right wheel at 0.5 mm) or the contact jumps
from tread to flange (the right wheel at 5 mm). The fmpy test <code>fmu/tests/fmpy/test_profiles.py</code> checks it.</p>

<h3>Non-Hertzian contact (parameter <code>contact_method</code>) and measured profiles</h3>
<p><code>contact_method</code> = hertz (1) finds one Hertz ellipse per minimum of the undeformed gap, the fastest
way. It is off where the gap is not Hertzian: flat within microns over 10 mm (the centred wheelset on new
profiles), with two close minima (the tread–flange transition) or conformal (worn profiles).
<code>contact_method</code> = non_hertzian (2, the default: it is the one that meets CONTACT there) finds one patch per contact region of the two profiles' virtual
interpenetration, strip by strip across the rail (Kik and Piotrowski, Vehicle System Dynamics 46 (2008) 27–48, as
CONTACT's fast KPEC method): the region's extent and shape, its load, the pressure centroid as the contact point
with the contact angle there, and an equivalent ellipse of the same area for the creep-force
model; regions closer than 8 mm along the surface are one patch (CONTACT's D_SEP). With a prescribed wheel load
the wheelset's height is solved under the creep forces' share as with Hertz. On all 42 cases of the Manchester
benchmark's A-2.2 (both wheels) with <code>creep_force_model</code> = exact_table: one patch where CONTACT finds
one, the contact point within 0.85 mm on the rail, the contact angle within 0.01 rad on the tread and 0.04 on the
flange root, the normal force within 0.2 % and the creep forces within 0.12 μN of CONTACT's full solution, but
for the right wheel at 0.5 mm (F<sub>s</sub>, 0.133 μN: a wide patch on a gap flat within microns); the creepages
are the strips' load-weighted mean, taken at their mean rolling radius (on the centred wheelset's wide patch the
radius varies across it: F<sub>x</sub> 0.083 μN off CONTACT's 0.3 N, 0.123 μN at the centroid's own radius). On
measured worn profiles (a worn wheel on a worn high rail from CONTACT's test bank, 20 cases from the tread over the
worn gauge corner to the flange, with friction) every patch CONTACT finds with at least 1 % of the load is found, two
where it finds two, within the same tolerances but for the contact angle of a light patch on the worn gauge corner;
with Hertz the contact point is off by up to 2.5 mm and the
creep forces by 0.21 μN. The pressure follows Kik and Piotrowski's assumed distribution (semi-elliptic along each
strip): its peak lies 7–13 % below CONTACT's on the tread, 15–25 % on the flange, up to 41 % where the patch
is wide and up to 63 % where tread and flange root share it (its total and its centroid are right); on the centred wheelset at 10 kN the small gauge-side lobe peaks at 592 MPa where CONTACT's
lobe, joined to the tread by a neck, stays below its 338 MPa. A wheel step costs 4–10 µs repeated and 9–21 µs with the wheelset moving (up to 4 times Hertz's, the most for
the centred wheelset's wide patch; up to 0.1 ms from a cold start); the wheel's state holds where its last
vertical balance settled, where the next one starts, so that a restored FMU state continues bit for bit: the strips' geometry is tabulated per wheel when the
instance leaves initialisation (under half a millisecond), only with <code>contact_method</code> = non_hertzian.</p>
{non_hertzian_figures}
<p><b>Measured profiles.</b> A MiniProf file (<code>.whl</code>, <code>.ban</code>) is read as the instrument
writes it: every header form, its column definition and offsets, commented-out points, a left-side measurement
mirrored; zig-zags, back-steps and overhangs that cannot touch are dropped. Its points are then smoothed by
CONTACT's weighted smoothing spline with the filter wavelength <code>profile_filter_wavelength</code> (5 mm by
default: measurement noise shorter than it is removed, the shape kept; 0 interpolates the cleaned points): read
unsmoothed, the contact search locks onto the noise. SIMPACK files and the built-in profiles are used as given. A
file that cannot be read is fmi2Error naming the variable, the file, the line and the reason.</p>

<h2>Which variables each option uses</h2>
{option_table}
<p>&lt;ModelStructure&gt; lists, for each output, every input it depends on under some choice of model and options
(FMI 2.0 asks for every dependency that can exist); a unit test perturbs each input under a set of scenes covering
every option and model and checks the lists are exactly those. InitialUnknowns list the same inputs and every
parameter that can change the output at initialization.</p>"#;

/// How the contact unit's win64 binary is tested (`scripts/test-platforms`), for the Platforms section.
const WIN64_TESTED: &str =
    "Tested under wine: the same results as linux64 bit for bit, but for Kalker's exact theory, \
     within 1e-15 of the force (the C math libraries round ln and hypot differently in the last bit). An FMU state \
     serialized on one platform restores on the other.";

/// The FMU's `documentation/index.html`, describing `binaries`.
pub fn index_html(binaries: &[BinaryNote]) -> String {
    let platforms = platforms_section(binaries, WIN64_TESTED);
    let plot = line_plot(
        "Default scene: creep force against creepage (Polach, Kalker stiffness)",
        "creepage [%]",
        "force on the wheel [kN]",
        &default_curves(),
    );
    let scene = default_contact_input();
    format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>wheel_rail_contact FMU</title><style>{STYLE}</style></head>
<body>
<h1>wheel_rail_contact: wheel–rail creep forces (FMI 2.0 Co-Simulation)</h1>

<h2>What it computes</h2>
<p>By default (every option off, <code>creep_force_model</code> = polach), the tangential forces of one wheel–rail contact patch — the longitudinal creep force F<sub>x</sub>, the lateral
creep force F<sub>y</sub> and the adhesion utilisation |F|/(μQ) — from the creepages ξ, η, the spin creepage φ,
the normal force Q, the contact-ellipse semi-axes a (rolling direction) and b (lateral), the friction coefficient
μ, and the material constants G and ν. The method is Polách's fast analytical solution (O. Polách, “Solution of
wheel-rail contact forces suitable for calculation of rail vehicle dynamics”), with the contact stiffness either
from Kalker's linear theory or fitted to a measured creep curve. The parameter <code>creep_force_model</code> selects another
rung of the speed–accuracy ladder (Kalker's linear theory, Shen–Hedrick–Elkins, FASTSIM, Kalker's exact theory and
its table), and
four options, each off by default, supply what a scene lacks: Polach's 2005 traction law, Hertz's contact ellipse,
creepages from kinematics, creep relaxation (sections below). Without relaxation the outputs are algebraic in the
inputs: every fmi2DoStep computes them from the inputs set before the step, so any communication step size is
exact; with relaxation the exact exponential update keeps that property. An output read after an input it depends
on was set within a step is computed at the new inputs, without advancing the time or the relaxed forces (direct
feedthrough, as <code>&lt;ModelStructure&gt;</code> declares), so a master can solve an algebraic loop through
the unit.</p>
<p><b>Model Exchange.</b> The same binary is also an FMI 2.0 Model Exchange FMU (<code>&lt;ModelExchange&gt;</code>
beside <code>&lt;CoSimulation&gt;</code>, one modelIdentifier): the unit is algebraic in its inputs, and an output
read in event or continuous-time mode is computed at the inputs set at that moment, bit for bit what a
Co-Simulation step at those inputs gives. With <code>contact_geometry</code> = profiles its 13 event indicators
change sign where the wheel's patches jump — a contact's onset (up to 5 contacts, tread first; with
<code>contact_method</code> = non_hertzian also where regions of one patch merge or part), two neighbours joining
into one patch or parting and a joined patch passing to another gap minimum (up to 4 pairs) — so that the
integrator stops at the jump; 1.0 where nothing switches (always with one patch). Its two continuous states are the relaxed forces
<code>relaxed_force_longitudinal</code>, <code>relaxed_force_lateral</code> of <code>creep_relaxation</code>, with
the relaxation law dF/dt = (V<sub>r</sub>/L)(F<sub>ss</sub> − F) as their derivatives (0 with relaxation off); the
output forces are the states projected onto the friction limit μQ, and where that moves them a step event
(fmi2CompletedIntegratorStep) lets fmi2NewDiscreteStates move the states onto the limit. With
<code>contact_geometry</code> = profiles, <code>creep_relaxation</code> = on is refused at
fmi2ExitInitializationMode (each patch relaxes on its own, and patches come and go). Each interface refuses the
other's functions (fmi2Error naming both).</p>

<h2>Sign convention and units</h2>
<p>Kalker's and CONTACT's convention: x in the rolling direction, y lateral, z the contact normal into the wheel;
creepages are rigid slip velocities divided by the rolling speed. <b>The forces act on the wheel and oppose the
creepages</b>: in the linear range F<sub>x</sub> = −G·a·b·C11·ξ and F<sub>y</sub> = −G·a·b·C22·η −
G·(ab)<sup>3/2</sup>·C23·φ (ERRATA E4). All values are SI (N, m, Pa, 1/m); the display units (kN, mm, GPa, 1/mm)
are declared for masters that show them.</p>

<h2>Variables</h2>
{table}
<p>Dependencies declared in &lt;ModelStructure&gt; (checked by a test that perturbs each input):</p>
{dependencies}

<h2>Default scene (the start values)</h2>
<p>A loaded wheel on a rail with a small braking creepage: Q = {q} kN (a 20 t axle load), a = {a} mm, b = {b} mm —
the Hertzian ellipse of a new 920 mm wheel with a conical tread on a rail head of 300 mm crown radius at that
load (E = 210 GPa, ν = 0.28; the same Hertz formula gives CONTACT's published a = 8.000 mm, b = 4.000 mm for its
curvatures 0.8464e-3 and 2.406e-3 /mm at 82 kN) — μ = {mu} (dry rail), G = {g} GPa and ν = {nu} (the values of
CONTACT's published cases), ξ = {xi}, η = φ = 0.</p>
{plot}

<h2>Equations and sources</h2>
<p>Equation numbers are those of Polách's paper; E1–E7 are the corrections of the paper's transcription that the
project uses (its errata), each checked by a test of the core library.</p>
<pre>
ε   = π G a b c_jj s_C / (4 Q μ)                         gradient, eq. (7) with C of eq. (28)  [E3]
c_jj = √((c11 ξ/s)² + (c22 η/s)²),  s = √(ξ² + η²)      direction-weighted coefficient, eq. (29) [E1]
s_yC = η + φ a  if |η + φ a| > |η|,  else η              eq. (21)
s_C  = √(ξ² + s_yC²)                                     eq. (22)
F    = (2 Q μ / π) (ε/(1 + ε²) + arctan ε)               eq. (14)
F_x  = −F ξ / s_C,   F_y = −F η / s_C + F_yS             eq. (3) with the sign convention [E4]
F_yS = (9/16) a Q μ K_M K_S φ / s_C,  K_S = 1 + 6.3 (1 − e^(−a/b))      eqs. (23), (24)
ε_s  = (8/3) G b √(ab) c23 |s_yC| / (Q μ K_S)            spin gradient, eqs. (25), (32) [E2]
K_M  = −(2/3) ε_s / (1 + ε_s²)²                          eq. (20) in closed form, no cancellation [E5]
s_C = 0 → no force; Q ≤ 0 (lift-off) or μ = 0 → zero forces, no error    [E6]
</pre>
<p>Kalker's coefficients C11, C22, C23 come from his table E.3 (Kalker 1990, <i>Three-dimensional elastic bodies
in rolling contact</i>), interpolated as CONTACT does, with his thin-ellipse asymptotes below a/b or b/a = 0.1.</p>
<p><b>Measured creep curve</b> (<code>stiffness_source = measured_curve</code>, eqs. (33)–(36), E7): from the peak
adhesion F_max/Q, the creepage s_max at the peak and the kinetic friction f_k, the FMU solves eq. (34)
F = (2 Q f_k/π)(k ε/(k² + ε²) + arctan ε) with eq. (35) for k = f_s/f_k and sets the stiffness C of eq. (36). A
curve exists only for f_k &lt; F_max/Q &lt; (1 + 1/π) f_k; other values give fmi2Error naming the parameter. The
fit runs when the values are first needed (fmi2ExitInitializationMode) and again whenever they change. <b>The
scene's <code>friction_coefficient</code> input still applies</b>: the fitted curve fixes the contact stiffness,
and μ scales the force level as in eq. (14); at μ = f_k the FMU reproduces the measured curve (peak F_max at
s_max).</p>

{options}

{platforms}

<h2>Behaviour</h2>
<ul>
<li>Invalid values (NaN, ±Inf, a or b ≤ 0, μ &lt; 0, G ≤ 0, ν outside [0, 0.5], an impossible measured curve, an
unknown Enumeration value, an invalid option parameter) are reported where outputs are computed — fmi2ExitInitializationMode, fmi2DoStep, and
fmi2GetReal of an output in initialization mode — as fmi2Error with a message naming the variable and its value.
The instance keeps its state and last valid outputs; once the master sets a good value it continues.</li>
<li>Calls outside the states the standard allows return fmi2Error and log “fmi2XXX: illegal call in state YYY”.</li>
<li>fmi2DoStep requires h &gt; 0 and currentCommunicationPoint equal to the end of the previous step (relative
tolerance 1e-9); with a stop time, no step may end after it. canHandleVariableCommunicationStepSize is true.</li>
<li>FMU state (canGetAndSetFMUstate, canSerializeFMUstate): fmi2GetFMUstate/SetFMUstate copy the instance's mode,
time, every variable's value (the profiles' names too) and the model's internal state (with profiles, each
patch's); fmi2SerializeFMUstate writes a versioned byte string
(magic “WRCstate”, format version, this FMU's GUID, length, CRC-32, then the state), exactly
fmi2SerializedFMUstateSize bytes. fmi2DeSerializeFMUstate rejects truncated, corrupted, foreign or other-version
byte strings with fmi2Error and the reason, changing nothing.</li>
<li>Directional derivatives (providesDirectionalDerivative): J·v of the outputs with respect to the continuous
inputs at the current values — exact (forward-mode dual numbers) for Polach, Kalker's linear theory,
Shen–Hedrick–Elkins (one-sided at kinks: Kalker's table rows in a/b, Φ = 0, aΦ = −2η) and exact_table (the
interpolant's, one-sided on its cell edges); a central difference for
FASTSIM and the exact theory (tolerance 1e-2 relative). A parameter as a known is fmi2Error naming it. With
hertz_contact, creepages_from_kinematics, creep_relaxation or a Polach 2005 traction law on (one patch), the call
is fmi2Error (“directional derivatives are not available with …”). With contact_geometry = profiles: the
central difference of the wheel's outputs over a step of 10 µm, 10 µrad, 10 µm/s, 10 N of the inputs (one-sided
where the patches change within it), within 0.1 % of the outputs' own differences on the tread and the
flange.</li>
<li>Not supported (declared false; the functions return fmi2Error saying so): input interpolation, output
derivatives, asynchronous steps.</li>
<li>Logging: messages go to the master's logger as "%s" plus text, with its componentEnvironment. With debug
logging off, only warnings, discards, errors and fatal errors are sent; fmi2SetDebugLogging(true, categories)
selects categories (logStatusWarning, logStatusDiscard, logStatusError, logStatusFatal, logCalls; logAll or no
category selects all).</li>
<li>A panic inside the FMU (a bug) is caught at the C boundary: fmi2Fatal, logged, and the instance can then only
be freed. Instances are independent; there is no global state.</li>
</ul>
</body></html>
"#,
        table = variables_table(&VARIABLES, UNITS),
        options = OPTIONS_HTML
            .replace("{model_list}", &model_list_html())
            .replace("{option_table}", &option_table_html())
            .replace("{profile_figures}", &profile_figure::DISPLACEMENTS.map(profile_figure::figure).concat())
            .replace(
                "{non_hertzian_figures}",
                &non_hertzian_figure::DISPLACEMENTS.map(non_hertzian_figure::figures).concat()
            ),
        dependencies = dependencies_list(&VARIABLES),
        q = scene.normal_force / 1e3,
        a = scene.semi_axis_a * 1e3,
        b = scene.semi_axis_b * 1e3,
        mu = scene.friction_coefficient,
        g = scene.shear_modulus / 1e9,
        nu = scene.poisson_ratio,
        xi = scene.creepage_longitudinal,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_platforms_section_states_what_the_binaries_need() {
        let zig = BinaryNote::Linux64 { glibc: (2, 28), baseline_applied: true };
        let plain = BinaryNote::Linux64 { glibc: (2, 35), baseline_applied: false };
        let html = index_html(&[zig, BinaryNote::Win64 { linked_by_zig: true }]);
        assert!(html.contains("needs glibc ≥ 2.28 (the newest glibc symbol version it uses; built against"));
        assert!(html.contains("<b>win64</b>") && !html.contains("No win64 binary"));
        let html = index_html(&[plain]);
        assert!(html.contains("needs glibc ≥ 2.35 (the newest glibc symbol version it uses; built with plain cargo"));
        assert!(html.contains("No win64 binary in this build") && !html.contains("glibc ≥ 2.28"));
    }

    #[test]
    fn every_variable_is_documented_with_its_unit() {
        let html = index_html(&[BinaryNote::Win64 { linked_by_zig: true }]);
        for variable in &VARIABLES {
            assert!(html.contains(&format!("<td><code>{}</code></td>", variable.name)), "{}", variable.name);
        }
        assert!(html.contains("N (shown in kN: 1 N = 0.001 kN)"));
        assert!(html.contains("<svg") && html.contains("eq. (34)") && html.contains("[E4]"));
    }

    /// The profile mode has its section, with the figure at both displacements: the default
    /// curve's plot, two of the profiles in contact, and the non-Hertzian patches' shape and
    /// pressure at two poses.
    #[test]
    fn the_profile_mode_is_documented_with_its_figure() {
        let html = index_html(&[BinaryNote::Win64 { linked_by_zig: true }]);
        assert!(html.contains("<h2>Contact from profiles (parameter <code>contact_geometry</code>)</h2>"));
        assert!(html
            .contains("<h3>Non-Hertzian contact (parameter <code>contact_method</code>) and measured profiles</h3>"));
        assert_eq!(html.matches("<svg").count(), 7);
        assert!(html.contains("right wheel, y_ws = 2 mm") && html.contains("right wheel, y_ws = 7 mm"));
        assert!(html.contains("y_ws = 0 mm, 10 kN: the patches in plan view"));
        assert!(html.contains("y_ws = 5 mm, 10 kN: the pressure along x = 0"));
        assert!(!html.contains("{profile_figures}") && !html.contains("{non_hertzian_figures}"));
    }

    #[test]
    fn default_curves_oppose_the_creepage_and_stay_below_the_friction_limit() {
        let limit = default_contact_input().friction_limit() / 1e3;
        for series in default_curves() {
            assert_eq!(series.points[0], (0.0, 0.0));
            assert!(series.points[1..].iter().all(|&(_, force)| force < 0.0 && force > -limit));
        }
    }
}
