//! Several gestures in one hierarchy (issue 9; docs/ALGORITHM.md "Several gestures in one
//! hierarchy"): a [`GestureModel`] is one bottom level (the postures) shared by every gesture
//! and, above it, one branch of upper levels per gesture label. Training fits the bottom on
//! every demonstration, then each label's upper levels on that label's demonstrations (the
//! events extension's own training, unchanged); the label primes the top of the hierarchy on
//! reproduction, and recognition ([`super::recognize`]) pushes a sequence up every branch.
//!
//! A single-gesture model (format 8, no label) loads as a [`GestureModel`] with one unlabelled
//! branch, and is saved exactly as before; a multi-gesture model is format 9: the labels,
//! their recognition calibration and every branch in format 8 (which holds the branch's own
//! postures of the shared bottom nodes, [`Hsom::fit_postures`]). Older files (formats 5-7)
//! get the "retrain" error.

use std::path::{Path, PathBuf};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::config::{Algorithm, HsomConfig};
use crate::demos::Demonstration;
use crate::fsutil::write_atomic;

use super::algorithm::{Hsom, Presentation};
use super::errors::{HsomError, PersistError};
use super::persist::{ext, fnv1a, Format, FORMAT_VERSION, MAGIC, TEXT_MAGIC};
use super::recognize::{Calibration, Scoring};
use super::reproduction::Reproduction;

/// Format version of a multi-gesture model file (a single-gesture model stays
/// [`FORMAT_VERSION`]).
pub const GESTURES_FORMAT_VERSION: u32 = 21;

/// Most gesture labels a model may hold (a bound on what a file may make us allocate).
pub const MAX_LABELS: usize = 1024;

/// Why a multi-gesture step was refused.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GestureError {
    /// A label the model does not hold.
    #[error("no gesture {label:?} in the model; it holds: {labels}")]
    UnknownLabel {
        /// The label asked for.
        label: String,
        /// The model's labels, comma-separated.
        labels: String,
    },
    /// A multi-gesture model asked to reproduce without a label.
    #[error("the model holds several gestures ({labels}): choose one with --gesture NAME (or gesture=NAME)")]
    LabelNeeded {
        /// The model's labels, comma-separated.
        labels: String,
    },
    /// Recognition asked of a model without labels.
    #[error("a single-gesture model has no labels to recognise: train on labelled directories (demos/<label>/*.csv)")]
    NoLabels,
    /// A label that is not a plain word.
    #[error("gesture label {label:?} (from {source_dir}) is not a plain word: use letters, digits, '_' and '-' only")]
    BadLabel {
        /// The label.
        label: String,
        /// Where it came from (a directory, or `in memory`).
        source_dir: String,
    },
    /// The same label given twice.
    #[error("gesture label {label:?} is given twice")]
    DuplicateLabel {
        /// The label.
        label: String,
    },
    /// A label without demonstrations.
    #[error("gesture {label:?} has no demonstrations")]
    EmptyLabel {
        /// The label.
        label: String,
    },
    /// Labels whose demonstrations have different columns.
    #[error("gesture {label:?} has columns {found:?}, but gesture {first_label:?} has {expected:?}: every gesture must record the same variables")]
    ColumnsDiffer {
        /// The label that differs.
        label: String,
        /// Its columns.
        found: Vec<String>,
        /// The first label.
        first_label: String,
        /// The first label's columns.
        expected: Vec<String>,
    },
    /// Several gestures need the events extension (the paper's procedure trains every level
    /// at once, so its upper levels cannot be split by label).
    #[error("several gestures need algorithm = events (configs/nao-gestures.xml); this configuration uses the paper's algorithm")]
    NeedsEvents,
    /// A prefix shorter than one sample or longer than its file.
    #[error("--prefix {prefix}: the demonstration has {len} samples; give 1 to {len}")]
    Prefix {
        /// The prefix asked for.
        prefix: usize,
        /// The demonstration's samples.
        len: usize,
    },
    /// Training or reproduction was refused.
    #[error(transparent)]
    Hsom(#[from] HsomError),
    /// A model file could not be saved or loaded.
    #[error(transparent)]
    Persist(#[from] PersistError),
}

/// True for a plain word: `[A-Za-z0-9_-]+`.
pub fn is_plain_label(label: &str) -> bool {
    !label.is_empty()
        && label
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// One hierarchy for one or several gestures: a shared bottom level, one branch of upper
/// levels per label (every branch is an [`Hsom`] whose bottom is the shared one).
#[derive(Debug, Clone, PartialEq)]
pub struct GestureModel {
    /// Empty for a single-gesture model (one unlabelled branch).
    pub(crate) labels: Vec<String>,
    pub(crate) branches: Vec<Hsom>,
    /// Per label, what recognition compares with (empty without labels).
    pub(crate) calibration: Vec<Calibration>,
    /// How recognition scores (not stored: the default on load).
    pub(crate) scoring: Scoring,
}

impl From<Hsom> for GestureModel {
    fn from(model: Hsom) -> Self {
        GestureModel {
            labels: Vec::new(),
            branches: vec![model],
            calibration: Vec::new(),
            scoring: Scoring::default(),
        }
    }
}

impl HsomConfig {
    /// Train one hierarchy on labelled demonstration sets `(label, demonstrations)`: the
    /// bottom level on all of them, then one branch of upper levels per label; each label's
    /// recognition threshold is calibrated on its training data (leave-one-out). Labels must
    /// be plain words, distinct, each with demonstrations of the same columns.
    pub fn fit_gestures(
        &self,
        sets: &[(String, Vec<Demonstration>)],
        progress: Option<&dyn Fn(usize, usize)>,
    ) -> Result<GestureModel, GestureError> {
        self.gestures_inner(sets, progress, true)
    }

    /// The untrained counterpart of [`HsomConfig::fit_gestures`] (seeded initial weights,
    /// calibrated in the same way): the negative control of recognition.
    pub fn initialise_gestures(
        &self,
        sets: &[(String, Vec<Demonstration>)],
    ) -> Result<GestureModel, GestureError> {
        self.gestures_inner(sets, None, false)
    }

    fn gestures_inner(
        &self,
        sets: &[(String, Vec<Demonstration>)],
        progress: Option<&dyn Fn(usize, usize)>,
        learn: bool,
    ) -> Result<GestureModel, GestureError> {
        if self.params().kind() != Algorithm::Events {
            return Err(GestureError::NeedsEvents);
        }
        if sets.is_empty() {
            return Err(HsomError::NoDemonstrations.into());
        }
        for (i, (label, demos)) in sets.iter().enumerate() {
            if !is_plain_label(label) {
                return Err(GestureError::BadLabel {
                    label: label.clone(),
                    source_dir: "in memory".into(),
                });
            }
            if sets[..i].iter().any(|(l, _)| l == label) {
                return Err(GestureError::DuplicateLabel {
                    label: label.clone(),
                });
            }
            if demos.is_empty() {
                return Err(GestureError::EmptyLabel {
                    label: label.clone(),
                });
            }
            let (first_label, first) = (&sets[0].0, &sets[0].1[0]);
            if let Some(d) = demos.iter().find(|d| d.columns != first.columns) {
                return Err(GestureError::ColumnsDiffer {
                    label: label.clone(),
                    found: d.columns.clone(),
                    first_label: first_label.clone(),
                    expected: first.columns.clone(),
                });
            }
        }
        let all: Vec<Demonstration> = sets.iter().flat_map(|(_, d)| d.clone()).collect();
        // the shared bottom sees every gesture as often as a gesture learned alone does:
        // trainingSteps per label
        let cfg = if sets.len() > 1 {
            let mut p = self.params().clone();
            p.training_steps = p.training_steps.saturating_mul(sets.len());
            p.check(self.source()).map_err(|e| {
                GestureError::Persist(PersistError::Corrupted {
                    path: PathBuf::from(self.source()),
                    what: e.to_string(),
                })
            })?
        } else {
            self.clone()
        };
        let shared = if learn {
            // drawn at random when shared (docs/ALGORITHM.md, "Several gestures")
            let order = if sets.len() > 1 {
                Presentation::Shuffled
            } else {
                Presentation::InOrder
            };
            cfg.fit_presented(&all, progress, order)?
        } else {
            cfg.initialise(&all)?
        };
        let norm: Vec<Vec<Vec<Vec<f64>>>> = sets
            .iter()
            .map(|(_, demos)| {
                demos
                    .iter()
                    .map(|d| shared.normalise_rows(&d.rows))
                    .collect()
            })
            .collect();
        let seed = self.params().seed;
        let branches: Vec<Hsom> = norm
            .iter()
            .enumerate()
            .map(|(g, n)| {
                let mut b = shared.branch(n, learn, branch_seed(seed, g, None));
                if learn {
                    // each branch places the shared nodes' events where its gesture has them
                    b.fit_postures(n);
                }
                b
            })
            .collect();
        let calibration = super::recognize::calibrate(&shared, &branches, &norm, learn, seed);
        Ok(GestureModel {
            labels: sets.iter().map(|(l, _)| l.clone()).collect(),
            branches,
            calibration,
            scoring: Scoring::default(),
        })
    }
}

/// The seed of branch `g` (`held_out`: of its leave-one-out variant without that
/// demonstration).
pub(crate) fn branch_seed(seed: u64, g: usize, held_out: Option<usize>) -> u64 {
    let h = held_out.map_or(0, |i| i as u64 + 1);
    seed.wrapping_add(0x9e37_79b9_7f4a_7c15u64.wrapping_mul(g as u64 + 1))
        .wrapping_add(h.wrapping_mul(0x2545_f491_4f6c_dd1d))
}

impl Hsom {
    /// Normalised rows.
    pub(crate) fn normalise_rows(&self, rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
        rows.iter().map(|r| self.normalise(r)).collect()
    }

    /// A branch: this model's bottom level (and normalisation) with every statistic
    /// recomputed and the upper levels trained on `norm` (normalised demonstrations of one
    /// gesture) by the events extension's own training.
    pub(crate) fn branch(&self, norm: &[Vec<Vec<f64>>], learn: bool, seed: u64) -> Hsom {
        let mut b = self.clone();
        let h = b.maps.len();
        b.hits.iter_mut().for_each(|v| v.fill(0));
        b.end_hits.fill(0);
        b.qe.fill(0.0);
        b.te.fill(0.0);
        b.trained[1..].iter_mut().for_each(|t| *t = 0);
        let lens: Vec<f64> = norm.iter().map(|d| d.len() as f64).collect();
        b.demo_len = [
            lens.iter().cloned().fold(f64::INFINITY, f64::min),
            lens.iter().sum::<f64>() / lens.len().max(1) as f64,
            lens.iter().cloned().fold(0.0, f64::max),
        ];
        b.demo_runs = [0.0; 3];
        b.dwell.fill(0.0);
        b.accuracy = vec![0.0; h];
        b.lookup = vec![0.0; h];
        b.threshold = vec![0.0; h];
        b.heldout_accuracy = vec![0.0; h];
        b.heldout_lookup = vec![0.0; h];
        b.followers.iter_mut().for_each(|f| f.fill(u32::MAX));
        b.follower_at.fill(0.0);
        b.exemplars.iter_mut().for_each(|e| e.fill(u32::MAX));
        b.replay(norm);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        b.fit_events(norm, learn, &mut rng);
        b
    }
}

impl GestureModel {
    /// The same model scoring recognition another way (the thresholds stay the default
    /// scoring's: compare labels, not `unknown`, with another scoring).
    pub fn with_scoring(mut self, scoring: Scoring) -> Self {
        self.scoring = scoring;
        self
    }

    /// The gesture labels (empty for a single-gesture model).
    pub fn labels(&self) -> &[String] {
        &self.labels
    }

    /// The branches: one [`Hsom`] per label (one for a single-gesture model), each with the
    /// shared bottom level.
    pub fn branches(&self) -> &[Hsom] {
        &self.branches
    }

    /// The variables learned.
    pub fn columns(&self) -> &[String] {
        self.branches[0].columns()
    }

    /// The branch of `label`; `None` is only accepted for a single-gesture model.
    pub fn branch(&self, label: Option<&str>) -> Result<&Hsom, GestureError> {
        match (label, self.labels.is_empty()) {
            (None, true) => Ok(&self.branches[0]),
            (None, false) => Err(GestureError::LabelNeeded {
                labels: self.labels.join(", "),
            }),
            (Some(l), _) => self
                .labels
                .iter()
                .position(|x| x == l)
                .map(|i| &self.branches[i])
                .ok_or_else(|| GestureError::UnknownLabel {
                    label: l.to_string(),
                    labels: if self.labels.is_empty() {
                        "no labels (a single-gesture model: leave the gesture out)".into()
                    } else {
                        self.labels.join(", ")
                    },
                }),
        }
    }

    /// Reproduce gesture `label` from `initial` (the label primes the top of the hierarchy).
    pub fn reproduce(
        &self,
        label: Option<&str>,
        initial: &[f64],
    ) -> Result<Reproduction, GestureError> {
        Ok(self.branch(label)?.reproduce(initial)?)
    }

    /// Save: a single-gesture model exactly as [`Hsom::save`] (format 8); several gestures as
    /// format 9 (`.bin` or `.txt`), read back with every check first, written atomically.
    pub fn save(&self, path: &Path) -> Result<(), PersistError> {
        if self.labels.is_empty() {
            return self.branches[0].save(path);
        }
        let bytes = match ext(path)? {
            Format::Bin => {
                let b = self.to_bytes();
                GestureModel::from_bytes(&b, path)?;
                b
            }
            Format::Txt => {
                let t = self.to_text();
                GestureModel::from_text(&t, path)?;
                t.into_bytes()
            }
        };
        write_atomic(path, &bytes).map_err(|source| PersistError::Io {
            path: path.to_path_buf(),
            source,
        })
    }

    /// Load a model saved by [`GestureModel::save`] or [`Hsom::save`] (format 8 or 9).
    pub fn load(path: &Path) -> Result<GestureModel, PersistError> {
        let fmt = ext(path)?;
        let bytes = std::fs::read(path).map_err(|source| PersistError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        match fmt {
            Format::Bin => {
                let version = bytes
                    .get(8..12)
                    .map(|v| u32::from_le_bytes(v.try_into().unwrap_or([0; 4])));
                // a multi-gesture file of any version (an old one gets the "retrain" error)
                if bytes.len() >= 12
                    && &bytes[..8] == MAGIC
                    && version.is_some_and(|v| v > FORMAT_VERSION && v < 1000)
                {
                    GestureModel::from_bytes(&bytes, path)
                } else {
                    Ok(Hsom::from_bytes(&bytes, path)?.into())
                }
            }
            Format::Txt => {
                let t = std::str::from_utf8(&bytes).map_err(|_| PersistError::BadMagic {
                    path: path.to_path_buf(),
                })?;
                // a multi-gesture file of any version (an old one gets the "retrain" error)
                let version = t
                    .strip_prefix(&format!("{TEXT_MAGIC}\nversion "))
                    .and_then(|r| r.lines().next())
                    .and_then(|v| v.trim().parse::<u32>().ok());
                if version.is_some_and(|v| v > FORMAT_VERSION && v < 1000) {
                    GestureModel::from_text(t, path)
                } else {
                    Ok(Hsom::from_text(t, path)?.into())
                }
            }
        }
    }

    /// Format 9, binary: magic, version, label count, per label its name, calibration and
    /// branch (format 8 bytes), then an FNV-1a checksum of everything before it.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::new();
        b.extend_from_slice(MAGIC);
        b.extend_from_slice(&GESTURES_FORMAT_VERSION.to_le_bytes());
        b.extend_from_slice(&(self.labels.len() as u32).to_le_bytes());
        for ((label, cal), branch) in self
            .labels
            .iter()
            .zip(&self.calibration)
            .zip(&self.branches)
        {
            b.extend_from_slice(&(label.len() as u32).to_le_bytes());
            b.extend_from_slice(label.as_bytes());
            let values = cal.values();
            b.extend_from_slice(&(values.len() as u32).to_le_bytes());
            for v in values {
                b.extend_from_slice(&v.to_le_bytes());
            }
            let inner = branch.to_bytes();
            b.extend_from_slice(&(inner.len() as u64).to_le_bytes());
            b.extend_from_slice(&inner);
        }
        let sum = fnv1a(&b);
        b.extend_from_slice(&sum.to_le_bytes());
        b
    }

    /// Read format 9, binary; `path` only names the file in errors.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<GestureModel, PersistError> {
        let p = path.to_path_buf();
        if bytes.len() < 8 + 4 + 4 + 8 || &bytes[..8] != MAGIC {
            return Err(PersistError::BadMagic { path: p });
        }
        let body = &bytes[..bytes.len() - 8];
        let stored = u64::from_le_bytes(bytes[bytes.len() - 8..].try_into().unwrap_or([0; 8]));
        if fnv1a(body) != stored {
            return Err(corrupted(&p, "checksum mismatch".into()));
        }
        let mut r = Cursor {
            b: body,
            pos: 8,
            path: &p,
        };
        let version = r.u32("version")?;
        if version != GESTURES_FORMAT_VERSION {
            return Err(PersistError::Version {
                path: p.clone(),
                found: version,
                expected: GESTURES_FORMAT_VERSION,
            });
        }
        let n = r.u32("label count")? as usize;
        if n == 0 || n > MAX_LABELS {
            return Err(corrupted(&p, format!("{n} gesture labels")));
        }
        let (mut labels, mut calibration, mut branches) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..n {
            let len = r.u32("label length")? as usize;
            let label = String::from_utf8(r.take(len, "label")?.to_vec())
                .map_err(|_| corrupted(&p, "a label is not UTF-8".into()))?;
            let nv = r.u32("calibration length")? as usize;
            let raw = r.take(nv.saturating_mul(8), "calibration")?;
            let values: Vec<f64> = raw
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
                .collect();
            let blen = r.u64("branch length")?;
            let inner = r.take(usize::try_from(blen).unwrap_or(usize::MAX), "branch")?;
            let branch = Hsom::from_bytes(inner, &p.join(format!("[gesture {label}]")))?;
            labels.push(label);
            calibration.push(values);
            branches.push(branch);
        }
        if r.pos != body.len() {
            return Err(corrupted(&p, "bytes after the last gesture".into()));
        }
        GestureModel::assemble(labels, calibration, branches, &p)
    }

    /// Format 9, text: the format line, `version 9`, `gestures N`, then per label a
    /// `gesture NAME` line, a `calibration ...` line, a `lines K` line and its branch's text
    /// (format 8, K lines); a final checksum line.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        let _ = writeln!(s, "{TEXT_MAGIC}");
        let _ = writeln!(s, "version {GESTURES_FORMAT_VERSION}");
        let _ = writeln!(s, "gestures {}", self.labels.len());
        for ((label, cal), branch) in self
            .labels
            .iter()
            .zip(&self.calibration)
            .zip(&self.branches)
        {
            let _ = writeln!(s, "gesture {label}");
            let vals: Vec<String> = cal.values().iter().map(|v| format!("{v:e}")).collect();
            let _ = writeln!(s, "calibration {}", vals.join(" "));
            let inner = branch.to_text();
            let _ = writeln!(s, "lines {}", inner.lines().count());
            s.push_str(&inner);
        }
        let sum = fnv1a(s.as_bytes());
        let _ = writeln!(s, "checksum {sum:016x}");
        s
    }

    /// Read format 9, text; `path` only names the file in errors.
    pub fn from_text(text: &str, path: &Path) -> Result<GestureModel, PersistError> {
        let p = path.to_path_buf();
        let body_end = text
            .trim_end_matches('\n')
            .rfind('\n')
            .map(|i| i + 1)
            .ok_or_else(|| PersistError::Truncated {
                path: p.clone(),
                what: "checksum line".into(),
            })?;
        let (body, last) = text.split_at(body_end);
        let stored = last
            .trim()
            .strip_prefix("checksum ")
            .and_then(|h| u64::from_str_radix(h, 16).ok())
            .ok_or_else(|| corrupted(&p, format!("bad checksum line {:.40?}", last.trim())))?;
        if fnv1a(body.as_bytes()) != stored {
            return Err(corrupted(&p, "checksum mismatch".into()));
        }
        let lines: Vec<&str> = body.lines().collect();
        let mut at = 0usize;
        let mut next = |key: &str| -> Result<&str, PersistError> {
            let l = lines.get(at).ok_or_else(|| PersistError::Truncated {
                path: p.clone(),
                what: format!("{key} line"),
            })?;
            at += 1;
            Ok(l)
        };
        if next("format")?.trim_end() != TEXT_MAGIC {
            return Err(PersistError::BadMagic { path: p.clone() });
        }
        let v = next("version")?;
        let found: u32 = v
            .strip_prefix("version ")
            .and_then(|x| x.trim().parse().ok())
            .ok_or_else(|| corrupted(&p, format!("bad version line {v:.40?}")))?;
        if found != GESTURES_FORMAT_VERSION {
            return Err(PersistError::Version {
                path: p.clone(),
                found,
                expected: GESTURES_FORMAT_VERSION,
            });
        }
        let g = next("gestures")?;
        let n: usize = g
            .strip_prefix("gestures ")
            .and_then(|x| x.trim().parse().ok())
            .filter(|&n| (1..=MAX_LABELS).contains(&n))
            .ok_or_else(|| corrupted(&p, format!("bad gestures line {g:.40?}")))?;
        let (mut labels, mut calibration, mut branches) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..n {
            let gl = next("gesture")?;
            let label = gl
                .strip_prefix("gesture ")
                .ok_or_else(|| corrupted(&p, format!("expected a gesture line, found {gl:.40?}")))?
                .to_string();
            let cl = next("calibration")?;
            let values: Vec<f64> = cl
                .strip_prefix("calibration")
                .ok_or_else(|| {
                    corrupted(&p, format!("expected a calibration line, found {cl:.40?}"))
                })?
                .split_whitespace()
                .map(|t| t.parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| corrupted(&p, format!("bad number in {cl:.40?}")))?;
            let ll = next("lines")?;
            let k: usize = ll
                .strip_prefix("lines ")
                .and_then(|x| x.trim().parse().ok())
                .ok_or_else(|| corrupted(&p, format!("bad lines line {ll:.40?}")))?;
            let mut inner = String::new();
            for _ in 0..k {
                inner.push_str(next("branch")?);
                inner.push('\n');
            }
            let branch = Hsom::from_text(&inner, &p.join(format!("[gesture {label}]")))?;
            labels.push(label);
            calibration.push(values);
            branches.push(branch);
        }
        if at != lines.len() {
            return Err(corrupted(&p, "lines after the last gesture".into()));
        }
        GestureModel::assemble(labels, calibration, branches, &p)
    }

    /// Check what was read: plain, distinct labels, a valid calibration each, branches of the
    /// same configuration, columns, normalisation and bottom level.
    fn assemble(
        labels: Vec<String>,
        calibration: Vec<Vec<f64>>,
        branches: Vec<Hsom>,
        p: &Path,
    ) -> Result<GestureModel, PersistError> {
        for (i, l) in labels.iter().enumerate() {
            if !is_plain_label(l) || labels[..i].contains(l) {
                return Err(corrupted(p, format!("gesture label {l:?}")));
            }
        }
        let first = &branches[0];
        for (l, b) in labels.iter().zip(&branches) {
            let same = b.config == first.config
                && b.columns == first.columns
                && b.offset == first.offset
                && b.scale == first.scale
                && b.maps[0] == first.maps[0];
            if !same {
                return Err(corrupted(
                    p,
                    format!("gesture {l:?} does not share the first gesture's bottom level"),
                ));
            }
        }
        let calibration = labels
            .iter()
            .zip(calibration)
            .map(|(l, v)| {
                Calibration::from_values(&v, first.maps.len())
                    .ok_or_else(|| corrupted(p, format!("gesture {l:?}: bad calibration")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(GestureModel {
            labels,
            branches,
            calibration,
            scoring: Scoring::default(),
        })
    }
}

fn corrupted(p: &Path, what: String) -> PersistError {
    PersistError::Corrupted {
        path: p.to_path_buf(),
        what,
    }
}

/// A bounds-checked reader of the format-6 container.
struct Cursor<'a> {
    b: &'a [u8],
    pos: usize,
    path: &'a PathBuf,
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], PersistError> {
        if self.b.len() - self.pos < n {
            return Err(PersistError::Truncated {
                path: self.path.clone(),
                what: what.to_string(),
            });
        }
        let s = &self.b[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    fn u32(&mut self, what: &str) -> Result<u32, PersistError> {
        let s = self.take(4, what)?;
        Ok(u32::from_le_bytes(s.try_into().unwrap_or([0; 4])))
    }
    fn u64(&mut self, what: &str) -> Result<u64, PersistError> {
        let s = self.take(8, what)?;
        Ok(u64::from_le_bytes(s.try_into().unwrap_or([0; 8])))
    }
}

#[allow(dead_code)]
const _: () = assert!(FORMAT_VERSION < GESTURES_FORMAT_VERSION);
