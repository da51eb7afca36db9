//! The `rtw-scan` command's end-to-end tests, as one test binary (they run
//! its test build, this package's `rtw-scan-test`): each module is one
//! area (the CLI's commands, the files' reliability, shards, destinations,
//! the config template), and `common` holds what they share. One binary
//! links arrow and parquet once, where one binary per file linked them
//! sixteen times (docs/testing.md, "Build times"). Run one area with
//! `cargo test --release -p rtw-scan-test --test it cli_profile::`.

mod common;

mod cli;
mod cli_basin;
mod cli_bifurcation;
mod cli_design;
mod cli_physics;
mod cli_profile;
mod cli_refine;
mod cli_robustness;
mod cli_rough;
mod cli_segments;
mod cli_sensitivity;
mod default_variant;
mod destinations;
mod library_deps;
mod pipes;
mod reliability;
mod shard;
mod template;
