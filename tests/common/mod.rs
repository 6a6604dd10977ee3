//! Fixtures every test target shares: the `cosco` command and the demonstrator's waves.
#![allow(dead_code)]

pub mod waves;

use assert_cmd::Command;

/// The `cosco` binary of this build.
pub fn cosco() -> Command {
    Command::cargo_bin("cosco").unwrap()
}
