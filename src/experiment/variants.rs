//! Before and after: the beyond-the-paper settings switched off one at a time, the paper taken
//! literally and the bottom level alone, each trained, reproduced from the initial posture,
//! executed and scored exactly like the main result, so `report.md` shows what every setting
//! buys.

use crate::config::{parse_config, AlgorithmParams, EventsParams, HsomConfig, HsomParams};
use crate::demos::Demonstration;
use crate::eval::{FoldInput, Method, Training};
use crate::sim::{NaoArm, Transition};

use super::heldout::{hierarchy_held_out, on_arm};
use super::output::{hsom_model, HSOM_NEEDS};
use super::report::MethodResult;
use super::ExperimentError;

/// The shipped `configs/table1.xml` (the paper's Table I), built in.
pub const TABLE1_XML: &str = include_str!("../../configs/table1.xml");
/// Where [`TABLE1_XML`] comes from, for messages and reports.
pub const TABLE1_SOURCE: &str = "configs/table1.xml (built in)";

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

/// The variants of `config` (executed with `transition` unless said otherwise): each of its
/// settings that departs from the paper switched back alone (the events algorithm's
/// `changeRatio` and `actionHorizon` to the paper's 1), and the other transition.
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
    if let AlgorithmParams::Events(e) = &p.algorithm {
        // `p` with its events settings changed by `off`
        let events_off = |off: fn(&mut EventsParams)| {
            let (mut q, mut e) = (p.clone(), e.clone());
            off(&mut e);
            q.algorithm = AlgorithmParams::Events(e);
            q
        };
        if e.change_ratio < 1.0 {
            // events start on any change of the bottom BMU (no hysteresis)
            let q = events_off(|e| e.change_ratio = 1.0);
            push("changeRatio 1 (no event hysteresis)", q, transition)?;
        }
        if e.action_horizon > 1 {
            // the bottom learns the next state, the paper's action
            let q = events_off(|e| e.action_horizon = 1);
            push("actionHorizon 1 (the next state)", q, transition)?;
        }
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

/// Reference rows of the before/after table, each executed with `transition`: the paper
/// literal (`configs/table1.xml`) and `config` at height 1 (the bottom level alone: `levels`
/// truncated to the first, `height = 1`).
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
        named("this configuration at height 1", config.at_height(1))?,
    ])
}

/// Run one variant on `demos`: learned from all and scored against all (the in-sample
/// column) and, with `heldout` and at least 2 demonstrations, leave-one-out (the held-out
/// means).
pub fn run_variant<const N: usize>(
    arm: &NaoArm<N>,
    variant: &Variant,
    demos: &[Demonstration],
    heldout: bool,
) -> Result<MethodResult, ExperimentError> {
    let input = FoldInput {
        config: Some(&variant.config),
        ..FoldInput::new(demos, demos)
    };
    let run = on_arm(arm, variant.transition, Method::Hierarchy, &input)?;
    let bytes = hsom_model(&run)?.0.to_bytes().len() as u64;
    let mut result = MethodResult::of(&variant.name, HSOM_NEEDS, &run, bytes, Vec::new());
    if heldout && demos.len() >= 2 {
        result.heldout = Some(hierarchy_held_out(
            arm,
            &variant.config,
            demos,
            Training::Trained,
            variant.transition,
        )?);
    }
    Ok(result)
}
