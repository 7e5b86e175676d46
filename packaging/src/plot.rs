//! A small SVG line plot: enough for a creep-force curve, no dependency.

use std::fmt::Write as _;

/// One curve.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

const WIDTH: f64 = 640.0;
const HEIGHT: f64 = 400.0;
const MARGIN: (f64, f64, f64, f64) = (70.0, 20.0, 40.0, 50.0); // left, right, top, bottom
const COLOURS: [&str; 4] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"];

/// Five to ten round tick values covering [low, high].
fn ticks(low: f64, high: f64) -> Vec<f64> {
    let span = (high - low).max(f64::MIN_POSITIVE);
    let raw_step = span / 8.0;
    let magnitude = 10f64.powf(raw_step.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0].iter().map(|m| m * magnitude).find(|s| *s >= raw_step).unwrap_or(magnitude);
    let first = (low / step).ceil() as i64;
    let last = (high / step).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

/// An SVG document with the curves, axes, ticks, labels and a legend.
pub fn line_plot(title: &str, x_label: &str, y_label: &str, series: &[Series]) -> String {
    let all = || series.iter().flat_map(|s| s.points.iter());
    let (mut x_min, mut x_max) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (mut y_min, mut y_max) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.1), b.max(p.1)));
    if x_min >= x_max {
        (x_min, x_max) = (x_min - 1.0, x_min + 1.0);
    }
    if y_min >= y_max {
        (y_min, y_max) = (y_min - 1.0, y_min + 1.0);
    }
    let (left, right, top, bottom) = MARGIN;
    let x = |v: f64| left + (v - x_min) / (x_max - x_min) * (WIDTH - left - right);
    let y = |v: f64| HEIGHT - bottom - (v - y_min) / (y_max - y_min) * (HEIGHT - top - bottom);
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" viewBox=\"0 0 {WIDTH} {HEIGHT}\" \
         font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    writeln!(
        svg,
        "<text x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"14\">{}</text>",
        WIDTH / 2.0,
        escape(title)
    )
    .unwrap();
    for tick in ticks(x_min, x_max) {
        let px = x(tick);
        writeln!(svg, "<line x1=\"{px:.1}\" y1=\"{top}\" x2=\"{px:.1}\" y2=\"{}\" stroke=\"#ddd\"/>", HEIGHT - bottom)
            .unwrap();
        writeln!(
            svg,
            "<text x=\"{px:.1}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            HEIGHT - bottom + 16.0,
            label(tick)
        )
        .unwrap();
    }
    for tick in ticks(y_min, y_max) {
        let py = y(tick);
        writeln!(svg, "<line x1=\"{left}\" y1=\"{py:.1}\" x2=\"{}\" y2=\"{py:.1}\" stroke=\"#ddd\"/>", WIDTH - right)
            .unwrap();
        writeln!(svg, "<text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>", left - 6.0, py + 4.0, label(tick))
            .unwrap();
    }
    writeln!(
        svg,
        "<rect x=\"{left}\" y=\"{top}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>",
        WIDTH - left - right,
        HEIGHT - top - bottom
    )
    .unwrap();
    writeln!(
        svg,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
        WIDTH / 2.0,
        HEIGHT - 10.0,
        escape(x_label)
    )
    .unwrap();
    writeln!(
        svg,
        "<text x=\"16\" y=\"{0}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {0})\">{1}</text>",
        HEIGHT / 2.0,
        escape(y_label)
    )
    .unwrap();
    for (index, curve) in series.iter().enumerate() {
        let colour = COLOURS[index % COLOURS.len()];
        let points: Vec<String> = curve.points.iter().map(|p| format!("{:.2},{:.2}", x(p.0), y(p.1))).collect();
        writeln!(
            svg,
            "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\" points=\"{}\"/>",
            points.join(" ")
        )
        .unwrap();
        let legend_y = top + 18.0 + 18.0 * index as f64;
        writeln!(
            svg,
            "<line x1=\"{0}\" y1=\"{legend_y}\" x2=\"{1}\" y2=\"{legend_y}\" stroke=\"{colour}\" stroke-width=\"2\"/>\
             <text x=\"{2}\" y=\"{3}\">{4}</text>",
            left + 12.0,
            left + 36.0,
            left + 42.0,
            legend_y + 4.0,
            escape(&curve.label)
        )
        .unwrap();
    }
    svg.push_str("</svg>\n");
    svg
}

fn label(value: f64) -> String {
    let text = format!("{:.6}", value);
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_owned()
    } else {
        text.to_owned()
    }
}

/// Escapes text for XML and HTML.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        assert_eq!(ticks(0.0, 1.0), vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]);
        assert_eq!(ticks(-28.3, 0.0), vec![-25.0, -20.0, -15.0, -10.0, -5.0, 0.0]);
    }

    #[test]
    fn plot_has_one_polyline_per_series() {
        let series = [
            Series { label: "a < b".into(), points: vec![(0.0, 0.0), (1.0, 2.0)] },
            Series { label: "c".into(), points: vec![(0.0, 1.0), (1.0, 1.0)] },
        ];
        let svg = line_plot("t", "x", "y", &series);
        assert_eq!(svg.matches("<polyline").count(), 2);
        assert!(svg.contains("a &lt; b") && svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
    }
}
