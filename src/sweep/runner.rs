//! Running a sweep: check the output directory (it holds this spec's runs or none), skip the
//! runs already recorded (resume), run the others of the shard on a thread pool, each
//! written to `DIR/runs/<run-id>.json` as it finishes.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::eval::Pool;

use super::run::{execute_run, RunRecord};
use super::shard::Shard;
use super::spec::{identity_hash, Identity, RunPlan, SweepSpec};
use super::{read_json, write_json, SweepError};

/// Name of the manifest in the output directory.
pub const MANIFEST: &str = "sweep.json";
/// Folder of the run files in the output directory.
pub const RUNS_DIR: &str = "runs";

/// `DIR/sweep.json`: which spec the directory's runs belong to.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// `SweepSpec::hash`.
    pub spec_hash: String,
    /// What the hash is of.
    pub identity: Identity,
    /// The spec file the sweep was started with.
    pub spec_file: String,
    /// The sweep's name.
    pub name: String,
    /// Runs in the whole grid.
    pub runs: usize,
    /// Every run id of the grid, in order.
    pub run_ids: Vec<String>,
}

impl Manifest {
    /// Read `DIR/sweep.json`.
    pub fn read(dir: &Path) -> Result<Manifest, SweepError> {
        read_json(&dir.join(MANIFEST), "read the sweep manifest", |e| {
            format!("not a sweep manifest: {e}")
        })
    }
}

/// How to run.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepOptions {
    /// Which runs.
    pub shard: Shard,
    /// Worker threads; `None`: every core.
    pub threads: Option<usize>,
    /// Run again the runs whose file records a failure.
    pub retry_failed: bool,
}

/// What the progress callback hears.
#[derive(Debug)]
pub enum Progress<'a> {
    /// Before the first run: runs to do now, runs of the shard already recorded.
    Start {
        /// Runs that will run.
        to_run: usize,
        /// Runs of the shard skipped because their file exists.
        skipped: usize,
        /// Worker threads.
        threads: usize,
    },
    /// A run finished and its file is written.
    Done(&'a RunRecord),
}

/// What a sweep did.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepSummary {
    /// Runs in the grid.
    pub grid: usize,
    /// Runs in this shard.
    pub in_shard: usize,
    /// Runs skipped (already recorded).
    pub skipped: usize,
    /// Runs run now.
    pub ran: usize,
    /// Of those, runs that recorded a failure.
    pub failed: usize,
    /// Wall time of the sweep, seconds.
    pub wall_s: f64,
    /// Sum of the wall times of the runs run now, seconds.
    pub runs_s: f64,
    /// Worker threads.
    pub threads: usize,
}

/// The run file of run `id` in `dir`.
pub fn run_path(dir: &Path, id: &str) -> PathBuf {
    dir.join(RUNS_DIR).join(format!("{id}.json"))
}

/// The run files in `dir/runs` (not the temporary files of writes in progress), sorted.
pub fn run_files(dir: &Path) -> Result<Vec<PathBuf>, SweepError> {
    let runs = dir.join(RUNS_DIR);
    let entries = match std::fs::read_dir(&runs) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(SweepError::io("list", &runs)(e)),
    };
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().is_some_and(|x| x == "json")
                && !p
                    .file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with('.'))
        })
        .collect();
    files.sort();
    Ok(files)
}

/// Every run file of `dir`, each checked to be a run of the spec whose hash is `hash` (`whose`:
/// where that hash is from, and `advice`, for the message).
pub fn read_runs_of(
    dir: &Path,
    hash: &str,
    whose: &str,
    advice: &str,
) -> Result<Vec<RunRecord>, SweepError> {
    let mut runs = Vec::new();
    for f in run_files(dir)? {
        let r = RunRecord::read(&f)?;
        if r.spec_hash != hash {
            return Err(SweepError::OutDir {
                path: dir.to_path_buf(),
                message: format!(
                    "{} is a run of another spec (hash {}, {whose} {hash}){advice}",
                    f.display(),
                    r.spec_hash,
                ),
            });
        }
        runs.push(r);
    }
    Ok(runs)
}

/// Check that `dir` holds this spec's runs or none, write its manifest, and return the runs
/// of `shard` still to do (every check before any run starts).
fn prepare(
    spec: &SweepSpec,
    dir: &Path,
    plans: &[RunPlan],
    options: &SweepOptions,
) -> Result<(Vec<RunPlan>, usize), SweepError> {
    let hash = spec.hash();
    let identity = spec.identity();
    let manifest_path = dir.join(MANIFEST);
    if manifest_path.exists() {
        let m = Manifest::read(dir)?;
        if m.spec_hash != hash || identity_hash(&m.identity) != hash {
            return Err(SweepError::OutDir {
                path: dir.to_path_buf(),
                message: format!(
                    "holds the runs of another spec ({}, {}: {}); give a new --out, or delete \
                     the directory to start again",
                    m.spec_file,
                    m.name,
                    identity_difference(&m.identity, &identity)
                ),
            });
        }
    }
    let runs = dir.join(RUNS_DIR);
    std::fs::create_dir_all(&runs).map_err(SweepError::io("create", &runs))?;
    let manifest = Manifest {
        spec_hash: hash.clone(),
        identity,
        spec_file: spec.source.display().to_string(),
        name: spec.settings.name.clone(),
        runs: plans.len(),
        run_ids: plans.iter().map(|p| p.id.clone()).collect(),
    };
    if !manifest_path.exists() {
        write_json(&manifest_path, &manifest, "write")?;
    }
    // every run file must be this spec's; finished runs of the shard are skipped
    let done: std::collections::HashSet<String> =
        read_runs_of(dir, &hash, "this spec", "; give a new --out")?
            .into_iter()
            .filter(|r| !(options.retry_failed && r.failed()))
            .map(|r| r.run_id)
            .collect();
    let shard: Vec<&RunPlan> = plans
        .iter()
        .filter(|p| options.shard.contains(p.index))
        .collect();
    let todo: Vec<RunPlan> = shard
        .iter()
        .filter(|p| !done.contains(&p.id))
        .map(|p| (*p).clone())
        .collect();
    Ok((todo, shard.len()))
}

/// Which part of two identities differs, for the message.
fn identity_difference(old: &Identity, new: &Identity) -> String {
    if old.settings != new.settings {
        format!("settings {} there, {} now", old.settings, new.settings)
    } else if old.axes != new.axes {
        format!("axes {} there, {} now", old.axes, new.axes)
    } else {
        let changed: Vec<&str> = new
            .config_sha256
            .iter()
            .filter(|(k, v)| old.config_sha256.get(*k) != Some(v))
            .map(|(k, _)| k.as_str())
            .collect();
        format!(
            "configuration file(s) changed since: {}",
            changed.join(", ")
        )
    }
}

/// Run the runs of `options.shard` not yet recorded in `dir`, on the worker pool
/// ([`Pool`]) of `options.threads` threads. Every check (spec, output
/// directory, existing run files) is done before the first run; a run that fails is recorded
/// and the sweep goes on. `progress` hears the start and every finished run.
pub fn run_sweep(
    spec: &SweepSpec,
    dir: &Path,
    options: &SweepOptions,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<SweepSummary, SweepError> {
    let t = Instant::now();
    if options.threads == Some(0) {
        return Err(SweepError::Invalid(
            "--threads 0: need at least 1 worker thread".into(),
        ));
    }
    let plans = spec.runs();
    let (todo, in_shard) = prepare(spec, dir, &plans, options)?;
    let pool = Pool::new(options.threads.unwrap_or(0)).map_err(SweepError::Invalid)?;
    let threads = pool.threads();
    progress(Progress::Start {
        to_run: todo.len(),
        skipped: in_shard - todo.len(),
        threads,
    });
    let hash = spec.hash();
    let shard = options.shard.label();
    let outcomes = pool.map(
        &todo,
        |plan: &RunPlan| {
            let record = execute_run(spec, plan, &hash, &shard);
            record.write(&run_path(dir, &plan.id))?;
            progress(Progress::Done(&record));
            Ok::<_, SweepError>((record.failed(), record.wall_s))
        },
        None,
    );
    let (written, errors): (Vec<_>, Vec<_>) = outcomes.into_iter().partition(Result::is_ok);
    if let Some(Err(first)) = errors.into_iter().next() {
        return Err(SweepError::Record {
            path: dir.join(RUNS_DIR),
            message: format!(
                "{} run file(s) could not be written; the first: {first}",
                todo.len() - written.len()
            ),
        });
    }
    let written: Vec<(bool, f64)> = written.into_iter().flatten().collect();
    Ok(SweepSummary {
        grid: plans.len(),
        in_shard,
        skipped: in_shard - todo.len(),
        ran: todo.len(),
        failed: written.iter().filter(|(failed, _)| *failed).count(),
        wall_s: t.elapsed().as_secs_f64(),
        runs_s: written.iter().map(|(_, wall_s)| wall_s).sum(),
        threads,
    })
}
