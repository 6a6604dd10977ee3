use super::kinematic::run;
use super::*;
use crate::condition::{Conditions, ViaPoint};

fn cols(n: usize) -> Vec<String> {
    plain_columns(n)
}

/// A 2-D plan of `n` rows: a half circle from (1, 0) to (-1, 0).
fn arc(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            let a = std::f64::consts::PI * i as f64 / (n - 1) as f64;
            vec![a.cos(), a.sin()]
        })
        .collect()
}

/// A closed-loop stepper over a fixed plan that re-joins it by alignment.
struct Realigning(Course);

impl Stepper for Realigning {
    fn width(&self) -> usize {
        2
    }
    fn step(&mut self, observed: &[f64]) -> Result<Vec<f64>, StepperError> {
        self.0.step_with(observed, true, |c| Ok(c.realigned()))
    }
    fn done(&self) -> bool {
        self.0.done()
    }
    fn set_goal(&mut self, goal: &[f64]) -> Result<(), StepperError> {
        self.0.set_goal(goal)
    }
    fn phase(&self) -> f64 {
        self.0.phase()
    }
    fn closed_loop(&self) -> bool {
        true
    }
}

fn realigning(plan: Vec<Vec<f64>>, conditions: Conditions) -> Realigning {
    Realigning(Course::new(cols(2), plan, conditions, None).unwrap())
}

#[test]
fn undisturbed_a_course_is_its_plan_and_never_replans() {
    let plan = arc(50);
    let mut s = realigning(plan.clone(), Conditions::default());
    let r = run(&mut s, &plan[0], &[], 49, 200).unwrap();
    assert!(r.finished);
    assert_eq!(r.path, plan);
    assert_eq!(s.0.replans(), 0);
    assert_eq!(s.phase(), 1.0);
}

#[test]
fn held_a_realigned_course_rejoins_without_a_jump_and_a_replay_jumps() {
    let plan = arc(100);
    let largest = (1..plan.len())
        .map(|k| crate::dtw::euclidean(&plan[k], &plan[k - 1]))
        .fold(0.0, f64::max);
    let held = Disturbance::hold(0.4, 0.25);
    let mut s = realigning(plan.clone(), Conditions::default());
    let r = run(&mut s, &plan[0], std::slice::from_ref(&held), 99, 1000).unwrap();
    assert!(r.finished);
    let release = r.release.unwrap();
    assert!(r.largest_step_from(release) <= 2.0 * largest + 1e-12);
    assert!(crate::dtw::euclidean(r.path.last().unwrap(), plan.last().unwrap()) < 1e-9);
    assert!(s.0.replans() > 0);
    // the negative control: the plan by its clock
    let mut c = ByClock::new(cols(2), plan.clone(), "the replay");
    let r = run(&mut c, &plan[0], std::slice::from_ref(&held), 99, 1000).unwrap();
    assert!(r.largest_step_from(release) > 10.0 * largest);
}

#[test]
fn a_moved_goal_is_reached_exactly_without_a_jump() {
    let plan = arc(80);
    let via = ViaPoint {
        phase: 0.8,
        posture: vec![-0.8, 0.7],
    };
    let conditions = Conditions {
        goal: None,
        via: vec![via],
    };
    let bent = crate::condition::meet(&plan, &conditions.points(), None).unwrap();
    let mut s = realigning(bent.clone(), conditions);
    let goal = vec![-1.1, 0.2];
    let moved = Disturbance::goal(0.5, goal.clone());
    let r = run(&mut s, &plan[0], std::slice::from_ref(&moved), 79, 1000).unwrap();
    assert!(r.finished);
    assert!(crate::dtw::euclidean(r.path.last().unwrap(), &goal) < 1e-9);
    // the path until the goal moved is the plan's
    assert_eq!(r.path[..41], bent[..41]);
    let largest = (1..bent.len())
        .map(|k| crate::dtw::euclidean(&bent[k], &bent[k - 1]))
        .fold(0.0, f64::max);
    assert!(r.largest_step_from(40) < 2.0 * largest);
}

#[test]
fn bad_postures_and_goals_are_named_errors() {
    let plan = arc(10);
    let mut s = realigning(plan.clone(), Conditions::default());
    let e = s.step(&[0.0]).unwrap_err().to_string();
    assert!(e.contains("the observed posture has 1 values"), "{e}");
    let e = s.step(&[0.0, f64::NAN]).unwrap_err().to_string();
    assert!(e.contains("the observed posture: x1 is NaN"), "{e}");
    let e = s.set_goal(&[1.0, 2.0, 3.0]).unwrap_err().to_string();
    assert!(e.contains("the goal has 3 values"), "{e}");
    let ranged = Course::new(
        cols(2),
        plan,
        Conditions::default(),
        Some(vec![(-2.0, 2.0); 2]),
    );
    let e = ranged
        .unwrap()
        .set_goal(&[0.0, 3.0])
        .unwrap_err()
        .to_string();
    assert!(e.contains("outside its range"), "{e}");
    let e = Course::new(cols(2), vec![], Conditions::default(), None).unwrap_err();
    assert!(e.to_string().contains("at least one"), "{e}");
    let e = ByClock::new(cols(2), arc(3), "the replay")
        .set_goal(&[0.0, 0.0])
        .unwrap_err();
    assert!(
        e.to_string().contains("the replay commands a fixed plan"),
        "{e}"
    );
}

#[test]
fn a_kinematic_loop_refuses_a_disturbance_out_of_range() {
    let plan = arc(10);
    let mut s = ByClock::new(cols(2), plan.clone(), "the replay");
    let bad = [
        Disturbance::hold(1.5, 0.1),
        Disturbance::hold(0.5, f64::NAN),
        Disturbance::moved(0.5, vec![0.1], 0.1),
    ];
    for d in bad {
        let e = run(&mut s, &plan[0], std::slice::from_ref(&d), 9, 100)
            .unwrap_err()
            .to_string();
        assert!(e.contains("allowed"), "{e}");
    }
    assert!(run(&mut s, &plan[0], &[], 0, 100).is_err());
}

#[test]
fn a_move_displaces_the_arm_and_holds_it_there() {
    let plan = arc(20);
    let mut s = ByClock::new(cols(2), plan.clone(), "the replay");
    let d = Disturbance::moved(0.5, vec![0.1, -0.2], 0.1);
    let r = run(&mut s, &plan[0], std::slice::from_ref(&d), 20, 100).unwrap();
    assert_eq!(r.path[10], vec![plan[9][0] + 0.1, plan[9][1] - 0.2]);
    assert_eq!(r.path[11], r.path[10]);
    assert_eq!((r.held[10], r.held[11], r.held[12]), (true, true, false));
    assert_eq!(r.release, Some(12));
}

#[test]
fn replaced_via_points_are_passed_from_then_on_and_a_refused_set_changes_nothing() {
    let plan = arc(80);
    let via = |posture: Vec<f64>| ViaPoint {
        phase: 0.75,
        posture,
    };
    let first = Conditions {
        goal: None,
        via: vec![via(vec![-0.8, 0.7])],
    };
    let bent = crate::condition::meet(&plan, &first.points(), None).unwrap();
    let mut course = Course::new(cols(2), bent.clone(), first, None).unwrap();
    let mut path = Vec::new();
    for k in 0..80 {
        if k == 30 {
            // the wrong width is refused, and the course keeps its via-point
            assert!(course.set_via(vec![via(vec![0.0])]).is_err());
            course.set_via(vec![via(vec![-0.3, 0.5])]).unwrap();
        }
        let observed = path.last().cloned().unwrap_or(plan[0].clone());
        path.push(
            course
                .step_with(&observed, true, |c| Ok(c.realigned()))
                .unwrap(),
        );
    }
    // the path until then is the first plan's; afterwards it passes the new via-point (read
    // between two rows at its phase of the rest) and never jumps
    assert_eq!(path[..30], bent[1..31]);
    let nearest = (path.iter())
        .map(|p| crate::dtw::euclidean(p, &[-0.3, 0.5]))
        .fold(f64::INFINITY, f64::min);
    assert!(nearest < 0.02, "{nearest}");
    // the control: the first plan does not pass there
    let before = (bent.iter())
        .map(|p| crate::dtw::euclidean(p, &[-0.3, 0.5]))
        .fold(f64::INFINITY, f64::min);
    assert!(before > 0.1, "{before}");
    let largest = (1..bent.len())
        .map(|k| crate::dtw::euclidean(&bent[k], &bent[k - 1]))
        .fold(0.0, f64::max);
    let steps = (31..path.len()).map(|k| crate::dtw::euclidean(&path[k], &path[k - 1]));
    assert!(steps.fold(0.0, f64::max) < 2.0 * largest);
}
