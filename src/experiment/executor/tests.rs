use super::*;
use crate::eval::{run_fold, FoldInput};

#[test]
fn the_arm_refuses_to_execute_against_columns_that_are_not_its_joints() {
    let arm = NaoArm::load_default().unwrap();
    let d = Demonstration {
        source: "x.csv".into(),
        columns: vec!["a".into(), "b".into()],
        time: None,
        rows: vec![vec![0.0, 0.0]; 10],
    };
    let demos = [d.clone(), d];
    let executor = ArmExecutor {
        arm: &arm,
        transition: Transition::Linear,
    };
    let runs = run_fold(
        &[Method::Replay],
        &FoldInput::new(&demos, &demos),
        &executor,
    );
    let msg = runs[0].1.as_ref().unwrap_err();
    assert!(
        msg.contains("LShoulderPitch") && msg.contains("\"a\""),
        "{msg}"
    );
}
