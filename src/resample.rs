//! Demonstrations at any sampling rate: each one with a `time` column resampled to one
//! rate, every `1 / hz` s from its first time to its last, by shape-preserving piecewise
//! cubic Hermite interpolation (PCHIP, Fritsch & Carlson 1980: monotone between samples, no
//! overshoot beyond neighbouring samples, so a resampled joint never leaves the range the
//! demonstration covered; [`crate::curve::pchip`], with the three-point end slopes). Reading
//! paths call [`resample_all`] when given a rate (`--resample HZ`, Python's `resample=`);
//! [`survey`] reports what it does.
//!
//! ```
//! use cosco_hsom::demos::Demonstration;
//! use cosco_hsom::resample::resample;
//! let d = Demonstration {
//!     source: "mem".into(),
//!     columns: vec!["q".into()],
//!     time: Some(vec![0.0, 0.3, 0.5, 1.0]),
//!     rows: vec![vec![0.0], vec![1.0], vec![1.0], vec![2.0]],
//! };
//! let r = resample(&d, 10.0).unwrap();
//! assert_eq!(r.rows.len(), 11);
//! assert!(r.rows.iter().all(|x| (0.0..=2.0).contains(&x[0])));
//! ```

use std::path::PathBuf;

use serde::Serialize;

use crate::curve::pchip;
use crate::demos::{median_interval, DemoError, Demonstration};

fn check_rate(hz: f64) -> Result<(), DemoError> {
    if hz.is_finite() && hz > 0.0 && hz <= 10_000.0 {
        Ok(())
    } else {
        Err(DemoError::ResampleRate { value: hz })
    }
}

/// One demonstration resampled every `1 / hz` s from its first time to its last (the
/// times start at its first time; the last one at or before its last time). It needs a
/// `time` column.
pub fn resample(d: &Demonstration, hz: f64) -> Result<Demonstration, DemoError> {
    check_rate(hz)?;
    crate::demos::validate(d)?;
    let t = d
        .time
        .as_ref()
        .ok_or_else(|| DemoError::ResampleWithoutTime {
            path: d.source.clone(),
        })?;
    let (t0, t1) = (t[0], t[t.len() - 1]);
    let n = ((t1 - t0) * hz + 1e-9).floor() as usize + 1;
    let at: Vec<f64> = (0..n).map(|i| t0 + i as f64 / hz).collect();
    let cols: Vec<Vec<f64>> = (0..d.width())
        .map(|k| {
            let y: Vec<f64> = d.rows.iter().map(|r| r[k]).collect();
            pchip(t, &y, &at)
        })
        .collect();
    Ok(Demonstration {
        source: d.source.clone(),
        columns: d.columns.clone(),
        time: Some(at.clone()),
        rows: (0..n)
            .map(|i| cols.iter().map(|c| c[i]).collect())
            .collect(),
    })
}

/// Every demonstration resampled to `hz` when a rate is given (each needs a `time`
/// column); unchanged without one.
pub fn resample_all(
    demos: Vec<Demonstration>,
    hz: Option<f64>,
) -> Result<Vec<Demonstration>, DemoError> {
    match hz {
        None => Ok(demos),
        Some(hz) => demos.iter().map(|d| resample(d, hz)).collect(),
    }
}

/// What resampling does to a set of files.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResampleReport {
    /// Target rate, Hz.
    pub rate_hz: f64,
    /// Files resampled.
    pub files: usize,
    /// Lowest and highest original rate (1 / median period), Hz.
    pub original_rate_hz: (f64, f64),
    /// Samples before and after, summed over the files.
    pub samples: (usize, usize),
}

impl ResampleReport {
    /// One line for the output.
    pub fn line(&self) -> String {
        format!(
            "resampled {} demonstrations from {:.4}-{:.4} Hz to {} Hz (shape-preserving cubic): {} samples -> {}",
            self.files,
            self.original_rate_hz.0,
            self.original_rate_hz.1,
            self.rate_hz,
            self.samples.0,
            self.samples.1
        )
    }
}

/// The line a command prints for `--resample HZ` on `paths` ([`survey`]); nothing without it.
pub fn report_line(paths: &[PathBuf], hz: Option<f64>) -> Result<Option<String>, DemoError> {
    hz.map(|hz| survey(paths, hz).map(|r| r.line())).transpose()
}

/// The report of resampling the demonstration files under `paths` (files, directories of
/// CSV files, or directories of label subdirectories) to `hz`.
pub fn survey(paths: &[PathBuf], hz: f64) -> Result<ResampleReport, DemoError> {
    check_rate(hz)?;
    let mut files: Vec<PathBuf> = Vec::new();
    for p in paths {
        collect_csv(p, 0, &mut files)?;
    }
    let mut report = ResampleReport {
        rate_hz: hz,
        files: 0,
        original_rate_hz: (f64::INFINITY, 0.0),
        samples: (0, 0),
    };
    for f in &files {
        let d = crate::demos::read_csv(f)?;
        let r = resample(&d, hz)?;
        let rate = median_interval(&d).map_or(f64::NAN, |p| 1.0 / p);
        report.files += 1;
        report.original_rate_hz.0 = report.original_rate_hz.0.min(rate);
        report.original_rate_hz.1 = report.original_rate_hz.1.max(rate);
        report.samples.0 += d.len();
        report.samples.1 += r.len();
    }
    if report.files == 0 {
        return Err(DemoError::NoDemonstrations);
    }
    Ok(report)
}

fn collect_csv(p: &std::path::Path, depth: usize, out: &mut Vec<PathBuf>) -> Result<(), DemoError> {
    if !p.is_dir() {
        out.push(p.to_path_buf());
        return Ok(());
    }
    let io = |source| DemoError::Io {
        path: p.display().to_string(),
        source,
    };
    let mut entries: Vec<PathBuf> = std::fs::read_dir(p)
        .map_err(io)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()
        .map_err(io)?;
    entries.sort();
    for e in entries {
        let csv = e
            .extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| x.eq_ignore_ascii_case("csv"));
        if (csv && e.is_file()) || (e.is_dir() && depth == 0) {
            collect_csv(&e, depth + 1, out)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
