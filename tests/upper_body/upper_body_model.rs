//! The Nao H25 V5 upper body (`models/nao_upper_body.xml`) against its reference
//! (nao-left-arm.md, nao-upper-body.md: ros-naoqi's NaoH25V50 description): kinematics, joint
//! table, the left arm against `models/nao_left_arm.xml`, contacts, servo stability, framing.
//! Through the crate's MuJoCo layer only.
#![cfg(feature = "sim")] // needs MuJoCo

use cosco_hsom::mujoco::{Contact, Data, MjError, Model};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeSet;

const UPPER: &str = include_str!("../../models/nao_upper_body.xml");
const LEFT_ARM: &str = include_str!("../../models/nao_left_arm.xml");

use crate::nao_tables as upper_body;
use upper_body::*;

fn load(xml: &str) -> Model {
    Model::from_xml_str(xml).expect("the model loads")
}

/// The upper body with `from` replaced by `to` (which must occur exactly once).
fn variant(from: &str, to: &str) -> Model {
    assert_eq!(UPPER.matches(from).count(), 1, "{from:?} in the model");
    load(&UPPER.replacen(from, to, 1))
}

/// The upper body whose collision geoms report every pair closer than 5 cm (margin = gap:
/// detected, never active), to measure clearances; the dynamics are those of the model.
fn measuring() -> Model {
    variant(r#"margin="0" gap="0""#, r#"margin="0.05" gap="0.05""#)
}

/// Write a posture by joint name (the model's qpos order is not assumed) and run forward.
fn pose<'m>(model: &'m Model, q: &Posture) -> Data<'m> {
    let mut data = Data::new(model).unwrap();
    set(&mut data, q);
    data.forward().unwrap();
    data
}

fn set(data: &mut Data, q: &Posture) {
    let model = data.model();
    for (joint, v) in all_joints().iter().zip(q) {
        let id = model
            .joint_id(joint.name)
            .unwrap_or_else(|| panic!("joint {}", joint.name));
        data.qpos_mut()[model.joint_qpos_adr(id)] = *v;
    }
}

fn random_posture(rng: &mut ChaCha8Rng) -> Posture {
    let mut q = [0.0; 14];
    for (v, joint) in q.iter_mut().zip(all_joints()) {
        *v = rng.gen_range(joint.range.0..=joint.range.1);
    }
    q
}

// ---------------------------------------------------------------------------------------
// (a) kinematics against a closed-form chain

/// Largest position (m) and orientation (matrix entry) error of the model's sites against
/// the tables over `n` seeded random postures.
fn site_errors(
    model: &Model,
    left: &[Joint; 6],
    right: &[Joint; 6],
    camera_pitch: f64,
    n: usize,
) -> (f64, f64) {
    let mut rng = ChaCha8Rng::seed_from_u64(51);
    let (mut pos, mut rot) = (0.0f64, 0.0f64);
    let mut data = Data::new(model).unwrap();
    for _ in 0..n {
        let q = random_posture(&mut rng);
        set(&mut data, &q);
        data.forward().unwrap();
        for (site, (r, p)) in SITES
            .iter()
            .zip(reference_sites(left, right, camera_pitch, &q))
        {
            let id = model.site_id(site).unwrap();
            let xpos = data.site_xpos(id);
            let xmat = data.site_xmat(id);
            for k in 0..3 {
                pos = pos.max((xpos[k] - p[k]).abs());
                for c in 0..3 {
                    rot = rot.max((xmat[3 * k + c] - r[(k, c)]).abs());
                }
            }
        }
    }
    (pos, rot)
}

#[test]
fn sites_follow_the_published_chains() {
    let model = load(UPPER);
    let (pos, rot) = site_errors(&model, &LEFT, &RIGHT, CAMERA_TOP.1, 200);
    eprintln!("sites against the chains: {pos:e} m, orientation {rot:e}");
    assert!(pos < 1e-6, "site positions off by {pos:e} m");
    assert!(rot < 1e-6, "site orientations off by {rot:e}");

    // negative controls: the right arm taken as an exact mirror of the left (its hand offset
    // z -0.01231 instead of the published -0.01213), and the camera without its pitch
    let mut mirrored = RIGHT;
    mirrored[5].origin[2] = LEFT[5].origin[2];
    let (pos, _) = site_errors(&model, &LEFT, &mirrored, CAMERA_TOP.1, 20);
    assert!(pos > 1e-5, "a mirrored right hand went unnoticed: {pos:e}");
    let (_, rot) = site_errors(&model, &LEFT, &RIGHT, 0.0, 20);
    assert!(rot > 1e-3, "an unpitched camera went unnoticed: {rot:e}");
}

// ---------------------------------------------------------------------------------------
// (b) joint table, actuators, servo gains

/// kp, kv, armature of each joint, in [`all_joints`] order: the left arm's (nao_left_arm.xml),
/// the same for the right arm, the head's as the model documents them.
fn gains() -> Vec<(f64, f64, f64)> {
    let arm = [
        (50.0, 1.2, 0.006),
        (50.0, 1.2, 0.006),
        (40.0, 0.7, 0.004),
        (40.0, 0.7, 0.004),
        (15.0, 0.25, 0.002),
        (5.0, 0.08, 0.001),
    ];
    let head = [(40.0, 1.0, 0.004), (40.0, 1.0, 0.004)];
    head.iter().chain(&arm).chain(&arm).copied().collect()
}

/// Every difference between the model's joints and actuators and `table` (joint order,
/// ranges, torque limits, control ranges, gains).
fn table_mismatches(model: &Model, table: &[Joint]) -> Vec<String> {
    let mut out = Vec::new();
    if (model.njnt(), model.nu()) != (table.len(), table.len()) {
        out.push(format!("{} joints, {} actuators", model.njnt(), model.nu()));
    }
    for (i, (joint, (kp, kv, armature))) in table.iter().zip(gains()).enumerate() {
        let name = joint.name;
        let mut check = |what: &str, ok: bool| {
            if !ok {
                out.push(format!("{name}: {what}"));
            }
        };
        check("joint order", model.joint_name(i).as_deref() == Some(name));
        check(
            "actuator order",
            model.actuator_name(i).as_deref() == Some(name),
        );
        let (Some(jid), Some(aid)) = (model.joint_id(name), model.actuator_id(name)) else {
            continue;
        };
        let (lo, hi) = joint.range;
        check("range", model.joint_range(jid) == Some((lo, hi)));
        check("actuated joint", model.actuator_joint(aid) == Some(jid));
        check(
            "ctrlrange",
            model.actuator_ctrl_range(aid) == Some((lo, hi)),
        );
        let t = joint.max_torque;
        check(
            "forcerange",
            model.actuator_force_range(aid) == Some((-t, t)),
        );
        check("kp", model.actuator_gain(aid) == kp);
        check("bias", model.actuator_bias(aid) == [0.0, -kp, -kv]);
        check(
            "armature",
            model.dof_armature(model.joint_dof_adr(jid)) == armature,
        );
    }
    out
}

#[test]
fn joints_and_actuators_match_the_published_table() {
    let model = load(UPPER);
    assert_eq!(
        table_mismatches(&model, &all_joints()),
        Vec::<String>::new()
    );

    // negative controls: the right arm with the left's shoulder-roll torque (1.7835, not the
    // published 1.783), and with the left's elbow-roll range unmirrored
    let mut table = all_joints();
    table[9].max_torque = LEFT[1].max_torque;
    table[11].range = LEFT[3].range;
    let found = table_mismatches(&model, &table);
    assert_eq!(
        found,
        [
            "RShoulderRoll: forcerange",
            "RElbowRoll: range",
            "RElbowRoll: ctrlrange"
        ],
    );
}

// ---------------------------------------------------------------------------------------
// (c) the left arm is the left-arm model's

/// Whether two bodies differ in mass, centre of mass or inertia.
fn body_differs(a: &Model, a_body: &str, b: &Model, b_body: &str) -> bool {
    let (x, y) = (a.body_id(a_body).unwrap(), b.body_id(b_body).unwrap());
    a.body_mass(x) != b.body_mass(y)
        || a.body_ipos(x) != b.body_ipos(y)
        || a.body_iquat(x) != b.body_iquat(y)
        || a.body_inertia(x) != b.body_inertia(y)
}

#[test]
fn left_arm_is_the_left_arm_model() {
    let upper = load(UPPER);
    let arm = load(LEFT_ARM);
    for body in ["torso"].iter().chain(&LEFT_BODIES) {
        assert!(!body_differs(&upper, body, &arm, body), "{body} differs");
    }
    // negative control: the right bicep is not the mirrored left one (published inertias)
    assert!(body_differs(&upper, "RBicep", &arm, "LBicep"));

    for joint in &LEFT {
        let (a, b) = (
            arm.actuator_id(joint.name).unwrap(),
            upper.actuator_id(joint.name).unwrap(),
        );
        assert_eq!(
            arm.actuator_gain(a),
            upper.actuator_gain(b),
            "{}",
            joint.name
        );
        assert_eq!(
            arm.actuator_bias(a),
            upper.actuator_bias(b),
            "{}",
            joint.name
        );
    }

    let mut rng = ChaCha8Rng::seed_from_u64(52);
    let mut arm_data = Data::new(&arm).unwrap();
    let (mut same, mut mirrored) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let q = random_posture(&mut rng);
        let left: Arm = q[2..8].try_into().unwrap();
        let data = pose(&upper, &posture([q[0], q[1]], left, mirror(left)));
        for (joint, v) in LEFT.iter().zip(left) {
            let id = arm.joint_id(joint.name).unwrap();
            arm_data.qpos_mut()[arm.joint_qpos_adr(id)] = v;
        }
        arm_data.forward().unwrap();
        for site in ["l_wrist", "l_gripper"] {
            let (a, b) = (arm.site_id(site).unwrap(), upper.site_id(site).unwrap());
            let (pa, pb) = (arm_data.site_xpos(a), data.site_xpos(b));
            let (ra, rb) = (arm_data.site_xmat(a), data.site_xmat(b));
            for k in 0..3 {
                same = same.max((pa[k] - pb[k]).abs());
            }
            for k in 0..9 {
                same = same.max((ra[k] - rb[k]).abs());
            }
            // negative control: the right arm at the mirrored posture, mirrored back
            let r = upper.site_id(&site.replacen('l', "r", 1)).unwrap();
            let pr = data.site_xpos(r);
            for (k, sign) in [1.0, -1.0, 1.0].iter().enumerate() {
                mirrored = mirrored.max((pa[k] - sign * pr[k]).abs());
            }
        }
    }
    eprintln!("left arm against nao_left_arm.xml: {same:e}; mirrored right: {mirrored:e}");
    assert!(same < 1e-12, "the left arms differ by {same:e}");
    assert!(
        mirrored > 1e-5,
        "the mirrored right gripper matched the left: {mirrored:e}"
    );
}

// ---------------------------------------------------------------------------------------
// (d) contacts

fn is_left(body: &str) -> bool {
    LEFT_BODIES.contains(&body)
}
fn is_right(body: &str) -> bool {
    RIGHT_BODIES.contains(&body)
}
fn names(c: &Contact) -> [&str; 2] {
    c.body_name.each_ref().map(|n| n.as_deref().unwrap_or("?"))
}

/// The smallest distance between collision geoms at `q`, measured with [`measuring`]
/// (negative: they penetrate), and the pair of bodies it is between.
fn clearance(measure: &Model, q: &Posture) -> (f64, String) {
    let data = pose(measure, q);
    let near = data.detected_contacts();
    near.iter()
        .min_by(|a, b| a.dist.total_cmp(&b.dist))
        .map_or((0.05, "nothing within 5 cm".into()), |c| {
            (c.dist, names(c).join("-"))
        })
}

/// The documented postures, for the left arm with the right at StandInit and mirrored,
/// and both arms at once for the whole-body postures (not ReadingWatch: the forearms would
/// cross).
fn documented_postures() -> Vec<(String, Posture)> {
    let mut out = Vec::new();
    for (name, arm) in DOCUMENTED {
        out.push((
            format!("{name} left"),
            posture([0.0; 2], arm, mirror(STAND_INIT)),
        ));
        out.push((
            format!("{name} right"),
            posture([0.0; 2], STAND_INIT, mirror(arm)),
        ));
        if name != "ReadingWatch" {
            out.push((format!("{name} both"), posture([0.0; 2], arm, mirror(arm))));
        }
    }
    out
}

#[test]
fn documented_postures_and_keyframes_touch_nothing() {
    let model = load(UPPER);
    let measure = measuring();
    let mut reading = Vec::new();
    for (name, q) in documented_postures() {
        let contacts = pose(&model, &q).contacts();
        assert!(contacts.is_empty(), "{name}: {contacts:?}");
        let (gap, pair) = clearance(&measure, &q);
        eprintln!("{name:>18}: clearance {:5.1} mm ({pair})", gap * 1e3);
        assert!(gap > 0.0, "{name}: {gap} between {pair}");
        if name.starts_with("ReadingWatch") {
            reading.push(gap);
        }
    }
    // the reading-watch margin (upper arm to the torso's front edge), the same on both sides
    assert!(
        reading.iter().all(|&g| g > 0.003),
        "reading-watch clearance {reading:?}"
    );
    assert!((reading[0] - reading[1]).abs() < 1e-9);
    for key in 0..model.nkey() {
        let mut data = Data::new(&model).unwrap();
        data.reset_to_key(key);
        data.forward().unwrap();
        assert!(
            data.contacts().is_empty(),
            "keyframe {:?}",
            model.key_name(key)
        );
        assert_eq!(
            model.key_qpos(key),
            model.key_ctrl(key),
            "{:?}",
            model.key_name(key)
        );
    }
    // the keyframes hold the documented postures
    let key = |name: &str| model.key_qpos(model.key_id(name).unwrap());
    let si = mirror(STAND_INIT);
    assert_eq!(key("StandInit"), posture([0.0; 2], STAND_INIT, si).to_vec());
    assert_eq!(
        key("ReadingWatch"),
        posture([0.0; 2], DOCUMENTED[4].1, si).to_vec()
    );
    assert_eq!(
        key("ReadingWatchRight"),
        posture([0.0; 2], STAND_INIT, mirror(DOCUMENTED[4].1)).to_vec()
    );
    for (name, arm) in &DOCUMENTED[1..4] {
        assert_eq!(
            key(name),
            posture([0.0; 2], *arm, mirror(*arm)).to_vec(),
            "{name}"
        );
    }
}

#[test]
fn a_hand_in_the_chest_is_a_contact() {
    let model = load(UPPER);
    for (side, q, arm) in [
        (
            "left",
            posture([0.0; 2], HAND_INTO_CHEST, mirror(STAND_INIT)),
            is_left as fn(&str) -> bool,
        ),
        (
            "right",
            posture([0.0; 2], STAND_INIT, mirror(HAND_INTO_CHEST)),
            is_right,
        ),
    ] {
        let contacts = pose(&model, &q).contacts();
        let hit = contacts.iter().find(|c| {
            let [a, b] = names(c);
            (arm(a) && b == "torso") || (arm(b) && a == "torso")
        });
        let hit = hit.unwrap_or_else(|| panic!("{side}: no hand-torso contact in {contacts:?}"));
        assert!(hit.dist < 0.0);
        let hand = ["_wrist", "ForeArm", "Hand_fingers"];
        assert!(
            names(hit)
                .iter()
                .any(|b| hand.iter().any(|h| b.ends_with(h))),
            "{hit:?}"
        );
        assert!(clearance(&measuring(), &q).0 < -0.005, "{side}");
    }
}

#[test]
fn crossed_arms_are_an_arm_arm_contact() {
    let model = load(UPPER);
    let arm_arm = |q: &Posture| {
        pose(&model, q).contacts().into_iter().any(|c| {
            let [a, b] = names(&c);
            (is_left(a) && is_right(b)) || (is_right(a) && is_left(b))
        })
    };
    assert!(arm_arm(&posture([0.0; 2], HUG, mirror(HUG))));
    // negative controls: one arm folded alone, and both arms at StandZero
    assert!(!arm_arm(&posture([0.0; 2], HUG, mirror(STAND_INIT))));
    assert!(!arm_arm(&posture(
        [0.0; 2],
        DOCUMENTED[3].1,
        mirror(DOCUMENTED[3].1)
    )));
}

/// Pairs of bodies meeting at one joint centre (a joint's own links).
const JOINT_NEIGHBOURS: [(&str, &str); 14] = [
    ("torso", "Neck"),
    ("torso", "Head"),
    ("Neck", "Head"),
    ("torso", "LShoulder"),
    ("LShoulder", "LBicep"),
    ("LBicep", "LElbow"),
    ("LElbow", "LForeArm"),
    ("LBicep", "LForeArm"),
    ("LForeArm", "l_wrist"),
    ("torso", "RShoulder"),
    ("RShoulder", "RBicep"),
    ("RBicep", "RElbow"),
    ("RBicep", "RForeArm"),
    ("RForeArm", "r_wrist"),
];

/// The pairs of joint neighbours in contact at 200 seeded random postures.
fn neighbour_contacts(model: &Model) -> BTreeSet<String> {
    let mut rng = ChaCha8Rng::seed_from_u64(53);
    let mut data = Data::new(model).unwrap();
    let mut found = BTreeSet::new();
    for _ in 0..200 {
        set(&mut data, &random_posture(&mut rng));
        data.forward().unwrap();
        for c in data.contacts() {
            if let Some((a, b)) = JOINT_NEIGHBOURS.iter().find(|(a, b)| c.between(a, b)) {
                found.insert(format!("{a}-{b}"));
            }
        }
    }
    found
}

#[test]
fn a_link_never_touches_its_joint_neighbours() {
    assert_eq!(neighbour_contacts(&load(UPPER)), BTreeSet::new());
    // negative control: without the model's <contact> exclusions the shoulders touch the torso
    let start = UPPER.find("<contact>").unwrap();
    let end = UPPER.find("</contact>").unwrap() + "</contact>".len();
    let mut bare = UPPER.to_string();
    bare.replace_range(start..end, "");
    let found = neighbour_contacts(&load(&bare));
    assert!(found.iter().any(|p| p == "torso-LShoulder"), "{found:?}");
}

/// The deepest penetration between collision geoms of `model` at `q` (0 without contact)
/// and the bodies it is between.
fn deepest(model: &Model, q: &Posture) -> (f64, String) {
    let contacts = pose(model, q).contacts();
    contacts
        .iter()
        .min_by(|a, b| a.dist.total_cmp(&b.dist))
        .map_or((0.0, String::new()), |c| {
            (c.dist.min(0.0), names(c).join("-"))
        })
}

/// Drive `model`'s servos from StandInit towards `target` for `steps`, and judge each
/// posture passed with the full model's contacts: the deepest penetration on the way, and
/// the one at the end with its bodies.
fn drive(model: &Model, target: &Posture, steps: usize) -> Result<(f64, f64, String), MjError> {
    let judge = load(UPPER);
    let mut data = Data::new(model).unwrap();
    data.reset_to_key(model.key_id("StandInit").unwrap());
    let order = all_joints();
    for (joint, v) in order.iter().zip(target) {
        data.ctrl_mut()[model.actuator_id(joint.name).unwrap()] = *v;
    }
    let mut worst = 0.0f64;
    let mut end = (0.0, String::new());
    for _ in 0..steps {
        data.step()?;
        let reached: Posture = std::array::from_fn(|i| {
            data.qpos()[model.joint_qpos_adr(model.joint_id(order[i].name).unwrap())]
        });
        end = deepest(&judge, &reached);
        worst = worst.min(end.0);
    }
    Ok((worst, end.0, end.1))
}

#[test]
fn servos_driving_a_hand_into_the_chest_are_stopped_by_it() {
    let q = posture([0.0; 2], HAND_INTO_CHEST, mirror(STAND_INIT));
    let (worst, end, pair) = drive(&load(UPPER), &q, 1000).unwrap();
    eprintln!(
        "hand driven into the chest: {:.2} mm on the way, {:.3} mm at rest ({pair})",
        worst * 1e3,
        end * 1e3
    );
    assert!(end < 0.0 && end > -0.001, "{end} between {pair}");
    assert!(worst > -0.005, "{worst}");
    assert!(pair.contains("torso"), "{pair}");
    // negative control: with contacts disabled the hand reaches into the chest
    let free = variant(
        r#"gravity="0 0 -9.81"/>"#,
        r#"gravity="0 0 -9.81"><flag contact="disable"/></option>"#,
    );
    let (worst, end, _) = drive(&free, &q, 1000).unwrap();
    assert!(worst < -0.005 && end < -0.005, "{worst} {end}");
}

// ---------------------------------------------------------------------------------------
// (e) servos

/// Hold keyframe StandInit under the servos for `seconds`: the largest joint error over the
/// run, the largest joint speed over its last 0.1 s, and whether any contact appeared.
fn hold(model: &Model, seconds: f64) -> Result<(f64, f64, bool), MjError> {
    let mut data = Data::new(model).unwrap();
    let key = model.key_id("StandInit").unwrap();
    data.reset_to_key(key);
    let target = model.key_qpos(key);
    let steps = (seconds / model.timestep()).round() as usize;
    let (mut error, mut speed, mut touched) = (0.0f64, 0.0f64, false);
    for i in 0..steps {
        data.step()?;
        for (q, t) in data.qpos().iter().zip(&target) {
            error = error.max((q - t).abs());
        }
        if (steps - i) as f64 * model.timestep() <= 0.1 {
            speed = data.qvel().iter().fold(speed, |m, v| m.max(v.abs()));
        }
        touched |= !data.contacts().is_empty();
    }
    Ok((error, speed, touched))
}

#[test]
fn stand_init_holds_for_two_seconds() {
    let (error, speed, touched) = hold(&load(UPPER), 2.0).unwrap();
    eprintln!("StandInit held 2 s: joint error {error:.5} rad, final speed {speed:e} rad/s");
    // static sag tau_gravity / kp: a few milliradians
    assert!(error < 0.01, "joint error {error} rad");
    assert!(speed < 1e-3, "still moving at {speed} rad/s");
    assert!(!touched);
    // negative control: at a 0.02 s timestep the explicit servo damping (kv dt / armature
    // above 2 at the wrist) diverges
    let coarse = variant(r#"timestep="0.002""#, r#"timestep="0.02""#);
    match hold(&coarse, 2.0) {
        Err(MjError::Unstable { .. }) => {}
        Ok((error, speed, _)) => assert!(error > 0.01 || speed > 1e-3, "{error} {speed}"),
        Err(other) => panic!("{other}"),
    }
}

/// Peak of a `step` rad step of joint `joint` from StandInit over 1 s, relative to the step.
fn step_peak(model: &Model, joint: &str, step: f64) -> f64 {
    let mut data = Data::new(model).unwrap();
    data.reset_to_key(model.key_id("StandInit").unwrap());
    let adr = model.joint_qpos_adr(model.joint_id(joint).unwrap());
    let start = data.qpos()[adr];
    data.ctrl_mut()[model.actuator_id(joint).unwrap()] = start + step;
    let mut peak = f64::MIN;
    for _ in 0..500 {
        data.step().unwrap();
        peak = peak.max((data.qpos()[adr] - start) / step);
    }
    peak
}

#[test]
fn head_servos_step_without_overshoot() {
    let model = load(UPPER);
    for (joint, step) in [("HeadYaw", 1.0), ("HeadPitch", 0.5), ("HeadPitch", -0.5)] {
        let peak = step_peak(&model, joint, step);
        eprintln!("{joint} step {step}: peak {peak:.4} of the step");
        // gravity sag at HeadPitch 0.5 is 0.0037 rad (0.7 % of the step)
        assert!(peak < 1.01 && peak > 0.98, "{joint} {step}: peak {peak}");
    }
    // negative control: half the velocity gain overshoots
    let soft = load(&UPPER.replace(r#"biasprm="0 -40 -1.0""#, r#"biasprm="0 -40 -0.5""#));
    assert!(step_peak(&soft, "HeadYaw", 1.0) > 1.05);
}

// ---------------------------------------------------------------------------------------
// (f) the clip's camera

/// Where `p` falls in the image of camera `cam` (aspect width / height): both coordinates
/// in -1..1 inside the picture, `None` behind the camera.
fn project(data: &Data, cam: usize, aspect: f64, p: [f64; 3]) -> Option<(f64, f64)> {
    let (c, r) = (data.cam_xpos(cam), data.cam_xmat(cam));
    let d = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
    // columns of cam_xmat: image right, image up, backwards
    let local: [f64; 3] = std::array::from_fn(|k| (0..3).map(|i| r[3 * i + k] * d[i]).sum());
    let depth = -local[2];
    if depth <= 0.0 {
        return None;
    }
    let half = (data.model().camera_fovy(cam).to_radians() / 2.0).tan() * depth;
    Some((local[0] / (half * aspect), local[1] / half))
}

/// The worst (largest) image coordinate of the head top and the arm's sites over postures
/// that reach out in every direction, as the clip (4:3) frames them.
fn framing(model: &Model, camera: &str) -> f64 {
    let cam = model.camera_id(camera).unwrap();
    let reach: [Arm; 5] = [
        STAND_INIT,
        [0.0, 1.32645, 0.0, -0.0349066, 0.0, 1.0], // sideways
        [-2.08567, 0.2, 0.0, -0.0349066, 0.0, 1.0], // straight up
        [2.08567, 0.0, 0.0, -0.0349066, 0.0, 1.0], // down and back
        [-1.0, 1.32645, -1.5, -1.54462, 0.0, 1.0], // raised, elbow bent
    ];
    let mut worst = 0.0f64;
    for arm in reach {
        let data = pose(model, &posture([0.0; 2], arm, mirror(arm)));
        let head = data.body_xpos(model.body_id("Head").unwrap());
        let top = [head[0], head[1], head[2] + 0.115];
        let sites = ["l_gripper", "r_gripper", "l_wrist", "r_wrist"];
        let points = sites
            .iter()
            .map(|s| data.site_xpos(model.site_id(s).unwrap()));
        for p in points.chain([top]) {
            let (x, y) = project(&data, cam, 4.0 / 3.0, p).unwrap_or((f64::INFINITY, 0.0));
            worst = worst.max(x.abs()).max(y.abs());
        }
    }
    worst
}

#[test]
fn the_front_camera_frames_both_arms_and_the_head() {
    let model = load(UPPER);
    let worst = framing(&model, "front");
    eprintln!("front camera: farthest point at {worst:.3} of the half-image");
    assert!(
        worst < 0.9,
        "front camera: a hand or the head at {worst} of the half-image"
    );
    // negative control: the head camera does not see the arms
    assert!(framing(&model, "head_top") > 1.0);
}
