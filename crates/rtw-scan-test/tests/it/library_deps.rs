//! The crates are the layers (docs/architecture.md): hybrid-ode → rtw-model
//! → rtw-engine → rtw-studies → {rtw-scan, rtw-py, rtw-bench}. Only the
//! command (`rtw-scan`) links clap, ctrlc and indicatif. `cargo tree -p
//! rtw-py -e normal` is the check by hand; this one reads the manifests, so
//! it runs offline and fast.

use std::path::Path;

fn manifest(rel: &str) -> toml::Table {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    let text = std::fs::read_to_string(&path).unwrap();
    text.parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

const TERMINAL: [&str; 3] = ["clap", "ctrlc", "indicatif"];

/// The dependencies (normal and dev) a manifest names.
fn names(m: &toml::Table, key: &str) -> Vec<String> {
    m.get(key)
        .and_then(toml::Value::as_table)
        .map(|t| t.keys().cloned().collect())
        .unwrap_or_default()
}

/// The layers are crates, and cargo holds their direction: the scan engine
/// knows neither the studies nor the command line, the studies not the
/// command line; no library links a terminal crate, and the library's other
/// users (rtw-py, rtw-bench) build on the libraries, never on the command.
#[test]
fn the_libraries_know_no_terminal_and_depend_only_downward() {
    let layers: [(&str, &[&str]); 4] = [
        ("../rtw-engine/Cargo.toml", &["rtw-studies", "rtw-scan"]),
        ("../rtw-studies/Cargo.toml", &["rtw-scan"]),
        ("../rtw-py/Cargo.toml", &["rtw-scan"]),
        ("../rtw-bench/Cargo.toml", &["rtw-scan"]),
    ];
    for (path, above) in layers {
        let m = manifest(path);
        let normal = names(&m, "dependencies");
        let all: Vec<String> = normal
            .iter()
            .cloned()
            .chain(names(&m, "dev-dependencies"))
            .collect();
        for name in above {
            assert!(
                !all.iter().any(|d| d == name),
                "{path} depends on {name}, a layer above it"
            );
        }
        if path.contains("rtw-engine") || path.contains("rtw-studies") || path.contains("rtw-py") {
            for name in TERMINAL {
                assert!(
                    !normal.iter().any(|d| d == name),
                    "{path} links {name}: only the command line may"
                );
            }
        }
    }
    // The command is the one member with the terminal crates.
    let cli = names(&manifest("../rtw-scan/Cargo.toml"), "dependencies");
    for name in TERMINAL {
        assert!(cli.iter().any(|d| d == name), "rtw-scan lacks {name}");
    }
}

/// The tests run `rtw-scan-test`, the command's test build, whose name a
/// plain build never writes: a user's `cargo run --release -p rtw-scan`
/// beside the test command re-links `target/release/rtw-scan`, and a test
/// that ran that file would meet a binary without `--fake-sim`. The test
/// build is this package's binary, not a second one of rtw-scan's (which
/// `cargo install` would install), and rtw-scan has no feature for it (a
/// feature would compile the command's library a second time for the
/// tests); no test may name the plain binary.
#[test]
fn the_tests_run_a_binary_that_a_plain_build_never_overwrites() {
    let bin_names = |m: &toml::Table| -> Vec<String> {
        m.get("bin")
            .and_then(toml::Value::as_array)
            .map(|bins| {
                bins.iter()
                    .filter_map(|b| b.get("name").and_then(toml::Value::as_str))
                    .map(str::to_owned)
                    .collect()
            })
            .unwrap_or_default()
    };
    let command = manifest("../rtw-scan/Cargo.toml");
    assert_eq!(bin_names(&command), ["rtw-scan"], "rtw-scan's binaries");
    assert!(
        command.get("features").is_none(),
        "rtw-scan has features: the test build would compile its library again"
    );
    assert_eq!(bin_names(&manifest("Cargo.toml")), ["rtw-scan-test"]);
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
