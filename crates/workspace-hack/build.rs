// A build script, so that cargo counts the [build-dependencies] above as
// this crate's and unifies their features with the proc-macros' (Cargo.toml).
fn main() {}
