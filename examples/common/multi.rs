//! Several gestures in one hierarchy on the simulated arm, held out: per seed,
//! every gesture is recorded `train + test` times; one hierarchy learns the first `train` of
//! each, and is measured on the others against each gesture learned alone (fidelity of the
//! executed reproduction) and against a 1-nearest-neighbour DTW classifier (recognition,
//! early recognition, time per query); with the unknown study, a hierarchy taught all
//! gestures but one is shown the one left out.

use std::time::Instant;

use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use cosco_hsom::config::HsomConfig;
use cosco_hsom::demos::Demonstration;
use cosco_hsom::dtw::Band;
use cosco_hsom::gesture::Gesture;
use cosco_hsom::hsom::{GestureModel, Scoring};
use cosco_hsom::metrics::MetricsParams;
use cosco_hsom::nearest::NearestNeighbour;
use cosco_hsom::sim::NaoArm;
use cosco_hsom::stats::median;
use cosco_hsom::table::Table;

use cosco_hsom::demos::sample_period;
use cosco_hsom::experiment::all_gestures::{confusion_counts, confusion_markdown};
use cosco_hsom::experiment::demonstrate::{synthetic_demonstrations, DemoSettings};
use cosco_hsom::experiment::{execute_and_score, ExperimentError, Transition};

/// What the study does.
#[derive(Debug, Clone)]
pub struct MultiSettings {
    /// Demonstrations per gesture to learn from.
    pub train: usize,
    /// Held-out demonstrations per gesture.
    pub test: usize,
    /// Encoder noise of the recordings, rad.
    pub noise: f64,
    /// How postures become servo targets.
    pub transition: Transition,
    /// Also reproduce, execute and score every held-out demonstration, shared and alone.
    pub fidelity: bool,
    /// Also the unknown study (one hierarchy per gesture left out).
    pub unknown: bool,
    /// Also the negative controls (untrained hierarchy, shuffled labels).
    pub controls: bool,
}

/// One held-out demonstration recognised.
#[derive(Debug, Clone, Serialize)]
pub struct Query {
    /// Its gesture.
    pub expected: String,
    /// The hierarchy's answer (`None`: unknown).
    pub hsom: Option<String>,
    /// The hierarchy's lowest-score label.
    pub hsom_best: String,
    /// Fraction of the gesture seen before the hierarchy's decision was final.
    pub hsom_early: f64,
    /// Seconds per recognition (whole sequence, no early answer).
    pub hsom_s: f64,
    /// The lowest-score label with level 1's distance alone ([`Scoring::Level1`]).
    pub level1_best: String,
    /// The lowest-score label with the bottom's postures alone ([`Scoring::Postures`]).
    pub postures_best: String,
    /// The lowest-score label with held-out-relative scores ([`Scoring::Relative`]).
    pub relative_best: String,
    /// 1-NN DTW's answer.
    pub nn: String,
    /// Fraction of the gesture seen before 1-NN DTW's decision was final.
    pub nn_early: f64,
    /// Seconds per 1-NN DTW query (whole sequence).
    pub nn_s: f64,
}

/// Fidelity of one held-out demonstration's reproduction, shared and alone.
#[derive(Debug, Clone, Serialize)]
pub struct FidelityPair {
    /// The gesture.
    pub gesture: String,
    /// Joint DTW (rad/step) of the shared hierarchy's executed reproduction.
    pub shared: f64,
    /// The same for the gesture learned alone.
    pub alone: f64,
    /// Wrist-path DTW (mm/step), shared (NaN when the arm gives no wrist path).
    pub shared_wrist_mm: f64,
    /// Wrist-path DTW (mm/step), alone.
    pub alone_wrist_mm: f64,
    /// Velocity reversals of the shared hierarchy's executed reproduction, all joints.
    pub shared_reversals: f64,
    /// Velocity reversals of the gesture learned alone, all joints.
    pub alone_reversals: f64,
    /// Velocity reversals of the held-out demonstration, all joints.
    pub demo_reversals: f64,
}

/// A control or the unknown study: answers as (expected, answer) pairs.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Answers {
    /// `(expected, answer)`; answer `None` is unknown.
    pub pairs: Vec<(String, Option<String>)>,
}

impl Answers {
    /// Fraction answered with the expected label.
    pub fn accuracy(&self) -> f64 {
        frac(
            self.pairs
                .iter()
                .filter(|(e, a)| a.as_deref() == Some(e.as_str())),
            self.pairs.len(),
        )
    }
}

fn frac<I: Iterator>(it: I, n: usize) -> f64 {
    it.count() as f64 / n.max(1) as f64
}

/// Everything measured on one seed.
#[derive(Debug, Clone, Serialize)]
pub struct SeedResult {
    /// The seed of the recordings.
    pub seed: u64,
    /// Held-out recognition.
    pub queries: Vec<Query>,
    /// Held-out fidelity (empty without `fidelity`).
    pub fidelity: Vec<FidelityPair>,
    /// Unknown study: the left-out gesture's demonstrations (expected `unknown`).
    pub unknown_left_out: Answers,
    /// Unknown study: the taught gestures' held-out demonstrations.
    pub unknown_known: Answers,
    /// Control: an untrained hierarchy (seeded initial weights, calibrated the same way).
    pub untrained: Answers,
    /// Control: labels shuffled among the training demonstrations.
    pub shuffled: Answers,
    /// Size of the multi-gesture model file, bytes.
    pub model_bytes: usize,
    /// Training time of the multi-gesture model, seconds.
    pub train_s: f64,
}

/// A gesture's demonstrations: (label, to learn from, held out).
pub type GestureSplit = (String, Vec<Demonstration>, Vec<Demonstration>);

/// Record the demonstrations of every gesture for `seed`: (label, training, held out).
pub fn record_sets(
    arm: &NaoArm,
    gestures: &[Gesture],
    seed: u64,
    settings: &MultiSettings,
) -> Result<Vec<GestureSplit>, ExperimentError> {
    let demo_settings = DemoSettings {
        encoder_noise: settings.noise,
        ..DemoSettings::default()
    };
    gestures
        .iter()
        .map(|g| {
            let mut d = synthetic_demonstrations(
                arm,
                g,
                settings.train + settings.test,
                seed,
                &demo_settings,
                |_| {},
            )?;
            let test = d.split_off(settings.train);
            Ok((g.name.to_string(), d, test))
        })
        .collect()
}

fn answers(
    model: &GestureModel,
    tests: &[(String, &Demonstration)],
) -> Result<Answers, ExperimentError> {
    let mut a = Answers::default();
    for (label, d) in tests {
        let r = model
            .recognize(&d.rows)
            .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
        a.pairs.push((label.clone(), r.label));
    }
    Ok(a)
}

fn gerr(e: cosco_hsom::hsom::GestureError) -> ExperimentError {
    ExperimentError::Invalid(e.to_string())
}

/// The study on one seed.
pub fn run_seed(
    arm: &NaoArm,
    config: &HsomConfig,
    gestures: &[Gesture],
    seed: u64,
    settings: &MultiSettings,
) -> Result<SeedResult, ExperimentError> {
    let rec = record_sets(arm, gestures, seed, settings)?;
    let sets: Vec<(String, Vec<Demonstration>)> =
        rec.iter().map(|(l, t, _)| (l.clone(), t.clone())).collect();
    let tests: Vec<(String, &Demonstration)> = rec
        .iter()
        .flat_map(|(l, _, t)| t.iter().map(move |d| (l.clone(), d)))
        .collect();
    let t0 = Instant::now();
    let model = config
        .fit_model(&sets, cosco_hsom::hsom::Fit::default())
        .map_err(gerr)?;
    let train_s = t0.elapsed().as_secs_f64();
    let model_bytes = model.to_bytes().len();
    let nn = NearestNeighbour::new(
        sets.iter()
            .flat_map(|(l, ds)| ds.iter().map(move |d| (l.clone(), d.rows.clone())))
            .collect(),
        Band::None,
    );
    let mut queries = Vec::new();
    for (label, d) in &tests {
        let t = Instant::now();
        model.scores(&d.rows).map_err(gerr)?;
        let hsom_s = t.elapsed().as_secs_f64();
        let r = model.recognize(&d.rows).map_err(gerr)?;
        let t = Instant::now();
        nn.classify(&d.rows)
            .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
        let nn_s = t.elapsed().as_secs_f64();
        let alt = |sc: Scoring| -> Result<String, ExperimentError> {
            let m = model.clone().with_scoring(sc);
            Ok(m.recognize(&d.rows).map_err(gerr)?.best)
        };
        let level1_best = alt(Scoring::Level1)?;
        let relative_best = alt(Scoring::Relative)?;
        let postures_best = alt(Scoring::Postures)?;
        let a = nn
            .classify_early(&d.rows)
            .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
        queries.push(Query {
            expected: label.clone(),
            hsom: r.label.clone(),
            hsom_best: r.best.clone(),
            hsom_early: r.decided_fraction(),
            hsom_s,
            level1_best,
            relative_best,
            postures_best,
            nn: a.label,
            nn_early: a.decided_at as f64 / d.rows.len() as f64,
            nn_s,
        });
    }
    let mut fidelity = Vec::new();
    if settings.fidelity {
        for (label, train, test) in &rec {
            let alone = config.fit(train)?;
            for d in test {
                let metrics = MetricsParams {
                    sample_period: sample_period(d),
                    ..MetricsParams::default()
                };
                let score = |postures: &[Vec<f64>]| -> Result<[f64; 4], ExperimentError> {
                    let e = execute_and_score(
                        arm,
                        postures,
                        settings.transition,
                        std::slice::from_ref(d),
                        &metrics,
                    )?
                    .fidelity;
                    Ok([
                        e.joint_dtw_rad_per_step.mean,
                        e.wrist_dtw_mm.map_or(f64::NAN, |w| w.mean),
                        e.reproduction_smoothness.total_reversals as f64,
                        e.demo_smoothness
                            .first()
                            .map_or(f64::NAN, |d| d.total_reversals as f64),
                    ])
                };
                let shared = model
                    .branch(Some(label))
                    .and_then(|b| Ok(b.reproduce(&d.rows[0])?))
                    .map_err(gerr)?;
                let own = alone.reproduce(&d.rows[0])?;
                let (sh, al) = (score(&shared.postures)?, score(&own.postures)?);
                fidelity.push(FidelityPair {
                    gesture: label.clone(),
                    shared: sh[0],
                    alone: al[0],
                    shared_wrist_mm: sh[1],
                    alone_wrist_mm: al[1],
                    shared_reversals: sh[2],
                    alone_reversals: al[2],
                    demo_reversals: sh[3],
                });
            }
        }
    }
    let (mut unknown_left_out, mut unknown_known) = (Answers::default(), Answers::default());
    if settings.unknown && sets.len() >= 3 {
        for u in 0..sets.len() {
            let taught: Vec<_> = sets
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != u)
                .map(|(_, s)| s.clone())
                .collect();
            let m = config
                .fit_model(&taught, cosco_hsom::hsom::Fit::default())
                .map_err(gerr)?;
            for (label, d) in &tests {
                let r = m.recognize(&d.rows).map_err(gerr)?;
                if *label == sets[u].0 {
                    unknown_left_out.pairs.push(("unknown".into(), r.label));
                } else {
                    unknown_known.pairs.push((label.clone(), r.label));
                }
            }
        }
        // "unknown" answered for the left-out gesture counts as right
        for p in &mut unknown_left_out.pairs {
            if p.1.is_none() {
                p.1 = Some("unknown".into());
            }
        }
    }
    let (mut untrained, mut shuffled) = (Answers::default(), Answers::default());
    if settings.controls {
        let m = config
            .fit_model(&sets, cosco_hsom::hsom::Fit::UNTRAINED)
            .map_err(gerr)?;
        untrained = answers(&m, &tests)?;
        let mut all: Vec<Demonstration> = sets.iter().flat_map(|(_, d)| d.clone()).collect();
        all.shuffle(&mut ChaCha8Rng::seed_from_u64(seed ^ 0x5eed));
        let per = settings.train;
        let mixed: Vec<(String, Vec<Demonstration>)> = sets
            .iter()
            .enumerate()
            .map(|(i, (l, _))| (l.clone(), all[i * per..(i + 1) * per].to_vec()))
            .collect();
        let m = config
            .fit_model(&mixed, cosco_hsom::hsom::Fit::default())
            .map_err(gerr)?;
        shuffled = answers(&m, &tests)?;
    }
    Ok(SeedResult {
        seed,
        queries,
        fidelity,
        unknown_left_out,
        unknown_known,
        untrained,
        shuffled,
        model_bytes,
        train_s,
    })
}

/// Markdown tables of the results over seeds.
pub fn to_markdown(results: &[SeedResult], labels: &[String]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let q: Vec<&Query> = results.iter().flat_map(|r| &r.queries).collect();
    let n = q.len();
    let hsom_acc = frac(
        q.iter().filter(|x| x.hsom.as_deref() == Some(&x.expected)),
        n,
    );
    let best_acc = frac(q.iter().filter(|x| x.hsom_best == x.expected), n);
    let nn_acc = frac(q.iter().filter(|x| x.nn == x.expected), n);
    let med = |f: &dyn Fn(&Query) -> f64| median(q.iter().map(|x| f(x))).unwrap_or(f64::NAN);
    let _ = writeln!(s, "### Recognition, held out ({n} queries)\n");
    let mut table = Table::new([
        "method",
        "accuracy",
        "lowest score right (no unknown)",
        "median early fraction",
        "median time per query",
    ]);
    table.row([
        "CoSCo-HSOM (one hierarchy)".to_string(),
        format!("{:.1} %", 100.0 * hsom_acc),
        format!("{:.1} %", 100.0 * best_acc),
        format!("{:.2}", med(&|x| x.hsom_early)),
        format!("{:.3} ms", 1e3 * med(&|x| x.hsom_s)),
    ]);
    table.row([
        "1-NN DTW".to_string(),
        format!("{:.1} %", 100.0 * nn_acc),
        format!("{:.1} %", 100.0 * nn_acc),
        format!("{:.2}", med(&|x| x.nn_early)),
        format!("{:.3} ms", 1e3 * med(&|x| x.nn_s)),
    ]);
    let _ = writeln!(s, "{table}");
    let _ = writeln!(
        s,
        "Alternative scorings (lowest score right): level 1 alone {:.1} %, relative to the held-out reference {:.1} %, the bottom's postures alone {:.1} %\n",
        100.0 * frac(q.iter().filter(|x| x.level1_best == x.expected), n),
        100.0 * frac(q.iter().filter(|x| x.relative_best == x.expected), n),
        100.0 * frac(q.iter().filter(|x| x.postures_best == x.expected), n)
    );
    let _ = writeln!(
        s,
        "Confusion (rows: gesture, columns: CoSCo-HSOM's answer):\n"
    );
    let _ = write!(
        s,
        "{}",
        confusion_markdown(&confusion(&q, labels), labels, true)
    );
    let fid: Vec<&FidelityPair> = results.iter().flat_map(|r| &r.fidelity).collect();
    if !fid.is_empty() {
        let _ = writeln!(
            s,
            "\n### Fidelity held out, joint DTW rad/step (median over held-out demonstrations)\n"
        );
        let mut table = Table::new(["gesture", "shared hierarchy", "learned alone", "ratio"]);
        for l in labels {
            let sh = median(fid.iter().filter(|f| &f.gesture == l).map(|f| f.shared));
            let al = median(fid.iter().filter(|f| &f.gesture == l).map(|f| f.alone));
            if let (Some(a), Some(b)) = (sh, al) {
                table.row([
                    l.clone(),
                    format!("{a:.4}"),
                    format!("{b:.4}"),
                    format!("{:.2}", a / b),
                ]);
            }
        }
        s += &table.to_string();
        let _ = writeln!(
            s,
            "\nWrist-path DTW (mm/step) and velocity reversals (all joints), medians:\n"
        );
        let mut table = Table::new([
            "gesture",
            "wrist shared",
            "wrist alone",
            "ratio",
            "reversals shared",
            "alone",
            "demonstrations",
        ]);
        for l in labels {
            let of = |f: &dyn Fn(&FidelityPair) -> f64| {
                median(
                    fid.iter()
                        .filter(|p| &p.gesture == l)
                        .map(|p| f(p))
                        .filter(|v| v.is_finite()),
                )
                .unwrap_or(f64::NAN)
            };
            let (ws, wa) = (of(&|p| p.shared_wrist_mm), of(&|p| p.alone_wrist_mm));
            table.row([
                l.clone(),
                format!("{ws:.2}"),
                format!("{wa:.2}"),
                format!("{:.2}", ws / wa),
                format!("{:.1}", of(&|p| p.shared_reversals)),
                format!("{:.1}", of(&|p| p.alone_reversals)),
                format!("{:.1}", of(&|p| p.demo_reversals)),
            ]);
        }
        s += &table.to_string();
    }
    let cat = |f: &dyn Fn(&SeedResult) -> &Answers| Answers {
        pairs: results.iter().flat_map(|r| f(r).pairs.clone()).collect(),
    };
    let lo = cat(&|r| &r.unknown_left_out);
    if !lo.pairs.is_empty() {
        let kn = cat(&|r| &r.unknown_known);
        let _ = writeln!(s, "\n### Unknown: taught three, shown the fourth\n");
        let mut table = Table::new(["", "answered right", "cases"]);
        table.row([
            "left-out gesture: `unknown`".to_string(),
            format!("{:.1} %", 100.0 * lo.accuracy()),
            lo.pairs.len().to_string(),
        ]);
        table.row([
            "taught gestures: their label".to_string(),
            format!("{:.1} %", 100.0 * kn.accuracy()),
            kn.pairs.len().to_string(),
        ]);
        s += &table.to_string();
    }
    let un = cat(&|r| &r.untrained);
    if !un.pairs.is_empty() {
        let sh = cat(&|r| &r.shuffled);
        let _ = writeln!(
            s,
            "\n### Negative controls (held-out accuracy, must fail the 95 % gate)\n"
        );
        let chance = 100.0 / labels.len().max(1) as f64;
        let mut table = Table::new(["control", "accuracy", "chance"]);
        table.row([
            "untrained hierarchy".to_string(),
            format!("{:.1} %", 100.0 * un.accuracy()),
            format!("{chance:.1} %"),
        ]);
        table.row([
            "shuffled labels".to_string(),
            format!("{:.1} %", 100.0 * sh.accuracy()),
            format!("{chance:.1} %"),
        ]);
        s += &table.to_string();
    }
    let bytes: Vec<usize> = results.iter().map(|r| r.model_bytes).collect();
    let _ = writeln!(
        s,
        "\nModel file: {} bytes; training {:.2} s (median)",
        bytes.first().copied().unwrap_or(0),
        median(results.iter().map(|r| r.train_s)).unwrap_or(f64::NAN)
    );
    s
}

/// Confusion counts: rows = expected label, columns = the labels then `unknown`.
pub fn confusion(q: &[&Query], labels: &[String]) -> Vec<Vec<usize>> {
    confusion_counts(labels, q.iter().map(|x| (&x.expected, x.hsom.as_ref())))
}
