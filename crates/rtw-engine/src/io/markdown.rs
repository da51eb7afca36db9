//! Markdown tables, as the summaries (`.md` files and stdout) print them.

/// `text` as one cell of a Markdown table: a bare `|` would end the cell and
/// shift every later cell of the row (a period-2 mode sequence joins its
/// steps with one, a multiplier's modulus is written |μ|), so it is escaped.
pub fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::cell;

    #[test]
    fn a_bar_inside_a_cell_is_escaped_so_the_row_keeps_its_cells() {
        let row = format!("| {} | next |", cell("slip c · td b+ | slip a · td c+"));
        // Cell boundaries: the bars not preceded by a backslash.
        let bounds = row
            .match_indices('|')
            .filter(|(i, _)| !row[..*i].ends_with('\\'))
            .count();
        assert_eq!(bounds, 3, "{row}");
        assert_eq!(cell("max |μ|"), "max \\|μ\\|");
    }
}
