//! No code: the union of the workspace's dependency features (Cargo.toml says why).
