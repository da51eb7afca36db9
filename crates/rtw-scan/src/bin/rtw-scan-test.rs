//! `rtw-scan-test`: the `rtw-scan` command with the test-only `fake-sim`
//! feature (the stand-in simulator behind `--fake-sim`, `RTW_SCAN_PAUSE`).
//! A binary of its own name, which only a build with that feature makes, so
//! that a user's `cargo run --release -p rtw-scan` beside the test command
//! re-links `target/release/rtw-scan` and never the binary the tests run.

fn main() -> std::process::ExitCode {
    rtw_engine::allow_test_pauses();
    rtw_scan::main()
}
