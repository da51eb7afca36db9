//! Writing the benchmark's results: the Markdown report (every table, the
//! default chosen by measurement) and the work–precision SVG.

use super::*;
use rtw_engine::config::variant_line;

/// The model of `o`, from its `rtw.variant` line (`rtw_engine::config::variant_line`):
/// its name where its model (the line before ` method=`) is the default's or
/// the literal model's, and the line itself. The report states the model each
/// part ran at from the options it used, so that nothing it calls the default
/// model is another (scripts/check_default_model.py holds a "default model"
/// followed by its line to the default's).
pub(crate) fn model_of(o: &Options) -> (&'static str, String) {
    let line = variant_line(o);
    let model = |l: &str| l.split(" method=").next().unwrap_or_default().to_string();
    let name = if model(&line) == model(&variant_line(&Options::default())) {
        "default model"
    } else if model(&line) == model(&variant_line(&Options::literal())) {
        "literal model"
    } else {
        "model"
    };
    (name, line)
}

/// A case's options at the reference setting, which every row changes only
/// in its method, tolerances and step cap.
fn case_reference_options(case: &Case) -> Options {
    REFERENCE.apply(&case_options(case.variant))
}

/// The Markdown report of what [`measure`] found.
pub(crate) fn report(m: &Measured) -> String {
    let mut md = String::new();
    let command = if m.quick {
        "cargo run --release -p rtw-bench -- --quick"
    } else {
        "cargo run --release -p rtw-bench"
    };
    let _ = writeln!(md, "# Work–precision benchmark\n");
    let _ = writeln!(
        md,
        "Made by `{command}` on a machine with {} logical cores ({} worker threads). \
         Reference: DOP853 at rtol 1e-13, atol 1e-15. Adaptive settings use atol = rtol/100; \
         every setting has no step cap (h_max = inf) and t_max = 20 s. Wall times are medians of {} \
         runs, one thread.\n",
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        rayon::current_num_threads(),
        m.reps,
    );
    report_cases(&mut md, m);
    report_scan(&mut md, m);
    report_choice(&mut md, m);
    md
}

/// The fixed cases' section.
fn report_cases(md: &mut String, m: &Measured) {
    let _ = writeln!(md, "## Fixed cases\n");
    let _ = writeln!(
        md,
        "State error: largest |Δ| of the full coordinates (x, y, θ, ẋ, ẏ, ω of each rod) \
         just before each of the first {FIRST_EVENTS} events, and at t = {T_FIX} s; \
         event-time error: largest |Δt| of the first {FIRST_EVENTS} touchdowns; f_w error \
         relative; fractions: largest |Δ| of NLSP/SLSP/DLSP/TLSP.\n"
    );
    for (case, result) in m.cases.iter().zip(&m.case_results) {
        let p = case.params;
        let (name, line) = model_of(&case_reference_options(case));
        let _ = writeln!(
            md,
            "### {} (ρ {:.4}, α {:.4}, f_n {:.4}, ζ {:.4}, φ {:.4}; {name})\n",
            case.name, p.rho, p.alpha, p.f_n, p.zeta, p.phi
        );
        let _ = writeln!(
            md,
            "Model: {name}, `{line}` (the reference's settings; each row changes the method, \
             its tolerances and the step cap only).\n"
        );
        let r = &result.reference.out;
        let _ = writeln!(
            md,
            "Reference: **{}**, f_w {:.4} Hz, NLSP/SLSP/DLSP/TLSP {:.3}/{:.3}/{:.3}/{:.3}, \
             period {}, t_end {:.3} s, {} RHS evaluations.\n",
            r.label.as_str(),
            r.f_w,
            r.fractions.nlsp,
            r.fractions.slsp,
            r.fractions.dlsp,
            r.fractions.tlsp,
            r.period,
            r.t_end,
            r.work.rhs_evals
        );
        let _ = writeln!(
            md,
            "| setting | median ms | RHS evals | label | state err, {FIRST_EVENTS} events | \
             touchdown time err (s) | state err at {T_FIX} s | f_w rel err | fraction err |"
        );
        let _ = writeln!(md, "|---|---:|---:|---|---:|---:|---:|---:|---:|");
        for row in &result.rows {
            let _ = writeln!(
                md,
                "| {} | {:.2} | {} | {}{} | {} | {} | {} | {} | {:.1e} |",
                row.setting.name(),
                row.run.ms,
                row.run.out.work.rhs_evals,
                row.run.out.label.as_str(),
                if row.run.out.label == r.label {
                    ""
                } else {
                    " ≠"
                },
                sci(row.event_err),
                sci(row.time_err),
                sci(row.fix_err),
                sci(row.fw_err),
                row.fraction_err
            );
        }
        md.push('\n');
    }
}

/// The scan's section.
fn report_scan(md: &mut String, m: &Measured) {
    let n_scan = m.scan.len();
    let (name, line) = model_of(&REFERENCE.apply(&m.scan_options));
    let _ = writeln!(md, "## Scan: {n_scan} samples of the paper's box, {name}\n");
    let _ = writeln!(
        md,
        "`configs/bench/scan200.toml` (docs/model.md §8's box at L = 0.8: the inputs of the first {n_scan} samples of `configs/paper.toml`). \
         Model: {name}, `{line}` (the reference's settings; each row changes the method, its tolerances and the step cap only). \
         CPU s: the sum of the per-sample times; wall s: the whole scan on the worker threads. \
         Outcome % per label, largest |Δ| against the reference (pp), labels that differ \
         (flips), median relative f_w error over samples stable in both with the same label.\n"
    );
    let labels: Vec<&str> = Label::ALL.iter().map(|l| l.as_str()).collect();
    let _ = writeln!(
        md,
        "| setting | RHS evals | CPU s | wall s | max Δ (pp) | flips | median f_w err | {} |",
        labels.join(" % | ") + " %"
    );
    let _ = writeln!(
        md,
        "|---|---:|---:|---:|---:|---:|---:|{}",
        "---:|".repeat(6)
    );
    let pct = |p: &[f64; 6]| {
        p.iter()
            .map(|v| format!("{v:.1}"))
            .collect::<Vec<_>>()
            .join(" | ")
    };
    let reference = &m.reference;
    let self_diff = compare_scans(&reference.points, &reference.points);
    let _ = writeln!(
        md,
        "| **{} (reference)** | {} | {:.2} | {:.2} | – | – | – | {} |",
        REFERENCE.name(),
        reference.rhs,
        reference.cpu_s,
        reference.wall_s,
        pct(&self_diff.percent)
    );
    for (setting, run, diff) in &m.scans {
        let _ = writeln!(
            md,
            "| {} | {} | {:.2} | {:.2} | {:.1} | {} | {:.1e} | {} |",
            setting.name(),
            run.rhs,
            run.cpu_s,
            run.wall_s,
            diff.max_pp,
            diff.flips.len(),
            diff.median_fw_rel,
            pct(&diff.percent)
        );
    }
    let _ = writeln!(
        md,
        "\nThe samples whose label differs from the reference:\n"
    );
    for (setting, _, diff) in &m.scans {
        let flips: Vec<String> = diff
            .flips
            .iter()
            .map(|(i, a, b)| format!("#{i} {}→{}", a.as_str(), b.as_str()))
            .collect();
        let _ = writeln!(
            md,
            "* {}: {}",
            setting.name(),
            if flips.is_empty() {
                "none".to_string()
            } else {
                flips.join(", ")
            }
        );
    }
}

/// The chosen default's section and its early-stop comparison.
fn report_choice(md: &mut String, m: &Measured) {
    let _ = writeln!(md, "\n## The default, by measurement\n");
    let Some((best, best_run, best_diff)) = m.chosen.map(|i| &m.scans[i]) else {
        let _ = writeln!(md, "No setting meets the criteria.");
        return;
    };
    let _ = writeln!(
        md,
        "The cheapest setting (fewest RHS evaluations over the scan) whose scan outcome \
         fractions stay within 1 pp of the reference, whose median f_w error over the scan is \
         below 1 % and whose f_w at the Fig. 7(a) walk errs by less than 1 %: **{}** ({} RHS \
         evaluations, {:.1}× fewer than the reference; {:.2} CPU s against {:.2}; max Δ {:.1} pp, \
         {} flips, median f_w error {:.1e}, Fig. 7(a) f_w error {:.1e}).\n",
        best.name(),
        best_run.rhs,
        m.reference.rhs as f64 / best_run.rhs as f64,
        best_run.cpu_s,
        m.reference.cpu_s,
        best_diff.max_pp,
        best_diff.flips.len(),
        best_diff.median_fw_rel,
        m.walk_fw_err(best)
    );
    for (i, _, _) in &best_diff.flips {
        let p = m.scan[*i];
        let _ = writeln!(
            md,
            "* flip #{i}: ρ {:.3}, α {:.3}, f_n {:.3}, ζ {:.3}, φ {:.3}",
            p.rho, p.alpha, p.f_n, p.zeta, p.phi
        );
    }
    let _ = writeln!(
        md,
        "\n## Early stop (`stop_when_settled`) at {}\n",
        best.name()
    );
    let _ = writeln!(
        md,
        "Each scan run at the chosen setting with and without the early stop; CPU s summed over \
         samples; Δ and flips of the early-stopped scan against the full-length one; stopped \
         early: stable samples whose run ended before t_max.\n"
    );
    let _ = writeln!(
        md,
        "| scan | samples | full RHS evals | early RHS evals | work ratio | full CPU s | early CPU s | max Δ (pp) | flips | stopped early |"
    );
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for e in &m.early {
        let _ = writeln!(
            md,
            "| `{}` | {} | {} | {} | {:.2}× | {:.2} | {:.2} | {:.1} | {} | {} |",
            e.name,
            e.samples,
            e.full.rhs,
            e.early.rhs,
            e.full.rhs as f64 / e.early.rhs as f64,
            e.full.cpu_s,
            e.early.cpu_s,
            e.diff.max_pp,
            e.diff.flips.len(),
            e.stopped
        );
    }
}

const COLORS: [(&str, &str); 3] = [
    ("rk4", "#d62728"),
    ("dp54", "#1f77b4"),
    ("dop853", "#2ca02c"),
];

fn by_method(points: impl Iterator<Item = (Setting, f64, f64)> + Clone) -> Vec<Series> {
    COLORS
        .iter()
        .map(|&(m, color)| Series {
            name: m.to_string(),
            color,
            points: points
                .clone()
                .filter(|(s, _, _)| s.method_name() == m)
                .map(|(_, x, y)| (x, y))
                .collect(),
        })
        .collect()
}

/// Writes the report and the work–precision plot of `m` into `dir`.
pub(crate) fn write_out(dir: &Path, md: &str, m: &Measured) -> Result<()> {
    let (plot_cases, cases, scans) = (m.plot_cases(), &m.cases, &m.scans);
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let mut panels = vec![];
    for ci in [0, 3] {
        panels.push(Panel {
            title: format!(
                "{} ({})",
                cases[ci].name,
                model_of(&case_reference_options(&cases[ci])).0
            ),
            x_label: format!("state error over the first {FIRST_EVENTS} events"),
            y_label: "median wall time per 20 s run (ms)".into(),
            x_log: true,
            y_log: true,
            series: by_method(plot_cases[ci].iter().copied()),
        });
    }
    panels.push(Panel {
        title: format!(
            "scan of {} samples ({})",
            scans.first().map_or(0, |s| s.1.points.len()),
            model_of(&REFERENCE.apply(&m.scan_options)).0
        ),
        x_label: "largest outcome-fraction error (pp)".into(),
        y_label: "CPU time of the scan (s)".into(),
        x_log: false,
        y_log: true,
        series: by_method(scans.iter().map(|(s, r, d)| (*s, d.max_pp, r.cpu_s))),
    });
    let svg = render(
        "Work against precision (reference: DOP853, rtol 1e-13)",
        &panels,
    );
    let md_path = dir.join("work-precision.md");
    std::fs::write(&md_path, md).with_context(|| format!("writing {}", md_path.display()))?;
    let svg_path = dir.join("work-precision.svg");
    std::fs::write(&svg_path, svg).with_context(|| format!("writing {}", svg_path.display()))?;
    eprintln!("wrote {} and {}", md_path.display(), svg_path.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The report names a model from its options, whatever the run's
    /// integrator settings: the default's and the literal model's by name,
    /// any other (such as the default before its strings were fitted) not.
    #[test]
    fn model_of_names_the_model_the_options_are_at() {
        let reference = |o: Options| REFERENCE.apply(&o);
        let (name, line) = model_of(&reference(Options::default()));
        assert_eq!(name, "default model");
        assert!(line.contains("method=dop853 rtol=1e-13"), "{line}");
        assert!(line.starts_with(&format!(
            "rest_length_ratio={} ",
            Options::default().strings.rest_length_ratio
        )));
        assert_eq!(
            model_of(&case_options("default")).0,
            "default model",
            "20 s without a cap or an early stop is a run setting, not a model"
        );
        assert_eq!(model_of(&reference(Options::literal())).0, "literal model");
        let mut old = Options::default();
        old.strings.rest_length_ratio = 0.85;
        let (name, line) = model_of(&old);
        assert_eq!(name, "model");
        assert!(line.starts_with("rest_length_ratio=0.85 "), "{line}");
    }
}
