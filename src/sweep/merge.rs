//! Merging a sweep's run files (from one machine or many shards) into tables and plots:
//! median, mean and interquartile range of every metric per method and axis value, paired
//! wins (CoSCo-HSOM against GMM/GMR on the same demonstrations), box plots by method and
//! gesture, and the list of failed runs. The tables depend on the run files' metrics only
//! (not on wall times, shards or file order), so N shards merged give the unsharded tables.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use plotters::style::RGBColor;

use crate::experiment::baseline::GMR_COLOR;
use crate::fsutil::write_atomic;
use crate::plot::{boxplots_png, BoxPanel};
use crate::stats::quantile;
use crate::table::Table;

use super::run::RunRecord;
use super::runner::{read_runs_of, Manifest};
use super::spec::{method_name, AxisValues};
use super::SweepError;
use crate::eval::Method;
use crate::metrics::registry::{Better, Metric, SWEEP as METRICS};
use crate::robot::Robot;

/// Files `merge` writes into the sweep directory.
pub const TABLES_MD: &str = "tables.md";
/// Long CSV of the statistics.
pub const TABLES_CSV: &str = "tables.csv";
/// CSV of the paired wins.
pub const WINS_CSV: &str = "wins.csv";
/// Wall and training times (they differ between machines and shards).
pub const TIMING_MD: &str = "timing.md";
/// Folder of the box plots.
pub const PLOTS_DIR: &str = "plots";

/// Median, mean and quartiles of some values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    /// How many values.
    pub n: usize,
    /// Median.
    pub median: f64,
    /// Mean.
    pub mean: f64,
    /// First quartile.
    pub q1: f64,
    /// Third quartile.
    pub q3: f64,
}

impl Stats {
    /// Of the finite `values`; `None` when there are none. Quartiles: [`quantile`].
    pub fn of(values: impl IntoIterator<Item = f64>) -> Option<Stats> {
        let mut v: Vec<f64> = values.into_iter().filter(|x| x.is_finite()).collect();
        v.sort_by(f64::total_cmp);
        Some(Stats {
            n: v.len(),
            median: quantile(&v, 0.5)?,
            mean: v.iter().sum::<f64>() / v.len() as f64,
            q1: quantile(&v, 0.25)?,
            q3: quantile(&v, 0.75)?,
        })
    }
}

/// One method's metrics in one run.
struct Sample<'a> {
    axes: &'a AxisValues,
    method: Method,
    metrics: &'a BTreeMap<String, f64>,
}

/// What `merge` found and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct MergeSummary {
    /// Runs in the grid.
    pub grid: usize,
    /// Run files found.
    pub recorded: usize,
    /// Runs with a failure, `id: error` (a failed method counts).
    pub failed: Vec<String>,
    /// Runs of the grid without a file.
    pub missing: Vec<String>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// Read every run file of `dir` (checked against `dir/sweep.json`), sorted by grid index.
pub fn read_runs(dir: &Path) -> Result<(Manifest, Vec<RunRecord>), SweepError> {
    let manifest = Manifest::read(dir)?;
    let hash = &manifest.spec_hash;
    let mut runs = read_runs_of(dir, hash, "the directory's sweep.json", "")?;
    runs.sort_by_key(|r| r.index);
    Ok((manifest, runs))
}

/// Merge the runs recorded in `dir` into `tables.md`, `tables.csv`, `wins.csv`, `timing.md`
/// and `plots/<metric>.png` there (all written atomically).
pub fn merge(dir: &Path) -> Result<MergeSummary, SweepError> {
    let (manifest, runs) = read_runs(dir)?;
    let samples: Vec<Sample> = runs
        .iter()
        .filter(|r| r.error.is_none())
        .flat_map(|r| {
            r.methods
                .iter()
                .filter(|m| m.error.is_none())
                .map(move |m| Sample {
                    axes: &r.axes,
                    method: m.method,
                    metrics: &m.metrics,
                })
        })
        .collect();
    let failed: Vec<String> = runs
        .iter()
        .flat_map(|r| {
            let whole = r.error.iter().map(move |e| format!("{}: {e}", r.run_id));
            let methods = r.methods.iter().filter_map(move |m| {
                m.error
                    .as_ref()
                    .map(|e| format!("{} ({}): {e}", r.run_id, method_name(m.method)))
            });
            whole.chain(methods)
        })
        .collect();
    let have: std::collections::HashSet<&str> = runs.iter().map(|r| r.run_id.as_str()).collect();
    let missing: Vec<String> = manifest
        .run_ids
        .iter()
        .filter(|id| !have.contains(id.as_str()))
        .cloned()
        .collect();
    let methods = methods_of(&samples);
    let rows = rows_of(&runs);

    let mut files = Vec::new();
    let mut write = |name: &str, bytes: Vec<u8>| -> Result<(), SweepError> {
        let p = dir.join(name);
        write_atomic(&p, &bytes).map_err(SweepError::io("write", &p))?;
        files.push(p);
        Ok(())
    };
    let md = tables_md(
        &manifest, &runs, &samples, &methods, &rows, &failed, &missing,
    );
    write(TABLES_MD, md.into_bytes())?;
    write(TABLES_CSV, tables_csv(&samples, &methods, &rows)?)?;
    write(WINS_CSV, wins_csv(&samples, &rows)?)?;
    write(TIMING_MD, timing_md(&manifest, &runs).into_bytes())?;
    let plots = dir.join(PLOTS_DIR);
    std::fs::create_dir_all(&plots).map_err(SweepError::io("create", &plots))?;
    if !samples.is_empty() {
        for m in &METRICS {
            let p = plots.join(format!("{}.png", m.key));
            if box_plot(&p, &manifest.name, m, &samples, &methods)? {
                files.push(p);
            }
        }
    }
    Ok(MergeSummary {
        grid: manifest.runs,
        recorded: runs.len(),
        failed,
        missing,
        files,
    })
}

fn methods_of(samples: &[Sample]) -> Vec<Method> {
    let mut m: Vec<Method> = samples.iter().map(|s| s.method).collect();
    m.sort();
    m.dedup();
    m
}

/// A row of the tables: an axis and its value, or `("all", "all")`.
type Row = (&'static str, String);

/// The axes of the tables' rows, in order (`method` is the columns).
const ROW_AXES: [&str; 8] = [
    "robot",
    "gesture",
    "seed",
    "config",
    "noise",
    "count",
    "height",
    "evaluation",
];

/// The rows of a table: `("all", "all")`, then each value of each of [`ROW_AXES`] that has
/// more than one value among the runs, in the order of the runs.
fn rows_of(runs: &[RunRecord]) -> Vec<Row> {
    let mut rows = vec![("all", "all".to_string())];
    for axis in &ROW_AXES {
        let mut values: Vec<String> = Vec::new();
        for r in runs {
            let v = r.axes.value(axis);
            if !values.contains(&v) {
                values.push(v);
            }
        }
        if values.len() > 1 {
            rows.extend(values.into_iter().map(|v| (*axis, v)));
        }
    }
    rows
}

fn in_row(s: &AxisValues, row: &Row) -> bool {
    row.0 == "all" || s.value(row.0) == row.1
}

fn stats_of(samples: &[Sample], metric: &str, method: Method, row: &Row) -> Option<Stats> {
    Stats::of(
        samples
            .iter()
            .filter(|s| s.method == method && in_row(s.axes, row))
            .filter_map(|s| s.metrics.get(metric).copied()),
    )
}

/// Wins of CoSCo-HSOM and GMM/GMR on `metric`, and ties, over the pairs in `row`: the two
/// methods on the same demonstrations (every axis equal but `method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Wins {
    hsom: usize,
    gmr: usize,
    ties: usize,
}

fn pair_key(a: &AxisValues) -> String {
    ROW_AXES
        .iter()
        .map(|x| a.value(x))
        .collect::<Vec<_>>()
        .join("\u{1f}")
}

fn wins(samples: &[Sample], metric: &Metric, row: &Row) -> Option<Wins> {
    if metric.better == Better::Neither {
        return None;
    }
    let mut pairs: BTreeMap<String, [Option<f64>; 2]> = BTreeMap::new();
    for s in samples.iter().filter(|s| in_row(s.axes, row)) {
        let slot = match s.method {
            Method::Hierarchy => 0,
            Method::GmmGmr => 1,
            _ => continue,
        };
        pairs.entry(pair_key(s.axes)).or_default()[slot] = s.metrics.get(metric.key).copied();
    }
    let score = |x: f64| match metric.better {
        Better::TowardOne => x.ln().abs(),
        _ => x,
    };
    let mut w = Wins::default();
    let mut any = false;
    for [h, g] in pairs.into_values() {
        let (Some(h), Some(g)) = (h, g) else { continue };
        any = true;
        let (h, g) = (score(h), score(g));
        if h < g {
            w.hsom += 1;
        } else if g < h {
            w.gmr += 1;
        } else {
            w.ties += 1;
        }
    }
    any.then_some(w)
}

fn fmt(v: f64, digits: usize) -> String {
    format!("{v:.digits$}")
}

#[allow(clippy::too_many_arguments)]
fn tables_md(
    manifest: &Manifest,
    runs: &[RunRecord],
    samples: &[Sample],
    methods: &[Method],
    rows: &[Row],
    failed: &[String],
    missing: &[String],
) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Sweep `{}`: merged tables\n\n{} of {} runs recorded, {} with a failure{}. Spec \
         hash `{}`. Made by `cosco sweep merge` from the run files (`runs/*.json`); wall \
         times are in `{TIMING_MD}`.\n",
        manifest.name,
        runs.len(),
        manifest.runs,
        failed.len(),
        if missing.is_empty() {
            ""
        } else {
            " (incomplete: see the end)"
        },
        manifest.spec_hash
    );
    // the left arm, the default robot, goes without saying
    let fixed: Vec<String> = ROW_AXES
        .iter()
        .filter(|a| !rows.iter().any(|r| r.0 == **a))
        .filter_map(|a| runs.first().map(|r| (a, r.axes.value(a))))
        .filter(|(a, v)| !(**a == "robot" && v == Robot::LeftArm.name()))
        .map(|(a, v)| format!("{a} = {v}"))
        .collect();
    if !fixed.is_empty() {
        let _ = writeln!(md, "Same in every run: {}.\n", fixed.join(", "));
    }
    let _ = writeln!(
        md,
        "Each cell: median / mean / interquartile range (first to third quartile) over the \
         runs of the row, `n` runs. Paired wins: the two methods on the same demonstrations \
         (every axis equal), CoSCo-HSOM wins - GMM/GMR wins - ties.\n"
    );
    let has_pairs = methods.contains(&Method::Hierarchy) && methods.contains(&Method::GmmGmr);
    for m in &METRICS {
        let better = match m.better {
            Better::Lower => ", lower is better",
            Better::TowardOne => ", closer to 1 is better",
            Better::Neither => "",
        };
        let _ = writeln!(md, "## {}{better}\n", m.label);
        let pairs = has_pairs && m.better != Better::Neither;
        let columns = methods.iter().map(|&me| format!("{} (n)", method_name(me)));
        let columns = columns.chain(pairs.then(|| "paired wins".into()));
        let mut table = Table::new(
            ["axis", "value"]
                .map(String::from)
                .into_iter()
                .chain(columns),
        );
        for row in rows {
            let cells = methods
                .iter()
                .map(|&me| match stats_of(samples, m.key, me, row) {
                    Some(s) => format!(
                        "{} / {} / {}-{} ({})",
                        fmt(s.median, m.digits),
                        fmt(s.mean, m.digits),
                        fmt(s.q1, m.digits),
                        fmt(s.q3, m.digits),
                        s.n
                    ),
                    None => "n/a".into(),
                });
            let paired = pairs.then(|| {
                wins(samples, m, row)
                    .map_or("n/a".into(), |w| format!("{}-{}-{}", w.hsom, w.gmr, w.ties))
            });
            table.row(
                [row.0.to_string(), row.1.clone()]
                    .into_iter()
                    .chain(cells)
                    .chain(paired),
            );
        }
        let _ = writeln!(md, "{table}");
    }
    md.push_str("## Failed runs\n\n");
    if failed.is_empty() {
        md.push_str("None.\n");
    } else {
        for f in failed {
            let _ = writeln!(md, "- {}", f.replace('\n', " "));
        }
    }
    if !missing.is_empty() {
        let _ = writeln!(
            md,
            "\n## Missing runs\n\n{} runs of the grid have no file yet (a shard not run or \
             not finished):\n",
            missing.len()
        );
        for id in missing {
            let _ = writeln!(md, "- {id}");
        }
    }
    md
}

/// A long CSV: `metric`, `axis`, `value`, then `columns`; for every metric and row, the
/// records `cells` gives.
fn long_csv<C: IntoIterator<Item = Vec<String>>>(
    columns: &[&str],
    rows: &[Row],
    cells: impl Fn(&Metric, &Row) -> C,
) -> Result<Vec<u8>, SweepError> {
    let err = |e: &dyn std::fmt::Display| SweepError::Invalid(format!("CSV: {e}"));
    let mut w = csv::Writer::from_writer(Vec::new());
    let header = ["metric", "axis", "value"].iter().chain(columns);
    w.write_record(header).map_err(|e| err(&e))?;
    for m in &METRICS {
        for row in rows {
            for record in cells(m, row) {
                let key = [m.key, row.0, &row.1].map(str::to_string);
                w.write_record(key.into_iter().chain(record))
                    .map_err(|e| err(&e))?;
            }
        }
    }
    w.into_inner().map_err(|e| err(&e))
}

fn tables_csv(samples: &[Sample], methods: &[Method], rows: &[Row]) -> Result<Vec<u8>, SweepError> {
    let columns = ["method", "n", "median", "mean", "q1", "q3", "iqr"];
    long_csv(&columns, rows, |m, row| {
        let stats = methods
            .iter()
            .filter_map(|&me| Some((me, stats_of(samples, m.key, me, row)?)));
        stats
            .map(|(me, s)| {
                let numbers = [s.median, s.mean, s.q1, s.q3, s.q3 - s.q1].map(|x| x.to_string());
                [method_name(me).to_string(), s.n.to_string()]
                    .into_iter()
                    .chain(numbers)
                    .collect()
            })
            .collect::<Vec<_>>()
    })
}

fn wins_csv(samples: &[Sample], rows: &[Row]) -> Result<Vec<u8>, SweepError> {
    let columns = ["cosco_hsom_wins", "gmr_wins", "ties"];
    long_csv(&columns, rows, |m, row| {
        wins(samples, m, row).map(|w| [w.hsom, w.gmr, w.ties].map(|n| n.to_string()).to_vec())
    })
}

fn timing_md(manifest: &Manifest, runs: &[RunRecord]) -> String {
    let total: f64 = runs.iter().map(|r| r.wall_s).sum();
    let mut md = format!(
        "# Sweep `{}`: times\n\nThese differ between machines, loads and shards; the tables \
         in `{TABLES_MD}` do not.\n\nSum of the {} runs' wall times: {total:.1} s (median per \
         run {:.2} s).\n\n",
        manifest.name,
        runs.len(),
        Stats::of(runs.iter().map(|r| r.wall_s)).map_or(0.0, |s| s.median),
    );
    let mut shards: BTreeMap<&str, (usize, f64)> = BTreeMap::new();
    for r in runs {
        let e = shards.entry(r.shard.as_str()).or_default();
        e.0 += 1;
        e.1 += r.wall_s;
    }
    let mut table = Table::new(["shard", "runs", "sum of wall times (s)"]);
    for (s, (n, t)) in shards {
        table.row([s.to_string(), n.to_string(), format!("{t:.1}")]);
    }
    let _ = writeln!(md, "{table}");
    let mut table = Table::new([
        "method",
        "fits timed",
        "training, median (s)",
        "reproduction, median (ms)",
    ]);
    for method in [Method::Hierarchy, Method::GmmGmr] {
        let of = |key: &str| {
            Stats::of(runs.iter().flat_map(|r| {
                r.methods
                    .iter()
                    .filter(|m| m.method == method)
                    .filter_map(|m| m.timing.get(key).copied())
                    .collect::<Vec<_>>()
            }))
        };
        if let (Some(t), Some(r)) = (of("train_s"), of("reproduce_s")) {
            table.row([
                method_name(method).to_string(),
                t.n.to_string(),
                format!("{:.3}", t.median),
                format!("{:.2}", r.median * 1e3),
            ]);
        }
    }
    md.push_str(&table.to_string());
    md
}

/// One PNG for `metric`: a panel per combination of the axes other than gesture, seed and
/// method; in each, a box per gesture and method over the seeds. `false` when no run has the
/// metric. A panel's title names the axes that vary between panels, or else the evaluation,
/// the configuration and a robot other than the left arm.
fn box_plot(
    path: &Path,
    name: &str,
    metric: &Metric,
    samples: &[Sample],
    methods: &[Method],
) -> Result<bool, SweepError> {
    const PANEL_AXES: [&str; 6] = ["robot", "config", "noise", "count", "height", "evaluation"];
    let with: Vec<&Sample> = samples
        .iter()
        .filter(|s| s.metrics.contains_key(metric.key))
        .collect();
    if with.is_empty() {
        return Ok(false);
    }
    let mut combos: Vec<Vec<String>> = Vec::new();
    let mut gestures: Vec<String> = Vec::new();
    for s in &with {
        let c: Vec<String> = PANEL_AXES.iter().map(|a| s.axes.value(a)).collect();
        if !combos.contains(&c) {
            combos.push(c);
        }
        if !gestures.contains(&s.axes.gesture) {
            gestures.push(s.axes.gesture.clone());
        }
    }
    let varies: Vec<usize> = (0..PANEL_AXES.len())
        .filter(|&i| combos.iter().any(|c| c[i] != combos[0][i]))
        .collect();
    let color = |m: Method| match m {
        Method::GmmGmr => GMR_COLOR,
        Method::ProMP => crate::plot::PALETTE[1],
        Method::Dmp => RGBColor(120, 90, 40),
        Method::Dba => RGBColor(0, 150, 150),
        _ => RGBColor(31, 119, 180),
    };
    let panels: Vec<BoxPanel> = combos
        .iter()
        .map(|c| {
            let title = if varies.is_empty() {
                PANEL_AXES
                    .iter()
                    .zip(c)
                    .filter(|(a, v)| {
                        ["evaluation", "config"].contains(a)
                            || (**a == "robot" && v.as_str() != Robot::LeftArm.name())
                    })
                    .map(|(a, v)| format!("{a} {v}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            } else {
                varies
                    .iter()
                    .map(|&i| format!("{} {}", PANEL_AXES[i], c[i]))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let values = gestures
                .iter()
                .map(|g| {
                    methods
                        .iter()
                        .map(|&m| {
                            with.iter()
                                .filter(|s| {
                                    s.method == m
                                        && &s.axes.gesture == g
                                        && PANEL_AXES
                                            .iter()
                                            .zip(c)
                                            .all(|(a, v)| &s.axes.value(a) == v)
                                })
                                .filter_map(|s| s.metrics.get(metric.key).copied())
                                .collect()
                        })
                        .collect()
                })
                .collect();
            BoxPanel {
                title: format!("{name}: {title}"),
                y_label: metric.label.to_string(),
                categories: gestures.clone(),
                series: methods
                    .iter()
                    .map(|&m| (method_name(m).to_string(), color(m)))
                    .collect(),
                values,
            }
        })
        .collect();
    boxplots_png(
        path,
        &format!("{} by gesture and method", metric.label),
        &panels,
        2,
        (900, 440),
    )?;
    Ok(true)
}

#[cfg(test)]
mod tests;
