//! Demonstration sets as the commands read them from paths: one gesture (a directory of CSV
//! files, or files) or labelled directories (`DIR/<label>/*.csv`, each subdirectory a
//! gesture), each demonstration first resampled when a rate is given ([`crate::resample`]),
//! and every set checked as it is read ([`demos::validate_set`]), so that what is returned
//! is valid as a set. Every error is a [`DemoError`] naming the file or directory.

use std::path::{Path, PathBuf};

use crate::demos::{self, check_gesture_columns, is_plain_label, DemoError, Demonstration};
use crate::robot::Robot;

/// Read demonstration files (a directory of *.csv or explicit files), each first resampled
/// to `resample_hz` when given ([`crate::resample::resample_all`]), checked as a set (against
/// `state_length` when given).
pub fn read_demos(
    paths: &[PathBuf],
    state_length: Option<usize>,
    resample_hz: Option<f64>,
) -> Result<Vec<Demonstration>, DemoError> {
    let demos = crate::resample::resample_all(demos::read_dir_or_files(paths)?, resample_hz)?;
    if demos.is_empty() {
        return Err(DemoError::NoFiles {
            paths: paths
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        });
    }
    demos::validate_set(&demos, state_length)?;
    Ok(demos)
}

/// Demonstrations as read from `--demos`: one unlabelled gesture (a directory of CSV files or
/// files), or labelled sets (directories whose subdirectories are the labels).
#[derive(Debug, Clone)]
pub enum DemoSets {
    /// One gesture, no label.
    Plain(Vec<Demonstration>),
    /// `(label, demonstrations)` in the order of the paths, labels sorted within a directory.
    Labelled(Vec<(String, Vec<Demonstration>)>),
}

impl DemoSets {
    /// The sets as a model is fitted on them ([`crate::hsom::HsomConfig::fit_model`]).
    pub fn gestures(&self) -> crate::hsom::Gestures<'_> {
        match self {
            DemoSets::Plain(d) => d.into(),
            DemoSets::Labelled(s) => s.into(),
        }
    }

    /// The number of variables of the first demonstration.
    pub fn width(&self) -> usize {
        self.columns().len()
    }

    /// The columns of the first demonstration (every demonstration's: a set has one).
    pub fn columns(&self) -> &[String] {
        match self {
            DemoSets::Plain(d) => &d[0].columns,
            DemoSets::Labelled(s) => &s[0].1[0].columns,
        }
    }
}

/// The robot whose recommended configuration the demonstrations at `paths` take without
/// `--config`: the one whose joints their columns are ([`Robot::of_columns`]), the left arm
/// for any other variables. They are read as [`read_demo_sets`] reads them (each resampled to
/// `resample_hz` when given), and its errors are theirs.
pub fn robot_of(paths: &[PathBuf], resample_hz: Option<f64>) -> Result<Robot, DemoError> {
    let sets = read_demo_sets(paths, None, resample_hz)?;
    Ok(Robot::of_columns(sets.columns()).unwrap_or(Robot::LeftArm))
}

/// Read `--demos`: a directory whose subdirectories hold CSV files is labelled (each
/// subdirectory's name a label, a plain word, with at least one CSV); otherwise the paths are
/// read as one gesture ([`read_demos`]). Each demonstration is first resampled to
/// `resample_hz` when given. Every subdirectory's set is checked on its own and against
/// `state_length` when given, as it is read; labels must record the same columns; a label
/// that several paths give is then checked as the one set it makes.
pub fn read_demo_sets(
    paths: &[PathBuf],
    state_length: Option<usize>,
    resample_hz: Option<f64>,
) -> Result<DemoSets, DemoError> {
    let subs: Vec<Vec<PathBuf>> = paths
        .iter()
        .map(|p| subdirectories(p))
        .collect::<Result<_, _>>()?;
    let labelled: Vec<bool> = paths
        .iter()
        .zip(&subs)
        .map(|(p, s)| !s.is_empty() && !has_csv(p))
        .collect();
    if !labelled.iter().any(|&l| l) {
        return Ok(DemoSets::Plain(read_demos(
            paths,
            state_length,
            resample_hz,
        )?));
    }
    if let Some(i) = labelled.iter().position(|&l| !l) {
        return Err(DemoError::MixedSets {
            path: paths[i].display().to_string(),
        });
    }
    let mut sets: Vec<(String, Vec<Demonstration>)> = Vec::new();
    // labels that more than one path gives
    let mut gathered: Vec<String> = Vec::new();
    for dir in subs.iter().flatten() {
        let label = dir_label(dir);
        if !is_plain_label(&label) {
            return Err(DemoError::LabelDirectory {
                path: dir.display().to_string(),
                label,
            });
        }
        let demos = demos::read_dir_or_files(std::slice::from_ref(dir))?;
        let demos = crate::resample::resample_all(demos, resample_hz)?;
        demos::validate_set(&demos, state_length)?;
        match sets.iter_mut().find(|(l, _)| *l == label) {
            Some((_, d)) => {
                d.extend(demos);
                gathered.push(label);
            }
            None => sets.push((label, demos)),
        }
    }
    for i in 0..sets.len() {
        check_gesture_columns(&sets, i)?;
    }
    for (_, demos) in sets.iter().filter(|(l, _)| gathered.contains(l)) {
        demos::validate_set(demos, state_length)?;
    }
    Ok(DemoSets::Labelled(sets))
}

/// A directory's name, as a gesture label.
pub fn dir_label(dir: &Path) -> String {
    dir.file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default()
}

/// The entries of a directory, naming it when it cannot be read.
fn entries(dir: &Path) -> Result<Vec<PathBuf>, DemoError> {
    let io = |source| DemoError::Io {
        path: dir.display().to_string(),
        source,
    };
    let mut paths = Vec::new();
    for e in std::fs::read_dir(dir).map_err(io)? {
        paths.push(e.map_err(io)?.path());
    }
    paths.sort();
    Ok(paths)
}

/// Subdirectories of a directory, sorted (empty for a file).
pub fn subdirectories(path: &Path) -> Result<Vec<PathBuf>, DemoError> {
    if !path.is_dir() {
        return Ok(Vec::new());
    }
    Ok(entries(path)?.into_iter().filter(|p| p.is_dir()).collect())
}

/// True when `p` names a `*.csv` file.
fn is_csv(p: &Path) -> bool {
    p.is_file()
        && p.extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| x.eq_ignore_ascii_case("csv"))
}

/// True when the directory holds a `*.csv` file.
pub fn has_csv(path: &Path) -> bool {
    std::fs::read_dir(path).is_ok_and(|rd| rd.flatten().any(|e| is_csv(&e.path())))
}

/// The `*.csv` files of a directory, sorted; an error naming it when there is none.
pub fn csv_files(dir: &Path) -> Result<Vec<PathBuf>, DemoError> {
    let files: Vec<PathBuf> = entries(dir)?.into_iter().filter(|p| is_csv(p)).collect();
    if files.is_empty() {
        return Err(DemoError::EmptyDirectory {
            path: dir.display().to_string(),
        });
    }
    Ok(files)
}
