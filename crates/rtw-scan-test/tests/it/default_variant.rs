//! rtw's default model is the variant the study's admissibility rule picks
//! (docs/model.md §9, results/variants/summary.md): the committed
//! `results/variants/summary.json` names the rule's pick (`chosen`) and the
//! variant the figures and the report call the default (`default`, from
//! `scripts/figures.py`). Both must be the same variant, and that variant's
//! file, layered over nothing, must give exactly `Options::default()`: a
//! rerun of the study that picks another rest length, or a default changed
//! without rerunning it, fails here.

use rtw_engine::config::layers::{Overrides, simulation_options};
use rtw_model::Options;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn summary_field(key: &str) -> String {
    let path = root().join("results/variants/summary.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json[key]
        .as_str()
        .unwrap_or_else(|| panic!("{}: `{key}` is not a variant name", path.display()))
        .to_string()
}

#[test]
fn the_default_model_is_the_variant_the_rule_picks() {
    let chosen = summary_field("chosen");
    let file = root()
        .join("configs/variants")
        .join(format!("{chosen}.toml"));
    let picked = simulation_options(None, Some(&file), Overrides::NONE).unwrap();
    assert_eq!(
        picked,
        Options::default(),
        "rtw's default model differs from the rule's pick {chosen} ({})",
        file.display()
    );
}

#[test]
fn the_figures_default_is_the_variant_the_rule_picks() {
    assert_eq!(
        summary_field("default"),
        summary_field("chosen"),
        "scripts/rtwscripts/__init__.py's DEFAULT_VARIANT (the figures' default) is not the rule's pick"
    );
}

/// `configs/paper.toml` spells the default model out (so that its results
/// mean the same whatever the defaults): it must spell out this default.
#[test]
fn the_paper_scan_runs_the_default_model() {
    let file = root().join("configs/paper.toml");
    let paper = simulation_options(Some(&file), None, Overrides::NONE).unwrap();
    assert_eq!(paper, Options::default(), "{}", file.display());
}
