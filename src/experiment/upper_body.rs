//! The upper body's held-out reproductions executed on its simulated model
//! (`models/nao_upper_body.xml`, which has collision shapes): every held-out fold's hierarchy
//! reproduction followed by the position servos from its first posture, and the contacts
//! between two parts of the robot it made (`cosco heldout` on the upper body's joints).

use serde::Serialize;

use crate::demos::sample_period;
use crate::eval::{GestureLoo, Method, Section};
use crate::robot::Robot;
use crate::sim::{Controller, ControllerConfig, NaoArm, TargetTrajectory, Touch};
use crate::table::Table;

/// One held-out fold's hierarchy reproduction as executed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FoldContacts {
    /// The gesture.
    pub gesture: String,
    /// The held-out demonstration (its file).
    pub demonstration: String,
    /// The contacts between two parts of the robot during the execution, the gesture's own
    /// (every one of its demonstrations makes them, [`crate::sim::own_contacts`]) left out.
    pub touches: Vec<Touch>,
    /// The gesture's own contacts the execution made.
    pub own: Vec<Touch>,
    /// Why it was not executed (no reproduction, or the simulator refused it).
    pub error: Option<String>,
}

/// Execute `postures` (upper-body postures, one every `period` seconds) on `arm` from the first
/// posture (values clamped into the joint ranges) and return the contacts.
pub fn execute_contacts(
    arm: &NaoArm<14>,
    postures: &[Vec<f64>],
    period: f64,
) -> Result<Vec<Touch>, crate::sim::SimError> {
    let ranges = Robot::UpperBody.ranges();
    let clamped: Vec<Vec<f64>> = (postures.iter())
        .map(|p| {
            p.iter()
                .zip(&ranges)
                .map(|(v, (lo, hi))| v.clamp(*lo, *hi))
                .collect()
        })
        .collect();
    let times: Vec<f64> = (0..clamped.len()).map(|k| k as f64 * period).collect();
    let trajectory = TargetTrajectory::<14>::new_for(Robot::UpperBody, &times, &clamped)?;
    let mut sim = arm.sim()?;
    if let Some(first) = clamped.first() {
        sim.set_posture(first)?;
    }
    let rec = Controller::new(ControllerConfig::default())?.follow(&mut sim, &trajectory)?;
    Ok(rec.contacts)
}

/// Every held-out fold's hierarchy reproduction of `study` executed on the upper body's shipped
/// model, `threads` at a time; empty unless the demonstrations are the upper body's joints.
pub fn hierarchy_contacts(
    study: &[GestureLoo],
    threads: usize,
) -> Result<Vec<FoldContacts>, String> {
    let upper = |g: &GestureLoo| {
        (g.demonstrations.first())
            .is_some_and(|d| Robot::of_columns(&d.columns) == Some(Robot::UpperBody))
    };
    if !study.iter().any(upper) {
        return Ok(Vec::new());
    }
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).map_err(|e| e.to_string())?;
    let jobs: Vec<(&GestureLoo, usize)> = (study.iter().filter(|g| upper(g)))
        .flat_map(|g| (0..g.held_out.len()).map(move |i| (g, i)))
        .collect();
    let pool = crate::eval::Pool::new(threads.max(1))?;
    let gestures: Vec<&GestureLoo> = study.iter().filter(|g| upper(g)).collect();
    let demos: Vec<(usize, usize)> = (gestures.iter().enumerate())
        .flat_map(|(k, g)| (0..g.demonstrations.len()).map(move |i| (k, i)))
        .collect();
    let demo_contacts = pool.map(
        &demos,
        |&(k, i)| {
            let d = &gestures[k].demonstrations[i];
            execute_contacts(&arm, &d.rows, sample_period(d)).unwrap_or_default()
        },
        None,
    );
    let own: Vec<(String, Vec<[String; 2]>)> = (gestures.iter().enumerate())
        .map(|(k, g)| {
            let of: Vec<Vec<Touch>> = (demos.iter().zip(&demo_contacts))
                .filter(|((kk, _), _)| *kk == k)
                .map(|(_, c)| c.clone())
                .collect();
            (g.gesture.clone(), crate::sim::own_contacts(&of))
        })
        .collect();
    Ok(pool.map(
        &jobs,
        |&(g, i)| {
            let fold = &g.held_out[i];
            let period = g.demonstrations.get(i).map_or(0.025, sample_period);
            let executed = match fold.run(Method::Hierarchy) {
                Some(r) if !r.postures.is_empty() => {
                    execute_contacts(&arm, &r.postures, period).map_err(|e| e.to_string())
                }
                _ => Err("no hierarchy reproduction".to_string()),
            };
            let (touches, error) = match executed {
                Ok(t) => (t, None),
                Err(e) => (Vec::new(), Some(e)),
            };
            let mine = (own.iter().find(|(name, _)| *name == g.gesture)).map_or(&[][..], |o| &o.1);
            let (own, touches) = touches.into_iter().partition(|t| mine.contains(&t.limbs()));
            FoldContacts {
                gesture: g.gesture.clone(),
                demonstration: fold.demonstration.clone(),
                touches,
                own,
                error,
            }
        },
        None,
    ))
}

/// The section `cosco heldout` appends on the upper body: per gesture, the held-out folds whose
/// hierarchy reproduction, executed, made a contact; `None` for any other data.
pub fn contacts_section(study: &[GestureLoo], threads: usize) -> Result<Option<Section>, String> {
    let folds = hierarchy_contacts(study, threads)?;
    if folds.is_empty() {
        return Ok(None);
    }
    let mut gestures: Vec<&str> = Vec::new();
    for f in &folds {
        if !gestures.contains(&f.gesture.as_str()) {
            gestures.push(&f.gesture);
        }
    }
    let mut table = Table::new([
        "gesture",
        "folds executed",
        "with the gesture's own contact",
        "with another contact",
        "other contacts",
    ]);
    for g in &gestures {
        let of: Vec<&FoldContacts> = folds.iter().filter(|f| f.gesture == *g).collect();
        let executed = of.iter().filter(|f| f.error.is_none()).count();
        let touched = of.iter().filter(|f| !f.touches.is_empty()).count();
        let own = of.iter().filter(|f| !f.own.is_empty()).count();
        let count: usize = of.iter().map(|f| f.touches.len()).sum();
        table.row([
            g.to_string(),
            format!("{executed} of {}", of.len()),
            own.to_string(),
            touched.to_string(),
            count.to_string(),
        ]);
    }
    let executed = folds.iter().filter(|f| f.error.is_none()).count();
    let touched = folds.iter().filter(|f| !f.touches.is_empty()).count();
    let mut markdown = format!(
        "\n## Contacts on the simulated upper body\n\nEvery held-out fold's hierarchy \
         reproduction executed on the upper body's model (models/nao_upper_body.xml: the \
         position servos follow its postures at the demonstrations' rate from its first \
         posture): {touched} of {executed} executed folds made a contact between two parts of \
         the robot other than the gesture's own ({} folds). A gesture's own contact is one \
         that every one of its demonstrations, executed the same way, makes (a pair of limbs: \
         a hand's palm and fingers are one): the clap's hands.\n\n{table}",
        folds.len()
    );
    for f in folds
        .iter()
        .filter(|f| !f.touches.is_empty() || f.error.is_some())
    {
        let what = match &f.error {
            Some(e) => format!("not executed: {e}"),
            None => (f.touches.iter().map(Touch::describe))
                .collect::<Vec<_>>()
                .join("; "),
        };
        markdown.push_str(&format!("\n- {} ({}): {what}", f.gesture, f.demonstration));
    }
    if folds
        .iter()
        .any(|f| !f.touches.is_empty() || f.error.is_some())
    {
        markdown.push('\n');
    }
    Ok(Some(Section {
        key: "contacts",
        markdown,
        json: serde_json::json!({
            "executed": executed,
            "with_contact": touched,
            "with_own_contact": folds.iter().filter(|f| !f.own.is_empty()).count(),
            "folds": folds,
        }),
    }))
}
