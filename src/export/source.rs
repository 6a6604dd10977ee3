//! What `cosco export` exports: a reproduction CSV, or a model's reproduction made on the spot
//! (read or made by `app::export`).

/// Rate of a reproduction's `step` column when the file has no `time` column: the arm's
/// encoders' (the demonstrations' clock), Hz.
pub const DEFAULT_STEP_RATE_HZ: f64 = 40.0;
