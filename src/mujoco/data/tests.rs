use super::*;

/// A fixed box (half height 0.1, top at z = 0.1) and a free ball of radius 0.05 above it; a
/// second ball that never collides (contype 0); a "probe" sphere with a margin and a gap.
const SCENE: &str = r#"
<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <body name="table">
      <geom name="top" type="box" size="0.3 0.3 0.1"/>
    </body>
    <body name="ball" pos="0 0 0.14">
      <freejoint/>
      <geom name="ball_geom" type="sphere" size="0.05" mass="0.1"/>
    </body>
    <body name="ghost" pos="0.1 0 0.12">
      <freejoint/>
      <geom name="ghost_geom" type="sphere" size="0.05" mass="0.1" contype="0" conaffinity="0"/>
    </body>
    <body name="probe" pos="-0.2 0 0.17">
      <freejoint/>
      <geom name="probe_geom" type="sphere" size="0.05" mass="0.1" margin="0.04" gap="0.04"/>
    </body>
  </worldbody>
  <keyframe>
    <key name="lifted" qpos="0 0 0.5 1 0 0 0  0.1 0 0.12 1 0 0 0  -0.2 0 0.17 1 0 0 0"/>
  </keyframe>
</mujoco>"#;

#[test]
fn contacts_name_geoms_bodies_depth_and_position() {
    let model = Model::from_xml_str(SCENE).unwrap();
    let mut data = Data::new(&model).unwrap();
    data.forward().unwrap();
    let active = data.contacts();
    // the ball's bottom is at 0.09, 1 cm into the table; the ghost never collides; the
    // probe's bottom is 2 cm above the table, within its margin: detected, not active
    assert_eq!(active.len(), 1, "{active:?}");
    let c = &active[0];
    assert!(c.between("table", "ball") && c.between("ball", "table"));
    assert!(c.touches("ball") && !c.touches("ghost"));
    let names: Vec<_> = c.geom_name.iter().flatten().map(String::as_str).collect();
    assert!(
        names.contains(&"top") && names.contains(&"ball_geom"),
        "{names:?}"
    );
    assert_eq!(c.geom.map(|g| model.geom_body(g)), c.body);
    assert!((c.dist + 0.01).abs() < 1e-9, "penetration depth {}", c.dist);
    // midway between the surfaces: z = (0.09 + 0.1) / 2
    assert!(
        (c.pos[0]).abs() < 1e-9 && (c.pos[2] - 0.095).abs() < 1e-9,
        "{:?}",
        c.pos
    );
    assert!((c.normal[2].abs() - 1.0).abs() < 1e-9, "{:?}", c.normal);
    assert!(c.active);

    let detected = data.detected_contacts();
    assert_eq!(detected.len(), 2, "{detected:?}");
    let probe = detected.iter().find(|c| c.touches("probe")).unwrap();
    assert!(!probe.active);
    assert!((probe.dist - 0.02).abs() < 1e-9, "clearance {}", probe.dist);
}

#[test]
fn contacts_follow_the_state() {
    let model = Model::from_xml_str(SCENE).unwrap();
    let mut data = Data::new(&model).unwrap();
    // lift the ball (qpos: x y z then the quaternion) clear of the table
    data.qpos_mut()[2] = 0.5;
    data.forward().unwrap();
    assert!(data.contacts().iter().all(|c| !c.touches("ball")));
    // a fresh state reports nothing before the first forward
    let fresh = Data::new(&model).unwrap();
    assert!(fresh.contacts().is_empty());
    // after steps, the falling ball meets the table
    data.qpos_mut()[2] = 0.16;
    data.forward().unwrap();
    for _ in 0..200 {
        data.step().unwrap();
    }
    let c = data.contacts();
    assert!(c.iter().any(|c| c.between("ball", "table")), "{c:?}");
    assert!(c.iter().all(|c| c.dist < 0.0 && c.dist > -0.01), "{c:?}");
}

#[test]
fn geom_and_inertia_lookups() {
    let model = Model::from_xml_str(SCENE).unwrap();
    assert_eq!(model.ngeom(), 4);
    let g = model.geom_id("ball_geom").unwrap();
    assert_eq!(model.geom_name(g).as_deref(), Some("ball_geom"));
    assert_eq!(model.geom_body(g), model.body_id("ball").unwrap());
    assert_eq!(model.geom_id("nope"), None);
    assert_eq!(model.geom_name(99), None);
    let b = model.body_id("ball").unwrap();
    // a solid sphere: I = 2/5 m r^2 about its centre, on any axes
    let i = 0.4 * 0.1 * 0.05 * 0.05;
    for v in model.body_inertia(b) {
        assert!((v - i).abs() < 1e-12, "{v} vs {i}");
    }
    assert_eq!(model.body_ipos(b), [0.0; 3]);
    assert_eq!(model.body_iquat(b), [1.0, 0.0, 0.0, 0.0]);
}

#[test]
fn keyframes_by_name_and_reset() {
    let model = Model::from_xml_str(SCENE).unwrap();
    assert_eq!(model.nkey(), 1);
    let k = model.key_id("lifted").unwrap();
    assert_eq!(model.key_id("nope"), None);
    assert_eq!(model.key_qpos(k).len(), model.nq());
    assert_eq!(model.key_qpos(k)[2], 0.5);
    assert!(model.key_ctrl(k).is_empty());
    let mut data = Data::new(&model).unwrap();
    data.forward().unwrap();
    assert!(data.contacts().iter().any(|c| c.touches("ball")));
    data.reset_to_key(k);
    data.forward().unwrap();
    assert_eq!(data.qpos()[2], 0.5);
    assert!(data.contacts().iter().all(|c| !c.touches("ball")));
}
