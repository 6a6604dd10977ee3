//! Files the project writes keep the user's permissions: a model written under umask 022 is
//! mode 0644, and a model written over an existing file keeps that file's mode.
#![cfg(unix)]

use std::os::unix::fs::PermissionsExt as _;
use std::path::Path;
use std::process::Command;

/// Three strokes of a 2-D curve (columns x, y), 60 samples each.
fn write_strokes(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    for k in 0..3 {
        let mut text = String::from("x,y\n");
        for i in 0..60 {
            let s = i as f64 / 59.0;
            text += &format!("{},{}\n", (3.0 * s).sin() + 0.01 * k as f64, 2.0 * s);
        }
        std::fs::write(dir.join(format!("s{k}.csv")), text).unwrap();
    }
}

/// `cosco train` under `umask`, writing `out`.
fn train_under_umask(umask: &str, dir: &Path, out: &Path) {
    let xml = std::fs::read_to_string("configs/nao-gestures.xml")
        .unwrap()
        .replace(
            "<stateLength>6</stateLength>",
            "<stateLength>2</stateLength>",
        )
        .replace(
            "<actionLength>6</actionLength>",
            "<actionLength>2</actionLength>",
        )
        .replace(
            "<trainingSteps>5000</trainingSteps>",
            "<trainingSteps>300</trainingSteps>",
        );
    std::fs::write(dir.join("c.xml"), xml).unwrap();
    let status = Command::new("sh")
        .arg("-c")
        .arg(format!("umask {umask} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_cosco"))
        .arg("train")
        .arg("--config")
        .arg(dir.join("c.xml"))
        .arg("--demos")
        .arg(dir.join("demos"))
        .arg("--out")
        .arg(out)
        .status()
        .unwrap();
    assert!(status.success());
}

fn mode(path: &Path) -> u32 {
    std::fs::metadata(path).unwrap().permissions().mode() & 0o777
}

#[test]
fn a_model_written_under_umask_022_is_0644_and_under_077_is_0600() {
    let dir = tempfile::tempdir().unwrap();
    write_strokes(&dir.path().join("demos"));
    let shared = dir.path().join("shared.bin");
    train_under_umask("022", dir.path(), &shared);
    assert_eq!(mode(&shared), 0o644, "mode {:o}", mode(&shared));
    // The control: a stricter umask gives a stricter mode, so the mode is the umask's.
    let private = dir.path().join("private.bin");
    train_under_umask("077", dir.path(), &private);
    assert_eq!(mode(&private), 0o600, "mode {:o}", mode(&private));
}

#[test]
fn an_overwritten_model_keeps_its_mode() {
    let dir = tempfile::tempdir().unwrap();
    write_strokes(&dir.path().join("demos"));
    let model = dir.path().join("group.bin");
    std::fs::write(&model, b"an older file").unwrap();
    std::fs::set_permissions(&model, std::fs::Permissions::from_mode(0o664)).unwrap();
    train_under_umask("077", dir.path(), &model);
    assert_eq!(mode(&model), 0o664, "mode {:o}", mode(&model));
    assert_ne!(std::fs::read(&model).unwrap(), b"an older file");
}
