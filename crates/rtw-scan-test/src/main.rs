//! `rtw-scan-test`: the `rtw-scan` command with its test-only flags (the
//! stand-in simulator behind the hidden `--fake-sim`) and the pauses of
//! `RTW_SCAN_PAUSE`, which the end-to-end tests (`tests/it`) and
//! `scripts/fault_inject.sh` run. A binary of its own name and package, so
//! that a user's `cargo run --release -p rtw-scan` beside the test command
//! re-links `target/release/rtw-scan` and never the binary the tests run.

fn main() -> std::process::ExitCode {
    rtw_scan::test_main()
}
