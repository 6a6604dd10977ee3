use super::*;

#[test]
fn write_atomic_replaces_content_and_leaves_no_temp_file() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("a.txt");
    write_atomic(&p, b"first").unwrap();
    write_atomic(&p, b"second").unwrap();
    assert_eq!(std::fs::read(&p).unwrap(), b"second");
    let n = std::fs::read_dir(dir.path()).unwrap().count();
    assert_eq!(n, 1);
}

#[test]
fn write_atomic_into_missing_directory_fails_without_panic() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("missing").join("a.txt");
    assert!(write_atomic(&p, b"x").is_err());
}
