//! The numerical check behind each erratum of docs/model.md §7, printed as a
//! Markdown table (docs/reproduction.md):
//!
//!     cargo run --release -p rtw-model --example errata
//!
//! Everything is computed in [`rtw_model::modal::errata_table`] from the
//! string model and the modal analysis; the crate's modal tests assert the
//! same relations.

fn main() {
    print!("{}", rtw_model::modal::errata_table());
}
