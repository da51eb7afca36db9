//! The library without its command line: clap, ctrlc and indicatif come
//! only with the `cli` feature, which only the `rtw-scan` binary needs, and
//! the crates that use the library (rtw-py, the Python extension; rtw-bench)
//! take it without that feature. `cargo tree -p rtw-py -e normal` is the
//! check by hand; this one reads the manifests, so it runs offline and fast.

use std::path::Path;

fn manifest(rel: &str) -> toml::Table {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    let text = std::fs::read_to_string(&path).unwrap();
    text.parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn table<'a>(t: &'a toml::Table, key: &str) -> &'a toml::Table {
    t.get(key)
        .and_then(toml::Value::as_table)
        .unwrap_or_else(|| panic!("no table `{key}`"))
}

const TERMINAL: [&str; 3] = ["clap", "ctrlc", "indicatif"];

#[test]
fn the_terminal_crates_come_only_with_the_cli_feature() {
    let m = manifest("Cargo.toml");
    let deps = table(&m, "dependencies");
    for name in TERMINAL {
        let optional = deps
            .get(name)
            .and_then(|d| d.get("optional"))
            .and_then(toml::Value::as_bool);
        assert_eq!(optional, Some(true), "{name} must be optional");
    }
    let features = table(&m, "features");
    let cli: Vec<&str> = features["cli"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(toml::Value::as_str)
        .collect();
    for name in TERMINAL {
        assert!(cli.contains(&format!("dep:{name}").as_str()), "{cli:?}");
    }
    let bins = m["bin"].as_array().unwrap();
    // Every binary needs the command line (the test binary `fake-sim` too).
    for bin in bins {
        let needs: Vec<&str> = bin
            .get("required-features")
            .and_then(toml::Value::as_array)
            .map(|a| a.iter().filter_map(toml::Value::as_str).collect())
            .unwrap_or_default();
        assert!(needs.contains(&"cli"), "{bin:?}");
    }
}

#[test]
fn the_library_s_users_take_it_without_the_cli_feature() {
    let ws = manifest("../../Cargo.toml");
    let workspace = table(&ws, "workspace");
    let scan = &table(workspace, "dependencies")["rtw-scan"];
    assert_eq!(
        scan.get("default-features").and_then(toml::Value::as_bool),
        Some(false),
        "the workspace's rtw-scan dependency: {scan}"
    );
    for user in ["../rtw-py/Cargo.toml", "../rtw-bench/Cargo.toml"] {
        let m = manifest(user);
        let dep = &table(&m, "dependencies")["rtw-scan"];
        assert_eq!(
            dep.get("workspace").and_then(toml::Value::as_bool),
            Some(true),
            "{user}: {dep}"
        );
        let features = dep.get("features").map(ToString::to_string);
        assert!(
            !features.as_deref().unwrap_or("").contains("cli"),
            "{user}: {dep}"
        );
        assert!(dep.get("default-features").is_none(), "{user}: {dep}");
    }
}

/// The tests run `rtw-scan-test`, the command built with `fake-sim`, whose
/// name a plain build never writes: a user's `cargo run --release -p
/// rtw-scan` beside the test command re-links `target/release/rtw-scan`, and
/// a test that ran that file would meet a binary without `--fake-sim`. The
/// test binary must require the feature, and no test may name the plain one.
#[test]
fn the_tests_run_a_binary_that_a_plain_build_never_overwrites() {
    let m = manifest("Cargo.toml");
    let bins = m["bin"].as_array().expect("[[bin]] targets");
    let test_bin = bins
        .iter()
        .find(|b| b["name"].as_str() == Some("rtw-scan-test"))
        .expect("a [[bin]] named rtw-scan-test");
    let needs: Vec<&str> = test_bin["required-features"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(toml::Value::as_str)
        .collect();
    assert!(
        needs.contains(&"fake-sim"),
        "rtw-scan-test must require fake-sim: {needs:?}"
    );
    // With two binaries, `cargo run --release -p rtw-scan` (the README's
    // main command) must still know which one to run.
    assert_eq!(
        table(&m, "package")
            .get("default-run")
            .and_then(toml::Value::as_str),
        Some("rtw-scan"),
        "rtw-scan's [package] needs default-run = \"rtw-scan\""
    );
    let plain = concat!("CARGO_BIN_EXE_", "rtw-scan\"");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/it");
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            !text.contains(plain),
            "{} runs the plain rtw-scan binary, which a build beside the tests can replace: use common::bin()",
            path.display()
        );
    }
}
