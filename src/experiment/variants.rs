//! Before and after: the beyond-the-paper options switched off one at a time, and all at once
//! (the paper taken literally), each trained, reproduced from the initial posture, executed and
//! scored exactly like the main result, so `report.md` shows what every option buys.

use crate::config::{
    parse_config, Algorithm, Alignment, HsomConfig, HsomParams, Knots, ListUpdate, Plan, Reflex,
    ReproductionMode, Timing,
};
use crate::demos::Demonstration;
use crate::sim::NaoArm;

use super::heldout::{hsom_folds, HeldOutSummary};
use super::pipeline::{learn_and_reproduce, Training};
use super::report::MethodResult;
use super::{ExperimentError, Transition};

/// The shipped `configs/table1.xml` (the paper's Table I), built in.
pub const TABLE1_XML: &str = include_str!("../../configs/table1.xml");
/// Where [`TABLE1_XML`] comes from, for messages and reports.
pub const TABLE1_SOURCE: &str = "configs/table1.xml (built in)";
/// `tests/configs/successor-table.xml` (the successor-table settings), built in.
pub const SUCCESSOR_TABLE_XML: &str = include_str!("../../tests/configs/successor-table.xml");
/// Where [`SUCCESSOR_TABLE_XML`] comes from.
pub const SUCCESSOR_TABLE_SOURCE: &str = "tests/configs/successor-table.xml (built in)";

/// One variant to run: a name, the configuration and the transition.
#[derive(Debug, Clone)]
pub struct Variant {
    /// What differs from the main result.
    pub name: String,
    /// The configuration (trained anew).
    pub config: HsomConfig,
    /// How its postures are executed.
    pub transition: Transition,
}

/// The paper taken literally: activity lists updated every step, the bottom reflex, one
/// posture per node, action = next sample, no level skipped for low accuracy, the literal
/// (full depth-first) expansion, the node's action half as output, no end tolerance.
pub fn paper_literal(p: &HsomParams) -> HsomParams {
    let mut q = p.clone();
    q.algorithm = Algorithm::Paper;
    q.list_update = ListUpdate::EveryStep;
    q.change_ratio = 1.0;
    q.action_horizon = 1;
    q.reproduction.mode = ReproductionMode::Literal;
    q.reproduction.reflex = Reflex::Bmu;
    q.reproduction.timing = Timing::Step;
    q.reproduction.min_accuracy = 0.0;
    q.reproduction.continuity = 0.0;
    q.reproduction.closed_loop = false;
    q.reproduction.end_tolerance = 0.0;
    q.reproduction.loop_visits = 0;
    q.reproduction.revisit_successors = false;
    q
}

/// The variants of `config` (executed with `transition` unless said otherwise): the paper
/// literal, each option of the configuration that departs from the paper switched back alone,
/// and the other transition.
pub fn variants(
    config: &HsomConfig,
    transition: Transition,
) -> Result<Vec<Variant>, ExperimentError> {
    let p = config.params();
    let src = |what: &str| format!("{} ({what})", config.source());
    let mut out = Vec::new();
    let mut push =
        |name: &str, params: HsomParams, transition: Transition| -> Result<(), ExperimentError> {
            let config = params
                .check(&src(name))
                .map_err(|e| ExperimentError::Invalid(format!("variant '{name}': {e}")))?;
            out.push(Variant {
                name: name.to_string(),
                config,
                transition,
            });
            Ok(())
        };
    let literal = paper_literal(p);
    if &literal != p {
        push(
            "paper literal (every option off)",
            literal,
            Transition::Linear,
        )?;
    }
    if p.algorithm == Algorithm::Events && p.change_ratio < 1.0 {
        // events start on any change of the bottom BMU (no hysteresis)
        let mut q = p.clone();
        q.change_ratio = 1.0;
        push("without changeRatio hysteresis", q, transition)?;
    }
    if p.algorithm == Algorithm::Events && p.plan == Plan::Traced {
        // plans decoded slot by slot, one knot per event, the consensus read along the
        // stepped warp: the recommended configuration until the nineteenth session
        // (tests/configs/decoded-plan.xml)
        let mut q = p.clone();
        q.plan = Plan::Decoded;
        q.knots = Knots::Event;
        q.alignment = Alignment::Stepped;
        push("with decoded plans (the former default)", q, transition)?;
    }
    if p.list_update == ListUpdate::OnChange {
        let mut q = p.clone();
        q.list_update = ListUpdate::EveryStep;
        q.change_ratio = 1.0;
        push("without listUpdate=onChange", q, transition)?;
    }
    if p.action_horizon > 1 {
        let mut q = p.clone();
        q.action_horizon = 1;
        push("without actionHorizon", q, transition)?;
    }
    if p.reproduction.reflex != Reflex::Bmu {
        let mut q = p.clone();
        q.reproduction.reflex = Reflex::Bmu;
        push("without reflex=successor", q, transition)?;
    }
    if p.reproduction.timing != Timing::Step {
        let mut q = p.clone();
        q.reproduction.timing = Timing::Step;
        push("without learned timing", q, transition)?;
    }
    if p.reproduction.min_accuracy > 0.0 {
        let mut q = p.clone();
        q.reproduction.min_accuracy = 0.0;
        push("without minAccuracy", q, transition)?;
    }
    if p.reproduction.end_tolerance > 0.0 {
        let mut q = p.clone();
        q.reproduction.end_tolerance = 0.0;
        push("without endTolerance", q, transition)?;
    }
    if p.reproduction.loop_visits > 0 {
        let mut q = p.clone();
        q.reproduction.loop_visits = 0;
        push("without the loop breaker", q, transition)?;
    }
    if p.reproduction.revisit_successors {
        let mut q = p.clone();
        q.reproduction.revisit_successors = false;
        push("without revisitSuccessors", q, transition)?;
    }
    let other = match transition {
        Transition::Linear => Transition::MinimumJerk { tolerance: 0.02 },
        Transition::MinimumJerk { .. } => Transition::Linear,
    };
    push(
        &format!("with --transition {}", other.name()),
        p.clone(),
        other,
    )?;
    Ok(out)
}

/// `config` with its bottom level alone (`levels` truncated to the first, `height = 1`, no
/// `maxLevel`): the baseline the hierarchy must beat.
pub fn at_height_1(config: &HsomConfig) -> Result<HsomConfig, crate::config::ConfigError> {
    at_height(config, 1)
}

/// `config` with its lowest `height` levels (`levels` truncated, a `maxLevel` at or above
/// the new top level dropped: the top is the limit anyway). A height above the
/// configuration's own, or 0, is an error naming both: levels cannot be made up.
pub fn at_height(
    config: &HsomConfig,
    height: usize,
) -> Result<HsomConfig, crate::config::ConfigError> {
    config.at_height(height)
}

/// Reference rows of the before/after table, each executed with `transition`: the paper
/// literal (`configs/table1.xml`), the successor-table settings
/// (`tests/configs/successor-table.xml`), and `config` at height 1 (the bottom level alone:
/// `levels` truncated to the first, `height = 1`, no `maxLevel`).
pub fn reference_variants(
    config: &HsomConfig,
    transition: Transition,
) -> Result<Vec<Variant>, ExperimentError> {
    let named = |name: &str, config: Result<HsomConfig, crate::config::ConfigError>| {
        config
            .map(|config| Variant {
                name: name.to_string(),
                config,
                transition,
            })
            .map_err(|e| ExperimentError::Invalid(format!("variant '{name}': {e}")))
    };
    Ok(vec![
        named(
            "paper literal (configs/table1.xml)",
            parse_config(TABLE1_XML, TABLE1_SOURCE),
        )?,
        named(
            "successor-table settings (tests/configs/successor-table.xml)",
            parse_config(SUCCESSOR_TABLE_XML, SUCCESSOR_TABLE_SOURCE),
        )?,
        named("this configuration at height 1", at_height_1(config))?,
    ])
}

/// Run one variant on `demos`: learned from all and scored against all (the in-sample
/// column) and, with `heldout` and at least 2 demonstrations, leave-one-out (the held-out
/// means).
pub fn run_variant(
    arm: &NaoArm,
    variant: &Variant,
    demos: &[Demonstration],
    heldout: bool,
) -> Result<MethodResult, ExperimentError> {
    let run = learn_and_reproduce(
        arm,
        &variant.config,
        demos,
        Training::Trained,
        variant.transition,
        None,
    )?;
    let mut result =
        run.method_result(&variant.name, run.model.to_bytes().len() as u64, Vec::new());
    if heldout && demos.len() >= 2 {
        let folds = hsom_folds(
            arm,
            &variant.config,
            demos,
            Training::Trained,
            variant.transition,
        )?;
        result.heldout = HeldOutSummary::of(&folds.iter().collect::<Vec<_>>());
    }
    Ok(result)
}
