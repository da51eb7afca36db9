//! `rtw-scan`: see `rtw-scan --help` and the crate docs of `rtw_scan`.

fn main() -> std::process::ExitCode {
    rtw_scan::main()
}
