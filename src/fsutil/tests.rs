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

/// The process's umask, as Linux reports it (no call that needs `unsafe`).
#[cfg(target_os = "linux")]
fn umask() -> u32 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = status.lines().find(|l| l.starts_with("Umask:")).unwrap();
    u32::from_str_radix(line["Umask:".len()..].trim(), 8).unwrap()
}

#[cfg(target_os = "linux")]
#[test]
fn a_new_file_gets_the_mode_of_the_umask() {
    use std::os::unix::fs::PermissionsExt as _;
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("new.bin");
    write_atomic(&p, b"x").unwrap();
    let mode = std::fs::metadata(&p).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o666 & !umask(), "mode {mode:o}");
    // The control: a temporary file as tempfile makes it is 0600, which no usual umask gives.
    let control = tempfile::NamedTempFile::new_in(dir.path()).unwrap();
    let control_mode = control.as_file().metadata().unwrap().permissions().mode() & 0o777;
    assert_eq!(control_mode, 0o600);
}

#[cfg(unix)]
#[test]
fn a_replaced_file_keeps_its_mode() {
    use std::os::unix::fs::PermissionsExt as _;
    let dir = tempfile::tempdir().unwrap();
    for mode in [0o640, 0o604] {
        let p = dir.path().join(format!("kept-{mode:o}.bin"));
        std::fs::write(&p, b"old").unwrap();
        std::fs::set_permissions(&p, std::fs::Permissions::from_mode(mode)).unwrap();
        write_atomic(&p, b"new").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"new");
        let got = std::fs::metadata(&p).unwrap().permissions().mode() & 0o777;
        assert_eq!(got, mode, "mode {got:o}, expected {mode:o}");
    }
}
