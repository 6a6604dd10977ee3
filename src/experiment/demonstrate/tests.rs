use super::*;

#[test]
fn seeds_parse_lists_and_ranges_and_name_bad_entries() {
    assert_eq!(parse_seeds("1-5").unwrap(), vec![1, 2, 3, 4, 5]);
    assert_eq!(parse_seeds("1, 3,7-9").unwrap(), vec![1, 3, 7, 8, 9]);
    assert_eq!(parse_seeds("4").unwrap(), vec![4]);
    for (bad, named) in [
        ("1,,2", "''"),
        ("x", "'x'"),
        ("5-2", "'5-2'"),
        ("-3", "'-3'"),
    ] {
        let e = parse_seeds(bad).unwrap_err().to_string();
        assert!(e.contains(named), "{bad}: {e}");
    }
}

#[test]
fn gestures_parse_and_unknown_names_list_the_known_ones() {
    let g = parse_gestures("wave,salute").unwrap();
    assert_eq!(g.len(), 2);
    assert_eq!(g[0].name, "wave");
    let e = parse_gestures("wave,dance").unwrap_err().to_string();
    assert!(e.contains("'dance'") && e.contains("reading-watch"), "{e}");
}
