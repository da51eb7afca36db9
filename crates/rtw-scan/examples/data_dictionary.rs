//! Prints docs/data-dictionary.md: every Parquet column rtw-scan writes, with
//! its type, unit and meaning, from the same schemas the files carry.
//! `cargo run -p rtw-scan --example data_dictionary > docs/data-dictionary.md`
fn main() {
    print!("{}", rtw_studies::dictionary::markdown());
}
