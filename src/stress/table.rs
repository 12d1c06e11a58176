//! The text of a table, CSV or Markdown, one row a line: what the stress
//! tests and the benchmarks write their results as.

/// A table's text (CSV, or Markdown after its separator line): `header`,
/// then one line per row as `line` writes it.
pub fn table<T>(
    header: &str,
    rows: impl IntoIterator<Item = T>,
    line: impl Fn(T) -> String,
) -> String {
    let mut text = format!("{header}\n");
    for row in rows {
        text += &line(row);
        text.push('\n');
    }
    text
}

#[cfg(test)]
mod tests {
    use super::table;

    #[test]
    fn a_table_is_its_header_then_a_line_per_row() {
        let text = table("n,square", [1, 2, 3], |n| format!("{n},{}", n * n));
        assert_eq!(text, "n,square\n1,1\n2,4\n3,9\n");
        assert_eq!(
            table("| a |\n| --- |", Vec::<u8>::new(), |_| String::new()),
            "| a |\n| --- |\n"
        );
    }
}
