//! Gives the crate `RTW_BUILD_ID`: the identity of the sources that make
//! its numbers (`build_id.rs`), which `rtw.version` carries after the
//! crate's version. Two builds that could compute different rows never
//! share a version, so a run never resumes from, or merges, another build's
//! rows (docs/results-on-disk.md, "Versions").

include!("build_id.rs");

fn main() {
    let here =
        std::path::PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let roots = roots(&here);
    for (_, path) in &roots {
        println!("cargo:rerun-if-changed={}", path.display());
    }
    println!("cargo:rerun-if-changed=build_id.rs");
    let named: Vec<(&str, &std::path::Path)> =
        roots.iter().map(|(n, p)| (*n, p.as_path())).collect();
    println!("cargo:rustc-env=RTW_BUILD_ID={}", sources_id(&named));
}
