use super::*;

#[test]
fn header_separator_and_rows() {
    let mut t = Table::new(["a", "b c"]);
    assert!(t.is_empty());
    t.row(["1", "2"]).row([String::from("x"), String::new()]);
    assert_eq!(t.len(), 2);
    assert_eq!(
        t.to_string(),
        "| a | b c |\n|---|---|\n| 1 | 2 |\n| x | |\n"
    );
}

#[test]
fn a_row_printed_alone_is_the_table_row() {
    let mut t = Table::new([""; 3]);
    t.row([1, 22, 333]);
    let head = Table::new([""; 3]).to_string();
    assert_eq!(head, "| | | |\n|---|---|---|\n");
    assert_eq!(t.to_string(), head + &Table::line([1, 22, 333]));
}
