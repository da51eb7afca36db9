// The build's identity for `rtw.version` (docs/results-on-disk.md,
// "Versions"): a hash of the sources that make its numbers. Included by
// build.rs, which computes it, and by the crate's tests, which check it.

/// FNV-1a, 64 bits: small, and the same on every platform and Rust version
/// (std's hasher promises neither).
struct Fnv(u64);

impl Fnv {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// Every file under `dir`, as (path relative to it with `/`, contents),
/// sorted by path; empty when `dir` does not exist.
fn files_under(dir: &std::path::Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let path = e.path();
            if path.is_dir() {
                todo.push(path);
            } else if let Ok(bytes) = std::fs::read(&path) {
                let rel = path.strip_prefix(dir).unwrap_or(&path);
                let rel: Vec<String> = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                out.push((rel.join("/"), bytes));
            }
        }
    }
    out.sort();
    out
}

/// What the identity covers, from rtw-engine's folder `here`: the ODE
/// engine, the model, the scan engine itself, the studies over it, and the
/// locked versions of every dependency.
pub fn roots(here: &std::path::Path) -> Vec<(&'static str, std::path::PathBuf)> {
    let crates = here.join("..");
    vec![
        ("hybrid-ode", crates.join("hybrid-ode/src")),
        ("rtw-model", crates.join("rtw-model/src")),
        ("rtw-engine", here.join("src")),
        ("rtw-studies", crates.join("rtw-studies/src")),
        ("Cargo.lock", crates.join("../Cargo.lock")),
    ]
}

/// The identity of the sources in `roots` (each a name and a folder or a
/// file): 16 hex digits of a hash of every file's name and contents, in a
/// fixed order, so the same sources give the same identity on any machine
/// and any change to them another.
pub fn sources_id(roots: &[(&str, &std::path::Path)]) -> String {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    for (name, root) in roots {
        h.write(name.as_bytes());
        h.write(&[0]);
        let files = if root.is_file() {
            std::fs::read(root)
                .map(|b| vec![(String::new(), b)])
                .unwrap_or_default()
        } else {
            files_under(root)
        };
        h.write(&(files.len() as u64).to_le_bytes());
        for (path, bytes) in files {
            h.write(path.as_bytes());
            h.write(&[0]);
            h.write(&(bytes.len() as u64).to_le_bytes());
            h.write(&bytes);
        }
    }
    format!("{:016x}", h.0)
}

#[cfg(test)]
mod tests {
    use super::{roots, sources_id};

    /// The version is the crate's and the identity build.rs computed, which
    /// is that of the sources this test was built from.
    #[test]
    fn the_version_carries_the_identity_of_these_sources() {
        let roots = roots(std::path::Path::new(env!("CARGO_MANIFEST_DIR")));
        let named: Vec<(&str, &std::path::Path)> =
            roots.iter().map(|(n, p)| (*n, p.as_path())).collect();
        let id = sources_id(&named);
        assert_eq!(
            crate::VERSION,
            format!("{}+{id}", env!("CARGO_PKG_VERSION"))
        );
    }

    #[test]
    fn the_identity_is_the_sources_and_changes_with_any_of_them() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a"), dir.path().join("b"));
        std::fs::create_dir_all(a.join("sub")).unwrap();
        std::fs::write(a.join("x.rs"), "fn x() {}").unwrap();
        std::fs::write(a.join("sub/y.rs"), "fn y() {}").unwrap();
        // The same files written in the other order: the same identity.
        std::fs::create_dir_all(b.join("sub")).unwrap();
        std::fs::write(b.join("sub/y.rs"), "fn y() {}").unwrap();
        std::fs::write(b.join("x.rs"), "fn x() {}").unwrap();
        let id = |p: &std::path::Path| sources_id(&[("src", p)]);
        assert_eq!(id(&a), id(&b));
        assert_eq!(id(&a).len(), 16);
        // One byte of one file, a file's name, or the root's name.
        std::fs::write(b.join("sub/y.rs"), "fn y() {} ").unwrap();
        assert_ne!(id(&a), id(&b));
        std::fs::write(b.join("sub/y.rs"), "fn y() {}").unwrap();
        std::fs::rename(b.join("x.rs"), b.join("z.rs")).unwrap();
        assert_ne!(id(&a), id(&b));
        assert_ne!(id(&a), sources_id(&[("other", a.as_path())]));
        // A missing root counts as empty, and differs from a present one.
        assert_ne!(id(&a), id(&dir.path().join("none")));
    }
}
