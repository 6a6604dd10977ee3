//! Demonstration CSV reading, writing and set validation through the public API.

use crate::demos::{
    parse_csv, read_csv, read_dir_or_files, validate_set, write_csv, DemoError, Demonstration,
};
use std::path::PathBuf;

fn err(text: &str) -> DemoError {
    parse_csv("demo.csv", text.as_bytes()).unwrap_err()
}

fn demo(source: &str, columns: &[&str], rows: Vec<Vec<f64>>) -> Demonstration {
    Demonstration {
        source: source.into(),
        columns: columns.iter().map(|s| s.to_string()).collect(),
        time: None,
        rows,
    }
}

#[test]
fn reads_time_and_state_columns() {
    let d = parse_csv("demo.csv", b"time,q0,q1\n0,0.1,0.2\n0.025,0.11,0.21\n").unwrap();
    assert_eq!(d.columns, vec!["q0", "q1"]);
    assert_eq!(d.time, Some(vec![0.0, 0.025]));
    assert_eq!(d.rows, vec![vec![0.1, 0.2], vec![0.11, 0.21]]);
    assert_eq!(d.source, "demo.csv");
}

#[test]
fn write_then_read_round_trips_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("d.csv");
    let d = Demonstration {
        source: "x".into(),
        columns: vec!["a".into(), "b".into()],
        time: Some(vec![0.0, 0.1, 0.30000000000000004]),
        rows: vec![
            vec![1.0 / 3.0, -2.5e-17],
            vec![std::f64::consts::PI, 1e300],
            vec![0.0, -0.0],
        ],
    };
    write_csv(&path, &d).unwrap();
    let back = read_csv(&path).unwrap();
    assert_eq!(back.rows, d.rows);
    assert_eq!(back.time, d.time);
    assert_eq!(back.columns, d.columns);
    // no temporary file left behind
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn write_refuses_invalid_demonstration() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("d.csv");
    let d = demo("bad", &["a"], vec![vec![f64::NAN]]);
    assert!(matches!(
        write_csv(&path, &d),
        Err(DemoError::NotFinite { .. })
    ));
    assert!(!path.exists());
}

#[test]
fn empty_file_is_an_error() {
    assert!(matches!(err(""), DemoError::Empty { .. }));
}

#[test]
fn header_only_is_an_error() {
    let e = err("time,q0\n");
    assert!(matches!(e, DemoError::NoSamples { .. }), "{e}");
    assert!(e.to_string().contains("demo.csv"));
}

#[test]
fn header_with_only_time_is_an_error() {
    assert!(matches!(err("time\n0\n"), DemoError::NoStateColumns { .. }));
}

#[test]
fn ragged_row_names_its_line() {
    let e = err("a,b\n1,2\n3\n");
    match &e {
        DemoError::Ragged {
            line,
            expected,
            found,
            ..
        } => assert_eq!((*line, *expected, *found), (3, 2, 1)),
        other => panic!("unexpected {other}"),
    }
    assert!(e.to_string().contains("line 3"));
}

#[test]
fn non_numeric_cell_names_line_column_and_value() {
    let e = err("a,b\n1,2\n3,abc\n");
    match &e {
        DemoError::NotNumeric {
            line,
            column,
            value,
            ..
        } => {
            assert_eq!(*line, 3);
            assert_eq!(column, "b");
            assert_eq!(value, "abc");
        }
        other => panic!("unexpected {other}"),
    }
    let msg = e.to_string();
    assert!(msg.contains("demo.csv") && msg.contains("`b`") && msg.contains("abc"));
}

#[test]
fn nan_and_infinity_are_errors() {
    for bad in ["NaN", "inf", "-inf", "nan"] {
        let e = err(&format!("a,b\n1,{bad}\n"));
        match &e {
            DemoError::NotFinite {
                location, column, ..
            } => {
                assert_eq!(location, "line 2");
                assert_eq!(column, "b");
            }
            other => panic!("{bad}: unexpected {other}"),
        }
    }
}

#[test]
fn duplicate_column_names_are_an_error() {
    match err("time,a,b,a\n0,1,2,3\n") {
        DemoError::DuplicateColumn {
            column,
            first,
            second,
            ..
        } => {
            assert_eq!(column, "a");
            assert_eq!((first, second), (2, 4));
        }
        other => panic!("unexpected {other}"),
    }
}

#[test]
fn empty_column_name_is_an_error() {
    match err("a,,c\n1,2,3\n") {
        DemoError::EmptyColumnName { column_index, .. } => assert_eq!(column_index, 2),
        other => panic!("unexpected {other}"),
    }
}

#[test]
fn non_increasing_time_is_an_error() {
    for text in [
        "time,a\n0,1\n0.1,2\n0.1,3\n",
        "time,a\n0,1\n0.1,2\n0.05,3\n",
    ] {
        match err(text) {
            DemoError::NonIncreasingTime { location, .. } => assert_eq!(location, "line 4"),
            other => panic!("unexpected {other}"),
        }
    }
}

#[test]
fn missing_file_is_an_io_error_naming_it() {
    let e = read_csv(std::path::Path::new("/nonexistent/x.csv")).unwrap_err();
    assert!(matches!(e, DemoError::Io { .. }));
    assert!(e.to_string().contains("/nonexistent/x.csv"));
}

#[test]
fn directory_is_read_in_name_order_and_non_csv_skipped() {
    let dir = tempfile::tempdir().unwrap();
    for (name, v) in [("b.csv", 2.0), ("a.csv", 1.0), ("c.CSV", 3.0)] {
        std::fs::write(dir.path().join(name), format!("q\n{v}\n")).unwrap();
    }
    std::fs::write(dir.path().join("notes.txt"), "not a demo").unwrap();
    let demos = read_dir_or_files(&[dir.path().to_path_buf()]).unwrap();
    let firsts: Vec<f64> = demos.iter().map(|d| d.rows[0][0]).collect();
    assert_eq!(firsts, vec![1.0, 2.0, 3.0]);
}

#[test]
fn explicit_files_keep_their_order() {
    let dir = tempfile::tempdir().unwrap();
    let b = dir.path().join("b.csv");
    let a = dir.path().join("a.csv");
    std::fs::write(&b, "q\n2\n").unwrap();
    std::fs::write(&a, "q\n1\n").unwrap();
    let demos = read_dir_or_files(&[b, a]).unwrap();
    assert_eq!(demos[0].rows[0][0], 2.0);
    assert_eq!(demos[1].rows[0][0], 1.0);
}

#[test]
fn empty_directory_and_empty_list_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    assert!(matches!(
        read_dir_or_files(&[dir.path().to_path_buf()]),
        Err(DemoError::EmptyDirectory { .. })
    ));
    assert!(matches!(
        read_dir_or_files(&Vec::<PathBuf>::new()),
        Err(DemoError::NoDemonstrations)
    ));
}

#[test]
fn set_with_differing_columns_is_an_error() {
    let a = demo("a.csv", &["q0", "q1"], vec![vec![0.0, 0.0]]);
    let b = demo("b.csv", &["q0", "q2"], vec![vec![0.0, 0.0]]);
    match validate_set(&[a, b], None) {
        Err(DemoError::ColumnsDiffer {
            path, reference, ..
        }) => {
            assert_eq!(path, "b.csv");
            assert_eq!(reference, "a.csv");
        }
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn set_width_must_match_expected_state_length() {
    let a = demo("a.csv", &["q0", "q1"], vec![vec![0.0, 0.0]]);
    assert!(validate_set(std::slice::from_ref(&a), Some(2)).is_ok());
    match validate_set(&[a], Some(6)) {
        Err(DemoError::WidthMismatch {
            expected, found, ..
        }) => assert_eq!((expected, found), (6, 2)),
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn empty_set_is_an_error() {
    assert!(matches!(
        validate_set(&[], None),
        Err(DemoError::NoDemonstrations)
    ));
}

#[test]
fn in_memory_checks_rows_and_time() {
    let mut d = demo("m", &["a", "b"], vec![vec![0.0, 1.0], vec![0.0]]);
    assert!(matches!(
        validate_set(std::slice::from_ref(&d), None),
        Err(DemoError::RowWidth { sample: 1, .. })
    ));
    d.rows[1].push(2.0);
    d.time = Some(vec![0.0]);
    assert!(matches!(
        validate_set(std::slice::from_ref(&d), None),
        Err(DemoError::TimeLength { .. })
    ));
    d.time = Some(vec![0.0, 0.0]);
    assert!(matches!(
        validate_set(std::slice::from_ref(&d), None),
        Err(DemoError::NonIncreasingTime { .. })
    ));
    d.time = Some(vec![0.0, 0.025]);
    assert!(validate_set(&[d], None).is_ok());
}
