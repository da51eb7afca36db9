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
    for bin in bins {
        assert_eq!(
            bin.get("required-features").map(ToString::to_string),
            Some(r#"["cli"]"#.to_string()),
            "{bin:?}"
        );
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
