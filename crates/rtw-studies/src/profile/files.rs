//! A profile's files: `FILE.parquet` (one row per simulated slope, the
//! columns of a scan's rows, the profile as JSON in its metadata,
//! [`META_PROFILE`]) and its summary `FILE.md`, written together
//! ([`FileSet`]) after the outputs were checked to be a profile's own.

use super::{Profile, Settings};
use anyhow::Result;
use rtw_engine::config::variant::ModelChoices;
use rtw_engine::files::FileSet;
use rtw_engine::io::destination::{self, Output, summary_path};
use rtw_engine::io::metadata::{
    FileKind, META_OPTIONS, META_PARAMS, META_PROFILE, META_VARIANT, META_VERSION, META_WALL_TIME,
    kv,
};
use rtw_engine::io::parquet;
use rtw_engine::io::scan_rows::schema_for;
use rtw_engine::scan::Run;
use rtw_engine::scan::lock::Lock;
use rtw_model::{Label, Options};
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

/// The first words of a profile's summary: how a summary rtw-scan wrote is
/// told from one it did not.
const HEADING: &str = "# Slope profile of ";

/// Refuses, unless `force`, to write a profile at `out` (and its summary)
/// over files that are not a profile's (a profile with other robustness
/// columns included); removes stray temporary files.
pub(crate) fn check_outputs(out: &Path, options: &Options, force: bool) -> Result<()> {
    let files_ = [Output {
        path: out.to_path_buf(),
        flag: "--out",
        schema: schema_for(&options.robustness),
    }];
    destination::check_outputs(
        out,
        &files_,
        FileKind::Profile,
        "a slope profile",
        |first| first.starts_with(HEADING),
        force,
    )
}

/// The profile of `settings` (see [`super::run`]) written to `out` and its
/// summary `out.md`, both or neither; the outputs are checked before any
/// run (refused, unless `force`, over files that are not a profile's).
pub fn run_to_files(
    settings: &Settings,
    options: &Options,
    out: &Path,
    force: bool,
    run: &Run,
) -> Result<Profile> {
    let _lock = Lock::for_result(out, &format!("writing the profile {}", out.display()))?;
    check_outputs(out, options, force)?;
    let t0 = Instant::now();
    let profile = super::run(settings, options, run)?;
    let wall = t0.elapsed().as_secs_f64();
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let meta = vec![
        kv(META_VERSION, rtw_engine::io::metadata::VERSION.into()),
        kv(META_PROFILE, profile.to_json().to_string()),
        kv(META_PARAMS, serde_json::to_string(&settings.design)?),
        kv(META_OPTIONS, toml::to_string(options)?),
        kv(META_VARIANT, ModelChoices::of(options).to_string()),
        kv(META_WALL_TIME, format!("{wall:.3}")),
    ];
    let mut set = FileSet::default();
    parquet::add_file(&mut set, out, &profile.table(), meta)?;
    set.add_bytes(&summary_path(out), markdown(&profile).as_bytes())?;
    set.commit()?;
    Ok(profile)
}

/// Digits after the point that show a slope to its tolerance.
fn digits(tol: f64) -> usize {
    ((-tol.log10()).ceil() as usize + 1).clamp(3, 12)
}

/// The profile in words: the design and range, the segments, the stable
/// intervals per gait, `phi_min`, the widest stable interval and the
/// changes. `rtw-scan profile` prints it; it is `FILE.md`.
pub fn markdown(p: &Profile) -> String {
    let s = &p.settings;
    let d = digits(s.tol);
    let f = |v: f64| format!("{v:.d$}");
    let interval = |(lo, hi): (f64, f64)| format!("[{}, {}]", f(lo), f(hi));
    let mut md = String::new();
    let _ = writeln!(
        md,
        "{HEADING}L = {} m, ρ = {} kg/m, α = {}, f_n = {} Hz, ζ = {}\n",
        s.design.length, s.design.rho, s.design.alpha, s.design.f_n, s.design.zeta
    );
    let _ = writeln!(
        md,
        "φ from {} to {} rad, grid {} rad, each change of label located to {} rad by \
         bisection: {} runs ({} on the grid).\n",
        s.from,
        s.to,
        s.grid,
        s.tol,
        p.runs(),
        p.coarse_runs
    );
    let _ = writeln!(md, "| gait | stable slopes φ [rad] |\n|---|---|");
    for l in Label::ALL.into_iter().filter(|l| l.is_stable()) {
        let v: Vec<String> = p.intervals(l).into_iter().map(interval).collect();
        let shown = if v.is_empty() {
            "none".to_string()
        } else {
            v.join(", ")
        };
        let _ = writeln!(md, "| {} | {shown} |", l.as_str());
    }
    let _ = writeln!(md);
    match p.phi_min() {
        Some(m) if m == s.from => {
            let _ = writeln!(
                md,
                "phi_min = {} rad: stable from the range's start (it may be stable below)",
                f(m)
            );
        }
        Some(m) => {
            let _ = writeln!(md, "phi_min = {} rad (the shallowest stable slope)", f(m));
        }
        None => {
            let _ = writeln!(md, "phi_min: no stable slope in the range");
        }
    }
    if let Some((lo, hi)) = p.widest() {
        let _ = writeln!(
            md,
            "\nwidest interval of stable slopes: phi_lo = {}, phi_hi = {} ({} rad wide)",
            f(lo),
            f(hi),
            f(hi - lo)
        );
    }
    let _ = writeln!(
        md,
        "\n| φ_left | φ_right | label_left | label_right | one tol below / above | sharp |\n\
         |---|---|---|---|---|---|"
    );
    for c in &p.changes {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} / {} | {} |",
            f(c.phi_left),
            f(c.phi_right),
            c.label_left.as_str(),
            c.label_right.as_str(),
            c.label_below.as_str(),
            c.label_above.as_str(),
            if c.sharp() { "yes" } else { "no" }
        );
    }
    if p.changes.iter().any(|c| !c.sharp()) {
        let _ = writeln!(
            md,
            "\nA change that is not sharp has other labels one tol either side of its bracket's \
             middle: there the labels interleave at scales below tol, and the bracket holds one \
             change of a band of them."
        );
    }
    let _ = writeln!(md, "\n| label | φ from | φ to | runs |\n|---|---|---|---|");
    for g in &p.segments {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} |",
            g.label.as_str(),
            f(g.lo),
            f(g.hi),
            g.runs
        );
    }
    md
}
