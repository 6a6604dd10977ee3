//! Leave-one-out, and the in-sample result beside it, over methods x an executor: for each
//! demonstration of a gesture in turn, learn from the others, reproduce from its first
//! sample, execute, and score against it alone; in-sample, learn from all.

use crate::config::HsomConfig;
use crate::demo_sets::{read_demo_sets, DemoSets};
use crate::demos::Demonstration;

use super::executor::Executor;
use super::fold::{diagonal, fold, Conditioning, FoldInput, Split, Training};
use super::method::Method;
use super::results::GestureLoo;
use super::results::{Fold, Run};
use crate::gmr::MIN_DEMONSTRATIONS;

/// Gestures by name, each with its demonstrations.
pub type Gestures = Vec<(String, Vec<Demonstration>)>;

/// Which methods run besides the hierarchy and the nearest sequence, and whether the
/// in-sample result is computed too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LooSettings {
    /// The configuration at height 1.
    pub height_1: bool,
    /// GMM/GMR.
    pub gmr: bool,
    /// ProMP conditioned on the initial posture.
    pub promp: bool,
    /// The DMP from the initial posture to the mean end.
    pub dmp: bool,
    /// The DTW mean of the training demonstrations (DBA).
    pub dba: bool,
    /// The replay of the nearest training demonstration.
    pub replay: bool,
    /// Learn from all and score against each too.
    pub in_sample: bool,
    /// What the reproductions are conditioned on besides the initial posture.
    pub conditioning: Conditioning,
    /// A far goal `K` ([`FoldInput::far`]), `None` for none.
    pub far: Option<f64>,
    /// Teach every fold's hierarchy in two sittings ([`Training::Sittings`]): half its
    /// training demonstrations, then an update with the rest.
    pub sittings: bool,
    /// Worker threads (at least 1).
    pub threads: usize,
    /// Keep what every fold's methods learned ([`super::Fold::learned`]), for the loop study
    /// ([`super::in_loop`]).
    pub keep_learned: bool,
}

impl Default for LooSettings {
    fn default() -> Self {
        LooSettings {
            height_1: true,
            gmr: true,
            promp: true,
            dmp: true,
            dba: true,
            replay: true,
            in_sample: true,
            conditioning: Conditioning::Unconditioned,
            far: None,
            sittings: false,
            threads: 1,
            keep_learned: false,
        }
    }
}

impl LooSettings {
    /// The methods these settings run; `held_out` false drops the replay (in-sample it would
    /// replay the demonstration scored against).
    pub fn methods(&self, held_out: bool) -> Vec<Method> {
        Method::ALL
            .into_iter()
            .filter(|m| match m {
                Method::Hierarchy | Method::NearestSequence => true,
                Method::Height1 => self.height_1,
                Method::GmmGmr => self.gmr,
                Method::ProMP => self.promp,
                Method::Dmp => self.dmp,
                Method::Dba => self.dba,
                Method::Replay => self.replay && held_out,
            })
            .collect()
    }
}

/// Fewest demonstrations of a taught label in recognition held out: one held out leaves two
/// to learn from, so that the label's threshold is still calibrated held out.
pub const MIN_TAUGHT_DEMOS: usize = 3;

/// Why a held-out study was refused: leave-one-out ([`leave_one_out`]) or recognition
/// ([`recognition`](super::recognition)).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LooError {
    /// Too few demonstrations to leave one out.
    #[error("gesture '{gesture}': leave-one-out needs at least 3 demonstrations (2 to learn from, 1 to score against), got {found}")]
    TooFew {
        /// The gesture.
        gesture: String,
        /// Demonstrations given.
        found: usize,
    },
    /// No gesture given.
    #[error("no gesture to evaluate")]
    Empty,
    /// Recognition: no taught gesture given.
    #[error("no taught gesture: give at least one directory of demonstrations to teach")]
    NoTaught,
    /// Recognition: a taught label with too few demonstrations to hold one out.
    #[error("taught gesture '{label}': recognition held out needs at least {MIN_TAUGHT_DEMOS} demonstrations (one held out, two to learn from), got {found}")]
    TooFewTaught {
        /// The label.
        label: String,
        /// Demonstrations given.
        found: usize,
    },
    /// Recognition: a label given twice (taught twice, untaught twice, or both).
    #[error("gesture label '{label}' is given twice ({first} and {second}): each label once, taught or untaught")]
    DuplicateLabel {
        /// The label.
        label: String,
        /// Where it was first given: `taught` or `untaught`.
        first: &'static str,
        /// Where it was given again.
        second: &'static str,
    },
    /// Recognition: a path that is not a directory.
    #[error("{path}: not a directory; give a directory of CSV files (one gesture, named after the directory) or of gesture subdirectories (DIR/<gesture>/*.csv)")]
    NotADirectory {
        /// The path.
        path: String,
    },
    /// Recognition: a label (a directory's name) that is not a plain word.
    #[error("{path}: the gesture label {label:?} is not a plain word: name the directory with letters, digits, '_' and '-' only")]
    BadLabel {
        /// The directory.
        path: String,
        /// The label.
        label: String,
    },
    /// Recognition: a demonstration whose columns are not the first taught demonstration's.
    #[error("{path}: columns {found:?}, but the first taught demonstration ({first}) has {expected:?}; every gesture must record the same variables")]
    Columns {
        /// The demonstration.
        path: String,
        /// Its columns.
        found: Vec<String>,
        /// The first taught demonstration.
        first: String,
        /// Its columns.
        expected: Vec<String>,
    },
    /// Recognition: training or recognition refused (`what`: the model of which fold).
    #[error("{what}: {source}")]
    Gesture {
        /// Which model: the fold's held-out demonstration, or the model of all.
        what: String,
        /// The cause.
        source: Box<crate::hsom::GestureError>,
    },
    /// A bad setting.
    #[error("threads = {0}: needs at least 1")]
    Threads(usize),
    /// A far goal that is not a finite number >= 0.
    #[error("far goal K = {0}: needs a finite number >= 0 (times the demonstrations' end spread)")]
    Far(f64),
    /// The worker threads could not be started.
    #[error("{0}")]
    Pool(String),
    /// The configuration (at height 1, or for the data's width) is not valid.
    #[error(transparent)]
    Config(#[from] crate::config::ConfigError),
    /// The demonstrations' width is not the configuration's state length.
    #[error("{path}: {found} columns but the configuration's stateLength is {expected}; give a configuration for {found} variables, or take stateLength from the data")]
    Width {
        /// The first file of another width.
        path: String,
        /// The configuration's state length.
        expected: usize,
        /// The file's columns.
        found: usize,
    },
    /// A demonstration is not valid (non-finite values, columns that differ within a
    /// gesture, ...).
    #[error(transparent)]
    Demo(#[from] crate::demos::DemoError),
    /// An output cannot be written where it was asked.
    #[error(transparent)]
    Output(#[from] crate::fsutil::NotWritable),
    /// The hierarchy produced no reproduction on any fold: nothing to compare.
    #[error("the hierarchy produced no reproduction on any fold: {0}")]
    NoReproduction(String),
    /// An output file could not be written.
    #[error("writing {}", path.display())]
    Write {
        /// The file.
        path: std::path::PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A section computed from the folds besides the tables could not be (the simulator's
    /// execution of the reproductions).
    #[error("{0}")]
    Extra(String),
    /// The figure could not be drawn or written.
    #[cfg(feature = "plot")]
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}

/// Every demonstration of the configuration's `stateLength`, else the first that is not.
pub(super) fn check_width<'a>(
    mut demos: impl Iterator<Item = &'a Demonstration>,
    config: &HsomConfig,
) -> Result<(), LooError> {
    let expected = config.params().state_length;
    match demos.find(|d| d.width() != expected) {
        Some(d) => Err(LooError::Width {
            path: d.source.clone(),
            expected,
            found: d.width(),
        }),
        None => Ok(()),
    }
}

/// Write `bytes` atomically to `path`, naming it on failure.
pub(super) fn write(path: &std::path::Path, bytes: &[u8]) -> Result<(), LooError> {
    crate::fsutil::write_atomic(path, bytes).map_err(|source| LooError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// The gestures of `paths` as `cosco train` reads them: a directory of CSV files or files
/// (one gesture, named after its directory, else `gesture`), or directories of gesture
/// subdirectories (`DIR/<gesture>/*.csv`, each gesture on its own), each demonstration first
/// resampled to `resample_hz` when given ([`crate::resample::resample_all`]). With
/// `from_data` the configuration is adapted to the data's width ([`HsomConfig::for_width`]);
/// otherwise [`leave_one_out`] refuses files without the configuration's `stateLength`
/// columns.
pub fn read_gestures_at(
    paths: &[std::path::PathBuf],
    config: &HsomConfig,
    from_data: bool,
    resample_hz: Option<f64>,
) -> Result<(HsomConfig, Gestures), LooError> {
    let sets = match read_demo_sets(paths, None, resample_hz)? {
        DemoSets::Plain(d) => {
            let name = match paths {
                [one] if one.is_dir() => one.file_name().map(|n| n.to_string_lossy().to_string()),
                _ => None,
            };
            vec![(name.unwrap_or_else(|| "gesture".into()), d)]
        }
        DemoSets::Labelled(sets) => sets,
    };
    let width = sets[0].1[0].width();
    let config = if from_data {
        config.for_width(width)?
    } else {
        config.clone()
    };
    Ok((config, sets))
}

/// Leave-one-out on each gesture's demonstrations (`(name, demonstrations)`; each set is
/// checked first: at least 3, of the configuration's `stateLength`, valid), with the
/// settings' methods carried out by `executor` ([`Kinematic`](super::Kinematic): the postures
/// as they are); `progress(done, total)` after each fold when given. Folds run on
/// `settings.threads` threads; the result does not depend on their number.
pub fn leave_one_out<E: Executor>(
    config: &HsomConfig,
    gestures: Gestures,
    settings: &LooSettings,
    executor: &E,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<Vec<GestureLoo>, LooError> {
    if gestures.is_empty() {
        return Err(LooError::Empty);
    }
    if settings.threads == 0 {
        return Err(LooError::Threads(0));
    }
    if let Some(k) = settings.far.filter(|k| !(k.is_finite() && *k >= 0.0)) {
        return Err(LooError::Far(k));
    }
    if let Some((g, d)) = gestures.iter().find(|(_, d)| d.len() < 3) {
        return Err(LooError::TooFew {
            gesture: g.clone(),
            found: d.len(),
        });
    }
    check_width(gestures.iter().flat_map(|(_, d)| d), config)?;
    for (_, demos) in &gestures {
        crate::demos::validate_set(demos, None)?;
    }
    let height_1 = match settings.height_1 {
        true => Some(config.at_height(1)?),
        false => None,
    };
    let diagonals: Vec<f64> = gestures.iter().map(|(_, d)| diagonal(d)).collect();
    let pool = super::Pool::new(settings.threads).map_err(LooError::Pool)?;
    let base = FoldInput {
        config: Some(config),
        height_1: height_1.as_ref(),
        conditioning: settings.conditioning,
        far: settings.far,
        training: match settings.sittings {
            true => Training::Sittings,
            false => Training::Trained,
        },
        keep: settings.keep_learned,
        ..FoldInput::new(&[], &[])
    };
    let sets: Vec<(&[Demonstration], f64)> = (gestures.iter().map(|(_, d)| &d[..]))
        .zip(diagonals.iter().copied())
        .collect();
    let in_sample = settings.methods(false);
    let mut folds = loo_folds(
        &sets,
        &settings.methods(true),
        settings.in_sample.then_some(&in_sample[..]),
        &base,
        executor,
        &pool,
        progress,
    )
    .into_iter();
    let mut out = Vec::new();
    for (g, (name, demos)) in gestures.into_iter().enumerate() {
        let (held_out, in_sample) = folds.next().unwrap_or_default();
        out.push(GestureLoo {
            gesture: name,
            demonstrations: demos,
            diagonal: diagonals[g],
            held_out,
            in_sample,
        });
    }
    Ok(out)
}

/// Leave-one-out with the evaluator's folds ([`loo_map`]): on each set of `sets` (one
/// gesture's demonstrations and their diagonal), every demonstration held out in turn,
/// `held_out`'s methods learning from the others as `base` says (its training progress
/// aside), reproducing from its first posture and scored against it alone ([`fold`]); with
/// `in_sample`, those methods also learn from all and are scored against it. A baseline that
/// learns from demonstrations alone (GMM/GMR, ProMP) and has fewer than
/// [`MIN_DEMONSTRATIONS`] to learn from on a fold holds the reason. Per set, its held-out
/// folds and its in-sample folds, in demonstration order.
pub fn loo_folds<E: Executor>(
    sets: &[(&[Demonstration], f64)],
    held_out: &[Method],
    in_sample: Option<&[Method]>,
    base: &FoldInput<'_>,
    executor: &E,
    pool: &super::Pool,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Vec<(Vec<Fold>, Vec<Fold>)> {
    // `base` without its training progress (not shared between threads)
    let FoldInput {
        config,
        height_1,
        training,
        conditioning,
        far,
        gmr_components,
        keep,
        ..
    } = *base;
    let demos: Vec<&[Demonstration]> = sets.iter().map(|(d, _)| *d).collect();
    let work = |s: usize, split: Split| {
        let (demos, diag) = sets[s];
        let base = &FoldInput {
            config,
            height_1,
            training,
            conditioning,
            far,
            gmr_components,
            keep,
            ..FoldInput::new(&[], &[])
        };
        match (split, in_sample) {
            (Split::InSample(_), Some(methods)) => {
                limited_fold(methods, base, demos, split, diag, executor)
            }
            _ => limited_fold(held_out, base, demos, split, diag, executor),
        }
    };
    loo_map(&demos, in_sample.is_some(), pool, progress, work)
}

/// The one leave-one-out loop: on each set of `sets`, `work(set, Split::HeldOut(i))` for
/// every demonstration `i` in turn and, with `in_sample`, `work(set, Split::InSample(i))`
/// beside it. The work of every set shares `pool` (`progress(done, total)` after each job);
/// the result does not depend on its threads. Per set, its held-out results and its
/// in-sample results, in demonstration order.
pub fn loo_map<T: Send>(
    sets: &[&[Demonstration]],
    in_sample: bool,
    pool: &super::Pool,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    work: impl Fn(usize, Split) -> T + Sync,
) -> Vec<(Vec<T>, Vec<T>)> {
    let mut jobs = Vec::new();
    for (s, demos) in sets.iter().enumerate() {
        for i in 0..demos.len() {
            jobs.push((s, Split::HeldOut(i)));
            if in_sample {
                jobs.push((s, Split::InSample(i)));
            }
        }
    }
    let mut done = pool
        .map(&jobs, |&(s, split)| work(s, split), progress)
        .into_iter();
    sets.iter()
        .map(|demos| {
            let (mut held, mut ins) = (Vec::new(), Vec::new());
            for _ in 0..demos.len() {
                held.extend(done.next());
                if in_sample {
                    ins.extend(done.next());
                }
            }
            (held, ins)
        })
        .collect()
}

/// [`fold`], with a baseline that learns from demonstrations alone (GMM/GMR, ProMP) refused
/// when the split leaves it fewer than [`MIN_DEMONSTRATIONS`] to learn from (the reason
/// names the fold and the method).
fn limited_fold<E: Executor>(
    methods: &[Method],
    base: &FoldInput<'_>,
    demos: &[Demonstration],
    split: Split,
    diag: f64,
    executor: &E,
) -> Fold {
    let baseline = |m: &Method| matches!(m, Method::GmmGmr | Method::ProMP);
    let (learn_from, n) = match split {
        Split::HeldOut(i) => (demos.len() - 1, i + 1),
        Split::InSample(i) => (demos.len(), i + 1),
        Split::InSampleAll => (demos.len(), 1),
    };
    let (run, skip): (Vec<Method>, Vec<Method>) = methods
        .iter()
        .partition(|m| !baseline(m) || learn_from >= MIN_DEMONSTRATIONS);
    let mut f = fold(&run, base, demos, split, diag, executor);
    f.runs.extend(skip.iter().map(|&method| {
        let why = format!(
            "fold {n}: {} needs at least {MIN_DEMONSTRATIONS} demonstrations to learn from, \
             this fold has {learn_from}",
            method.name(),
        );
        Run::failed(method, why)
    }));
    f
}
