//! Behaviour of the safe MuJoCo layer through its public API.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use cosco_hsom::mujoco::{self, Data, MjError, Model};
use std::path::Path;

/// A two-joint arm with a site at the tip, two position actuators and a fixed camera.
const ARM: &str = r#"
<mujoco model="two_link">
  <compiler autolimits="true" angle="radian"/>
  <option timestep="0.002"/>
  <worldbody>
    <light pos="0 0 2"/>
    <camera name="front" pos="0 -1.2 0.3" xyaxes="1 0 0 0 0.2 1"/>
    <body name="upper" pos="0 0 0.5">
      <joint name="shoulder" type="hinge" axis="0 1 0" range="-1.5 1.5"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03" mass="1"/>
      <body name="lower" pos="0.3 0 0">
        <joint name="elbow" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.25 0 0" size="0.025" mass="0.5"/>
        <site name="tip" pos="0.25 0 0"/>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="shoulder_act" joint="shoulder" kp="50" ctrlrange="-1.5 1.5" forcerange="-20 20"/>
    <motor name="elbow_motor" joint="elbow"/>
  </actuator>
</mujoco>
"#;

fn arm() -> Model {
    Model::from_xml_str(ARM).expect("the test arm loads")
}

#[test]
fn version_is_222() {
    assert_eq!(mujoco::version(), 222);
    mujoco::check_version().unwrap();
}

#[test]
fn load_from_string_reports_sizes() {
    let m = arm();
    assert_eq!((m.nq(), m.nv(), m.nu(), m.njnt()), (2, 2, 2, 2));
    assert_eq!(m.nsite(), 1);
    assert_eq!(m.nbody(), 3, "world + upper + lower");
    assert_eq!(m.timestep(), 0.002);
}

#[test]
fn load_from_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("arm.xml");
    std::fs::write(&path, ARM).unwrap();
    let m = Model::from_xml_path(&path).unwrap();
    assert_eq!(m.nq(), 2);
    assert_eq!(m.joint_id("elbow"), Some(1));
}

#[test]
fn missing_file_error_names_the_path() {
    let err = Model::from_xml_path(Path::new("/nonexistent/dir/arm.xml")).unwrap_err();
    match &err {
        MjError::Load { path, .. } => assert_eq!(path, "/nonexistent/dir/arm.xml"),
        other => panic!("expected Load, got {other:?}"),
    }
    assert!(err.to_string().contains("/nonexistent/dir/arm.xml"));
}

#[test]
fn lookups_by_name_and_id() {
    let m = arm();
    assert_eq!(m.joint_id("shoulder"), Some(0));
    assert_eq!(m.joint_id("elbow"), Some(1));
    assert_eq!(m.joint_id("wrist"), None);
    assert_eq!(m.actuator_id("shoulder_act"), Some(0));
    assert_eq!(m.actuator_id("nope"), None);
    assert_eq!(m.site_id("tip"), Some(0));
    assert_eq!(m.site_id("base"), None);
    assert_eq!(m.body_id("lower"), Some(2));
    assert_eq!(m.body_id("hand"), None);
    assert_eq!(m.camera_id("front"), Some(0));
    assert_eq!(m.camera_id("side"), None);
    assert_eq!(m.joint_id("with\0nul"), None);

    assert_eq!(m.joint_name(1).as_deref(), Some("elbow"));
    assert_eq!(m.joint_name(2), None);
    assert_eq!(m.actuator_name(1).as_deref(), Some("elbow_motor"));
    assert_eq!(m.site_name(0).as_deref(), Some("tip"));
    assert_eq!(m.body_name(1).as_deref(), Some("upper"));
    assert_eq!(m.body_name(99), None);
}

#[test]
fn joint_and_actuator_properties() {
    let m = arm();
    assert_eq!(m.joint_range(0), Some((-1.5, 1.5)));
    assert_eq!(m.joint_range(1), None, "elbow is not limited");
    assert_eq!(m.joint_qpos_adr(1), 1);
    assert_eq!(m.joint_dof_adr(1), 1);
    assert_eq!(m.actuator_ctrl_range(0), Some((-1.5, 1.5)));
    assert_eq!(m.actuator_ctrl_range(1), None);
    assert_eq!(m.actuator_force_range(0), Some((-20.0, 20.0)));
    assert_eq!(m.actuator_force_range(1), None);
    assert_eq!(m.actuator_joint(0), Some(0));
    assert_eq!(m.actuator_joint(1), Some(1));
    assert!((m.body_mass(1) - 1.0).abs() < 1e-9);
    assert!((m.body_mass(2) - 0.5).abs() < 1e-9);
    assert_eq!(m.body_mass(0), 0.0);
}

/// Run `f` and check it left no MUJOCO_LOG.TXT in the working directory.
fn no_log_file<T>(f: impl FnOnce() -> T) -> T {
    let log = Path::new("MUJOCO_LOG.TXT");
    let before = log.exists();
    let out = f();
    assert!(
        before || !log.exists(),
        "MuJoCo wrote MUJOCO_LOG.TXT into the working directory"
    );
    out
}

#[test]
fn unknown_element_is_an_error_with_mujocos_message() {
    let xml = "<mujoco><worldbody><blob/></worldbody></mujoco>";
    let err = no_log_file(|| Model::from_xml_str(xml)).unwrap_err();
    match &err {
        MjError::Load { path, message } => {
            assert_eq!(path, "<string>");
            assert!(message.contains("blob"), "message: {message}");
            assert!(
                message.to_lowercase().contains("unrecognized"),
                "message: {message}"
            );
        }
        other => panic!("expected Load, got {other:?}"),
    }
}

#[test]
fn bad_attribute_is_an_error_with_mujocos_message() {
    let xml = r#"<mujoco><worldbody><body><joint type="hinge" flavour="x"/><geom size="0.1"/></body></worldbody></mujoco>"#;
    let err = no_log_file(|| Model::from_xml_str(xml)).unwrap_err();
    let text = err.to_string();
    assert!(text.contains("flavour"), "{text}");
}

#[test]
fn range_without_limited_is_rejected_with_mujocos_message() {
    // MuJoCo 2.2 wants limited="true" (or autolimits) with a range: the message says so.
    let xml = r#"<mujoco><worldbody><body><joint type="hinge" range="-1 1"/><geom size="0.1"/></body></worldbody></mujoco>"#;
    let err = no_log_file(|| Model::from_xml_str(xml)).unwrap_err();
    assert!(err.to_string().contains("limited"), "{err}");
}

#[test]
fn broken_file_error_names_path_and_reason() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.xml");
    std::fs::write(&path, "<mujoco><worldbody><blob/></worldbody></mujoco>").unwrap();
    let err = no_log_file(|| Model::from_xml_path(&path)).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("broken.xml") && text.contains("blob"),
        "{text}"
    );
}

#[test]
fn step_advances_time_and_gravity_moves_the_arm() {
    let m = arm();
    let mut d = Data::new(&m).unwrap();
    assert_eq!(d.time(), 0.0);
    assert_eq!(d.qpos(), &[0.0, 0.0]);
    for _ in 0..100 {
        d.step().unwrap();
    }
    assert!((d.time() - 0.2).abs() < 1e-9, "time {}", d.time());
    assert!(
        d.qpos()[1].abs() > 1e-3,
        "the unactuated elbow falls: {:?}",
        d.qpos()
    );
    assert!(d.qvel().iter().any(|v| v.abs() > 1e-3));
    assert!(
        d.qfrc_bias().iter().any(|v| v.abs() > 1e-3),
        "gravity shows in the bias"
    );
    d.reset();
    assert_eq!(d.time(), 0.0);
    assert_eq!(d.qpos(), &[0.0, 0.0]);
}

#[test]
fn position_actuator_tracks_its_target() {
    let m = arm();
    let mut d = Data::new(&m).unwrap();
    d.ctrl_mut()[0] = 0.5;
    for _ in 0..2000 {
        d.step().unwrap();
    }
    assert_eq!(d.ctrl()[0], 0.5);
    assert!(d.actuator_force()[0].abs() > 0.0);
    // sags under gravity (the elbow hangs), but moves towards the target
    assert!(d.qpos()[0] > 0.2, "shoulder {:?}", d.qpos());
}

#[test]
fn forward_updates_kinematics_after_setting_qpos() {
    let m = arm();
    let mut d = Data::new(&m).unwrap();
    let tip = m.site_id("tip").unwrap();
    let shoulder = m.joint_id("shoulder").unwrap();
    d.forward().unwrap();
    let straight = d.site_xpos(tip);
    assert!(
        (straight[0] - 0.55).abs() < 1e-9 && (straight[2] - 0.5).abs() < 1e-9,
        "{straight:?}"
    );
    assert_eq!(d.xanchor(shoulder), [0.0, 0.0, 0.5]);
    assert_eq!(d.xaxis(shoulder), [0.0, 1.0, 0.0]);
    assert_eq!(d.body_xpos(m.body_id("lower").unwrap()), [0.3, 0.0, 0.5]);
    let xmat = d.site_xmat(tip);
    assert_eq!(xmat, [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]);

    // Rotate the shoulder by +90 degrees about +y: the arm points down (x -> -z).
    d.qpos_mut()[0] = std::f64::consts::FRAC_PI_2;
    d.forward().unwrap();
    let down = d.site_xpos(tip);
    assert!(
        down[0].abs() < 1e-9 && (down[2] - (0.5 - 0.55)).abs() < 1e-9,
        "{down:?}"
    );
    assert_eq!(d.time(), 0.0, "forward does not integrate");
}

#[test]
fn divergence_is_reported_as_unstable() {
    let m = arm();
    let mut d = Data::new(&m).unwrap();
    for _ in 0..10 {
        d.step().unwrap();
    }
    let t = d.time();
    d.qvel_mut()[1] = f64::NAN;
    match d.step() {
        Err(MjError::Unstable { time, message }) => {
            assert_eq!(time, t);
            assert!(!message.is_empty());
        }
        other => panic!("expected Unstable, got {other:?}"),
    }
    // MuJoCo reset the state; stepping goes on from there.
    assert!(d.qvel().iter().all(|v| v.is_finite()));
    d.step().unwrap();
}

#[test]
fn data_borrows_its_model() {
    let m = arm();
    let d = Data::new(&m).unwrap();
    assert!(std::ptr::eq(d.model(), &m));
}

fn run_arm(m: &Model, target: f64) -> Vec<f64> {
    let mut d = Data::new(m).unwrap();
    d.ctrl_mut()[0] = target;
    for _ in 0..500 {
        d.step().unwrap();
    }
    d.qpos().to_vec()
}

#[test]
fn one_model_many_threads() {
    let m = arm();
    let targets = [0.0, 0.3, 0.6, 0.9];
    let parallel: Vec<Vec<f64>> = std::thread::scope(|s| {
        let handles: Vec<_> = targets
            .iter()
            .map(|&t| {
                let m = &m;
                s.spawn(move || run_arm(m, t))
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let sequential: Vec<Vec<f64>> = targets.iter().map(|&t| run_arm(&m, t)).collect();
    // Threads sharing one Model do not disturb each other: bit-identical to a sequential run,
    // and different targets give different states.
    assert_eq!(parallel, sequential);
    assert_ne!(parallel[0], parallel[3]);
}

#[test]
fn loading_in_parallel_with_errors_keeps_errors_apart() {
    std::thread::scope(|s| {
        for i in 0..4 {
            s.spawn(move || {
                for _ in 0..5 {
                    if i % 2 == 0 {
                        assert!(Model::from_xml_str(ARM).is_ok());
                    } else {
                        let err = Model::from_xml_str("<mujoco><bogus/></mujoco>").unwrap_err();
                        assert!(err.to_string().contains("bogus"), "{err}");
                    }
                }
            });
        }
    });
}

/// Twenty boxes falling on a floor with a MuJoCo stack large enough to compile (no contact
/// at rest) but far too small once contacts pile up.
fn tiny_stack_xml() -> String {
    let mut bodies = String::new();
    for i in 0..20 {
        let (x, z) = ((i % 5) as f64 * 0.2, 0.1 + 0.15 * (i / 5) as f64);
        bodies += &format!(
            r#"<body pos="{x} 0 {z}"><freejoint/><geom type="box" size="0.05 0.05 0.05"/></body>"#
        );
    }
    format!(
        r#"<mujoco><size nstack="2000"/><worldbody><geom type="plane" size="5 5 0.1"/>{bodies}</worldbody></mujoco>"#
    )
}

/// MuJoCo 2.2 goes on after a stack overflow when the error hook returns, writing past the
/// stack: the hook aborts the process instead, with MuJoCo's message, and no log file.
#[test]
fn stack_overflow_aborts_with_mujocos_message_and_no_log_file() {
    const CHILD: &str = "COSCO_HSOM_STACK_OVERFLOW_CHILD";
    if std::env::var_os(CHILD).is_some() {
        let m = Model::from_xml_str(&tiny_stack_xml()).unwrap();
        let mut d = Data::new(&m).unwrap();
        let mut outcome = Ok(());
        for _ in 0..500 {
            outcome = d.step();
        }
        // Not reached when the hook aborts; say so on stdout for the parent to see.
        println!("CHILD RETURNED: {outcome:?}");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "mujoco_safe_layer::stack_overflow_aborts_with_mujocos_message_and_no_log_file",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, "1")
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stdout.contains("CHILD RETURNED"),
        "the step returned: {stdout}"
    );
    use std::os::unix::process::ExitStatusExt;
    assert_eq!(
        out.status.signal(),
        Some(6),
        "SIGABRT expected; status {:?}, stderr {stderr}",
        out.status
    );
    assert!(
        stderr.contains("Stack overflow") && stderr.contains("nstack"),
        "{stderr}"
    );
    assert!(!dir.path().join("MUJOCO_LOG.TXT").exists());
}
