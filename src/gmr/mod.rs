//! The baseline the paper compares against (Section V, Calinon's GMM/GMR): pre-processing
//! (trim the idle start and end, align with DTW, resample), a Gaussian mixture over
//! `[t, q]` fitted by EM, and Gaussian mixture regression of `q` on `t`.
//!
//! ```
//! use cosco_hsom::demos::Demonstration;
//! use cosco_hsom::gmr::{ComponentChoice, GmrParams};
//! // three 1-D "gestures" of slightly different speed, with idle start and end
//! let demos: Vec<Demonstration> = [1.0, 1.1, 0.9].iter().enumerate().map(|(d, s)| {
//!     let mut rows = vec![vec![0.0]; 10];
//!     rows.extend((0..60).map(|i| vec![(std::f64::consts::PI * i as f64 / 59.0 * s).min(std::f64::consts::PI).sin()]));
//!     rows.extend(vec![vec![0.0]; 10]);
//!     Demonstration { source: format!("demo{d}"), columns: vec!["q".into()], time: None, rows }
//! }).collect();
//! let model = GmrParams::new().components(ComponentChoice::Fixed(4)).seed(7)
//!     .check().unwrap().fit(&demos).unwrap();
//! let path = model.reproduce(0.025).unwrap();
//! let peak = path.iter().map(|p| p.mean[0]).fold(f64::MIN, f64::max);
//! assert!(peak > 0.8, "peak {peak}");
//! ```

mod algorithm;
mod errors;
mod hyperparams;
mod io;
mod lead_in;
pub mod preprocess;
mod stepper;

pub use algorithm::{BicScore, Gmm, GmrModel, Prediction};
pub use errors::GmrError;
pub use hyperparams::{ComponentChoice, GmrParams, GmrValidParams, IdleTrim, MIN_DEMONSTRATIONS};
pub use io::{
    load_model, model_from_str, model_to_string, save_model, FORMAT_MAGIC, FORMAT_VERSION,
};
pub use lead_in::{lead_in_ticks_at, plan_at, GmrPlan, LEAD_IN_MIN_S};
pub use preprocess::{active_range, TrainingSet};
pub use stepper::{stepper, UNCONDITIONED};

#[cfg(test)]
mod tests;
