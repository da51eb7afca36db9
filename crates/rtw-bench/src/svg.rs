//! A small SVG line chart (log or linear axes, one polyline per series,
//! panels side by side): enough for the work–precision plot without a
//! plotting dependency.

use std::fmt::Write;

/// One series: a name for the legend, a colour, and its points.
pub struct Series {
    pub name: String,
    pub color: &'static str,
    pub points: Vec<(f64, f64)>,
}

/// One panel: title, axis labels, which axes are logarithmic, the series.
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_log: bool,
    pub y_log: bool,
    pub series: Vec<Series>,
}

const W: f64 = 460.0;
const H: f64 = 360.0;
const LEFT: f64 = 70.0;
const RIGHT: f64 = 20.0;
const TOP: f64 = 40.0;
const BOTTOM: f64 = 55.0;

/// An axis mapping data to pixels.
#[derive(Clone, Copy, Debug)]
struct Axis {
    lo: f64,
    hi: f64,
    log: bool,
}

impl Axis {
    /// Covers the finite (and, on a log axis, positive) values; whole decades
    /// on a log axis.
    fn fit(values: impl Iterator<Item = f64>, log: bool) -> Self {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if !lo.is_finite() {
            (lo, hi) = if log { (1.0, 10.0) } else { (0.0, 1.0) };
        }
        if log {
            let (a, b) = (lo.log10().floor(), hi.log10().ceil());
            Self {
                lo: 10f64.powf(a),
                hi: 10f64.powf(if b > a { b } else { a + 1.0 }),
                log,
            }
        } else {
            let pad = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
            Self {
                // Non-negative data (errors, counts) start at 0.
                lo: if lo >= 0.0 { 0.0 } else { lo - pad },
                hi: hi + pad,
                log,
            }
        }
    }

    /// Position in [0, 1] along the axis.
    fn frac(&self, v: f64) -> f64 {
        if self.log {
            (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }

    /// Tick values: every decade (log) or 5 steps (linear).
    fn ticks(&self) -> Vec<f64> {
        if self.log {
            let (a, b) = (
                self.lo.log10().round() as i32,
                self.hi.log10().round() as i32,
            );
            let step = ((b - a) as f64 / 8.0).ceil().max(1.0) as usize;
            (a..=b).step_by(step).map(|e| 10f64.powi(e)).collect()
        } else {
            (0..=5)
                .map(|k| self.lo + (self.hi - self.lo) * k as f64 / 5.0)
                .collect()
        }
    }
}

fn tick_text(v: f64, log: bool) -> String {
    if log {
        format!("1e{}", v.log10().round() as i32)
    } else if v.abs() >= 10.0 || v == 0.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.2}")
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Renders the panels side by side, with a title above.
pub fn render(title: &str, panels: &[Panel]) -> String {
    let width = W * panels.len() as f64;
    let height = H + 30.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="20" text-anchor="middle" font-size="15">{}</text>"#,
        width / 2.0,
        esc(title)
    );
    for (p, panel) in panels.iter().enumerate() {
        let ox = W * p as f64;
        let oy = 30.0;
        let pw = W - LEFT - RIGHT;
        let ph = H - TOP - BOTTOM;
        let pts = || panel.series.iter().flat_map(|s| s.points.iter());
        let xa = Axis::fit(pts().map(|p| p.0), panel.x_log);
        let ya = Axis::fit(pts().map(|p| p.1), panel.y_log);
        let px = |v: f64| ox + LEFT + pw * xa.frac(v);
        let py = |v: f64| oy + TOP + ph * (1.0 - ya.frac(v));
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle" font-size="13">{}</text>"#,
            ox + LEFT + pw / 2.0,
            oy + TOP - 12.0,
            esc(&panel.title)
        );
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{pw}" height="{ph}" fill="none" stroke="#444"/>"##,
            ox + LEFT,
            oy + TOP
        );
        for v in xa.ticks() {
            let x = px(v);
            let _ = writeln!(
                s,
                r##"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="#ddd"/><text x="{x}" y="{}" text-anchor="middle">{}</text>"##,
                oy + TOP,
                oy + TOP + ph,
                oy + TOP + ph + 16.0,
                tick_text(v, xa.log)
            );
        }
        for v in ya.ticks() {
            let y = py(v);
            let _ = writeln!(
                s,
                r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#ddd"/><text x="{}" y="{}" text-anchor="end">{}</text>"##,
                ox + LEFT,
                ox + LEFT + pw,
                ox + LEFT - 5.0,
                y + 4.0,
                tick_text(v, ya.log)
            );
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
            ox + LEFT + pw / 2.0,
            oy + H - 18.0,
            esc(&panel.x_label)
        );
        let _ = writeln!(
            s,
            r#"<text transform="translate({},{}) rotate(-90)" text-anchor="middle">{}</text>"#,
            ox + 16.0,
            oy + TOP + ph / 2.0,
            esc(&panel.y_label)
        );
        for (k, series) in panel.series.iter().enumerate() {
            let visible: Vec<(f64, f64)> = series
                .points
                .iter()
                .copied()
                .filter(|&(x, y)| {
                    x.is_finite() && y.is_finite() && (!xa.log || x > 0.0) && (!ya.log || y > 0.0)
                })
                .collect();
            let path: Vec<String> = visible
                .iter()
                .map(|&(x, y)| format!("{:.1},{:.1}", px(x), py(y)))
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="1.5"/>"#,
                path.join(" "),
                series.color
            );
            for &(x, y) in &visible {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{:.1}" cy="{:.1}" r="3" fill="{}"/>"#,
                    px(x),
                    py(y),
                    series.color
                );
            }
            let ly = oy + TOP + 14.0 + 16.0 * k as f64;
            let lx = ox + LEFT + pw - 110.0;
            let _ = writeln!(
                s,
                r#"<line x1="{lx}" y1="{ly}" x2="{}" y2="{ly}" stroke="{}" stroke-width="2"/><text x="{}" y="{}">{}</text>"#,
                lx + 18.0,
                series.color,
                lx + 23.0,
                ly + 4.0,
                esc(&series.name)
            );
        }
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_axis_spans_whole_decades_and_maps_ends() {
        let a = Axis::fit([3e-7, 2e-3].into_iter(), true);
        assert_eq!((a.lo, a.hi), (1e-7, 1e-2));
        assert!((a.frac(1e-7)).abs() < 1e-12 && (a.frac(1e-2) - 1.0).abs() < 1e-12);
        // Non-positive and non-finite values are left out of a log axis.
        let b = Axis::fit([0.0, f64::INFINITY, 5.0].into_iter(), true);
        assert_eq!((b.lo, b.hi), (1.0, 10.0));
    }

    #[test]
    fn render_draws_every_visible_point() {
        let panel = Panel {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            x_log: true,
            y_log: false,
            series: vec![Series {
                name: "a<b".into(),
                color: "red",
                points: vec![(1.0, 1.0), (10.0, 2.0), (0.0, 3.0)],
            }],
        };
        let svg = render("T", &[panel]);
        assert_eq!(svg.matches("<circle").count(), 2, "x = 0 is off a log axis");
        assert!(svg.contains("a&lt;b"));
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    }
}
