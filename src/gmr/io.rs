//! Save and load a [`GmrModel`] as versioned plain text (written here rather than through
//! serde: the file's lines are a model format that users and the main job's outputs read, and
//! it stays as it is).
//!
//! ```text
//! cosco-hsom gmr model
//! version 1
//! columns 2
//! column LShoulderPitch
//! column LShoulderRoll
//! duration 3.2e0
//! components 1
//! dim 3
//! weight 1e0
//! mean 1.6e0 -5e-1 2e-1
//! cov 1e0 0e0 0e0
//! cov 0e0 1e0 0e0
//! cov 0e0 0e0 1e0
//! end
//! ```
//!
//! Numbers are written in Rust's shortest round-trip exponent form, so a loaded model is
//! bit-identical to the saved one. Loading checks the magic line, the version, every
//! count against the lines that follow (nothing is allocated from a count before the data
//! are read; counts above 100 000 are refused), the dimensions, and the parameters
//! themselves (weights, symmetric positive definite covariances) via [`Gmm::new`].
//! Writing is atomic ([`crate::fsutil::write_atomic`]).

use std::path::Path;

use nalgebra::{DMatrix, DVector};

use super::algorithm::{Gmm, GmrModel};
use super::errors::GmrError;

/// First line of every model file.
pub const FORMAT_MAGIC: &str = "cosco-hsom gmr model";
/// The format version written and read by this build.
pub const FORMAT_VERSION: u32 = 1;
const MAX_COUNT: usize = 100_000;

fn num(x: f64) -> String {
    format!("{x:e}")
}

/// The model as text in format version [`FORMAT_VERSION`].
pub fn model_to_string(model: &GmrModel) -> Result<String, GmrError> {
    let mut s = format!("{FORMAT_MAGIC}\nversion {FORMAT_VERSION}\n");
    s += &format!("columns {}\n", model.columns().len());
    for c in model.columns() {
        if c.contains(['\n', '\r']) {
            return Err(GmrError::Query {
                message: format!("column name {c:?} contains a line break and cannot be saved"),
            });
        }
        s += &format!("column {c}\n");
    }
    let g = model.gmm();
    s += &format!("duration {}\n", num(model.duration()));
    s += &format!("components {}\ndim {}\n", g.n_components(), g.dim());
    for c in 0..g.n_components() {
        s += &format!("weight {}\n", num(g.weights()[c]));
        let m: Vec<String> = g.means()[c].iter().map(|v| num(*v)).collect();
        s += &format!("mean {}\n", m.join(" "));
        let cov = &g.covariances()[c];
        for i in 0..g.dim() {
            let r: Vec<String> = cov.row(i).iter().map(|v| num(*v)).collect();
            s += &format!("cov {}\n", r.join(" "));
        }
    }
    s += "end\n";
    Ok(s)
}

/// Save a model to `path` atomically.
pub fn save_model(path: &Path, model: &GmrModel) -> Result<(), GmrError> {
    let text = model_to_string(model)?;
    crate::fsutil::write_atomic(path, text.as_bytes()).map_err(|source| GmrError::Io {
        path: path.display().to_string(),
        source,
    })
}

struct Lines<'a> {
    path: String,
    iter: std::iter::Enumerate<std::str::Lines<'a>>,
    line: usize,
}

impl<'a> Lines<'a> {
    fn err(&self, message: String) -> GmrError {
        GmrError::Format {
            path: self.path.clone(),
            line: self.line,
            message,
        }
    }

    /// The next line, which must start with `key ` (or be exactly `key`); returns the rest.
    fn expect(&mut self, key: &str) -> Result<&'a str, GmrError> {
        match self.iter.next() {
            None => {
                self.line += 1;
                Err(self.err(format!("file ends early (truncated?): expected `{key}`")))
            }
            Some((i, l)) => {
                self.line = i + 1;
                if l == key {
                    return Ok("");
                }
                match l.strip_prefix(key).and_then(|r| r.strip_prefix(' ')) {
                    Some(rest) => Ok(rest),
                    None => Err(self.err(format!("expected `{key} …`, found `{l}`"))),
                }
            }
        }
    }

    fn count(&mut self, key: &str) -> Result<usize, GmrError> {
        let rest = self.expect(key)?;
        let n: usize = rest
            .trim()
            .parse()
            .map_err(|_| self.err(format!("`{key}` needs a whole number, found `{rest}`")))?;
        if n > MAX_COUNT {
            return Err(self.err(format!("`{key}` = {n} exceeds the limit {MAX_COUNT}")));
        }
        Ok(n)
    }

    fn floats(&mut self, key: &str, expected: usize) -> Result<Vec<f64>, GmrError> {
        let rest = self.expect(key)?;
        let mut out = Vec::new();
        for tok in rest.split_whitespace() {
            if out.len() == expected {
                return Err(self.err(format!("`{key}` has more than {expected} values")));
            }
            let v: f64 = tok
                .parse()
                .map_err(|_| self.err(format!("`{tok}` is not a number")))?;
            if !v.is_finite() {
                return Err(self.err(format!("`{tok}` is not finite")));
            }
            out.push(v);
        }
        if out.len() != expected {
            return Err(self.err(format!(
                "`{key}` has {} values, expected {expected}",
                out.len()
            )));
        }
        Ok(out)
    }
}

/// Parse a model from text; `path` names it in messages.
pub fn model_from_str(path: &str, text: &str) -> Result<GmrModel, GmrError> {
    let mut l = Lines {
        path: path.to_string(),
        iter: text.lines().enumerate(),
        line: 0,
    };
    match l.iter.next() {
        Some((_, m)) if m == FORMAT_MAGIC => l.line = 1,
        Some((_, m)) => {
            l.line = 1;
            return Err(l.err(format!(
                "not a GMR model file: first line is `{m}`, expected `{FORMAT_MAGIC}`"
            )));
        }
        None => return Err(l.err("empty file: not a GMR model".into())),
    }
    let v = l.expect("version")?;
    if v.trim() != FORMAT_VERSION.to_string() {
        return Err(GmrError::Version {
            path: path.to_string(),
            found: v.trim().to_string(),
            supported: FORMAT_VERSION,
        });
    }
    let n_columns = l.count("columns")?;
    let mut columns = Vec::new();
    for _ in 0..n_columns {
        columns.push(l.expect("column")?.to_string());
    }
    let duration = l.floats("duration", 1)?[0];
    let k = l.count("components")?;
    let d = l.count("dim")?;
    if d != n_columns + 1 {
        return Err(l.err(format!(
            "dim {d} is inconsistent with {n_columns} columns (expected {})",
            n_columns + 1
        )));
    }
    if k == 0 {
        return Err(l.err("a model needs at least one component".into()));
    }
    let (mut weights, mut means, mut covs) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..k {
        weights.push(l.floats("weight", 1)?[0]);
        means.push(DVector::from_vec(l.floats("mean", d)?));
        let mut rows = Vec::new();
        for _ in 0..d {
            rows.extend(l.floats("cov", d)?);
        }
        covs.push(DMatrix::from_row_slice(d, d, &rows));
    }
    l.expect("end")?;
    if let Some((i, extra)) = l.iter.find(|(_, s)| !s.trim().is_empty()) {
        l.line = i + 1;
        return Err(l.err(format!("unexpected content after `end`: `{extra}`")));
    }
    let gmm = Gmm::new(weights, means, covs)
        .map_err(|e| l.err(format!("inconsistent parameters: {e}")))?;
    GmrModel::new(columns, duration, gmm).map_err(|e| l.err(e.to_string()))
}

/// Load a model saved by [`save_model`].
pub fn load_model(path: &Path) -> Result<GmrModel, GmrError> {
    let p = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| GmrError::Io {
        path: p.clone(),
        source,
    })?;
    let text = String::from_utf8(bytes).map_err(|_| GmrError::Format {
        path: p.clone(),
        line: 0,
        message: "not UTF-8 text: not a GMR model".into(),
    })?;
    model_from_str(&p, &text)
}
