use super::*;

#[test]
fn parse_without_time_column() {
    let d = parse_csv("mem", b"a,b\n1,2\n3,4\n").unwrap();
    assert_eq!(d.columns, vec!["a", "b"]);
    assert!(d.time.is_none());
    assert_eq!(d.rows, vec![vec![1.0, 2.0], vec![3.0, 4.0]]);
}

#[test]
fn time_header_is_case_insensitive() {
    let d = parse_csv("mem", b" Time , a\n0, 1\n0.5, 2\n").unwrap();
    assert_eq!(d.time, Some(vec![0.0, 0.5]));
    assert_eq!(d.columns, vec!["a"]);
}

mod io;
