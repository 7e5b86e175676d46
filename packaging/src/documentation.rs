//! `documentation/index.html` of the FMU. The variable table is generated from the adapter's
//! own table (itself generated from `modelDescription.xml`), so it cannot drift; the plot is
//! computed with the core library at the default scene.

use std::fmt::Write as _;

use wheel_rail_contact::fmi::model_description::{Causality, Kind, Values, Variable, UNITS, VARIABLES};
use wheel_rail_contact::fmi::scene::contact_input;
use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};

use crate::plot::{escape, line_plot, Series};

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

fn display_unit_text(variable: &Variable) -> String {
    let Some(unit) = variable.unit else { return String::new() };
    match variable.display_unit {
        Some(display) => {
            let factor =
                UNITS.iter().find(|(u, _)| *u == unit).and_then(|(_, d)| d.iter().find(|(n, _)| *n == display));
            let factor = factor.map_or(1.0, |(_, f)| *f);
            format!("{unit} (shown in {display}: 1 {unit} = {factor} {display})")
        }
        None => unit.to_owned(),
    }
}

fn variables_table() -> String {
    let mut html = String::from(
        "<table>\n<tr><th>name</th><th>value reference</th><th>causality</th><th>variability</th>\
         <th>unit</th><th>start</th><th>meaning</th></tr>\n",
    );
    for variable in &VARIABLES {
        let start = match variable.kind {
            Kind::Real { start } => start.map(|s| format!("{s}")).unwrap_or_else(|| "(computed)".into()),
            Kind::Integer { start } => start.map(|s| s.to_string()).unwrap_or_else(|| "(computed)".into()),
            Kind::Enumeration { items, start, .. } => {
                let name = items.iter().find(|(_, value, _)| *value == start).map_or("?", |(name, _, _)| name);
                format!("{start} ({name})")
            }
        };
        let mut meaning = escape(variable.description);
        if let Kind::Enumeration { declared_type, items, .. } = variable.kind {
            write!(meaning, "<br>Enumeration {declared_type}:").unwrap();
            for (name, value, description) in items {
                write!(meaning, "<br>{value} = <code>{name}</code>: {}", escape(description)).unwrap();
            }
        }
        writeln!(
            html,
            "<tr><td><code>{}</code></td><td>{}</td><td>{:?}</td><td>{:?}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            variable.name,
            variable.value_reference,
            variable.causality,
            variable.variability,
            escape(&display_unit_text(variable)),
            start,
            meaning
        )
        .unwrap();
    }
    html.push_str("</table>\n");
    html
}

fn dependencies_text() -> String {
    let mut html = String::from("<ul>\n");
    for output in VARIABLES.iter().filter(|v| v.causality == Causality::Output) {
        let names: Vec<String> = output
            .dependencies
            .iter()
            .filter_map(|r| VARIABLES.iter().find(|v| v.value_reference == *r))
            .map(|v| format!("<code>{}</code>", v.name))
            .collect();
        writeln!(html, "<li><code>{}</code> depends on {}</li>", output.name, names.join(", ")).unwrap();
    }
    html.push_str("</ul>\n");
    html
}

const STYLE: &str = "body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.45}\
table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:0.25em 0.5em;vertical-align:top}\
pre{background:#f5f5f5;padding:0.5em}";

/// The whole page.
pub fn index_html() -> String {
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
<p>The tangential forces of one wheel–rail contact patch — the longitudinal creep force F<sub>x</sub>, the lateral
creep force F<sub>y</sub> and the adhesion utilisation |F|/(μQ) — from the creepages ξ, η, the spin creepage φ,
the normal force Q, the contact-ellipse semi-axes a (rolling direction) and b (lateral), the friction coefficient
μ, and the material constants G and ν. The method is Polách's fast analytical solution (O. Polách, “Solution of
wheel-rail contact forces suitable for calculation of rail vehicle dynamics”), with the contact stiffness either
from Kalker's linear theory or fitted to a measured creep curve. The outputs are algebraic in the inputs: every
fmi2DoStep computes them from the inputs set before the step, so any communication step size is exact.</p>

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

<h2>Behaviour</h2>
<ul>
<li>Invalid values (NaN, ±Inf, a or b ≤ 0, μ &lt; 0, G ≤ 0, ν outside [0, 0.5], an impossible measured curve, an
unknown stiffness_source) are reported where outputs are computed — fmi2ExitInitializationMode, fmi2DoStep, and
fmi2GetReal of an output in initialization mode — as fmi2Error with a message naming the variable and its value.
The instance keeps its state and last valid outputs; once the master sets a good value it continues.</li>
<li>Calls outside the states the standard allows return fmi2Error and log “fmi2XXX: illegal call in state YYY”.</li>
<li>fmi2DoStep requires h &gt; 0 and currentCommunicationPoint equal to the end of the previous step (relative
tolerance 1e-9); with a stop time, no step may end after it. canHandleVariableCommunicationStepSize is true.</li>
<li>FMU state (canGetAndSetFMUstate, canSerializeFMUstate): fmi2GetFMUstate/SetFMUstate copy the instance's mode,
time, every variable's value and the model's internal state; fmi2SerializeFMUstate writes a versioned byte string
(magic “WRCstate”, format version, this FMU's GUID, length, CRC-32, then the state), exactly
fmi2SerializedFMUstateSize bytes. fmi2DeSerializeFMUstate rejects truncated, corrupted, foreign or other-version
byte strings with fmi2Error and the reason, changing nothing.</li>
<li>Directional derivatives (providesDirectionalDerivative): J·v of the outputs with respect to the continuous
inputs at the current values — exact (forward-mode dual numbers) for Polach; a parameter as a known is fmi2Error
naming it.</li>
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
        table = variables_table(),
        dependencies = dependencies_text(),
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
    fn every_variable_is_documented_with_its_unit() {
        let html = index_html();
        for variable in &VARIABLES {
            assert!(html.contains(&format!("<td><code>{}</code></td>", variable.name)), "{}", variable.name);
        }
        assert!(html.contains("N (shown in kN: 1 N = 0.001 kN)"));
        assert!(html.contains("<svg") && html.contains("eq. (34)") && html.contains("[E4]"));
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
