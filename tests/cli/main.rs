//! The command line (`cosco`) and bad input of every kind: the target `make test` runs in
//! both builds, with the simulator and without it (`--no-default-features`).

#[path = "../common/mod.rs"]
mod common;
#[path = "../hsom_common/mod.rs"]
mod hsom_common;

mod bad_input;
mod cli_cosco;
mod upper_body_columns;
