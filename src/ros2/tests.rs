use super::*;

fn traj() -> Trajectory {
    let names = vec!["a".to_string(), "b".to_string()];
    let times = vec![0.0, 0.025, 0.05, 0.075];
    let positions = vec![
        vec![0.0, 1.0],
        vec![0.1, 0.9],
        vec![0.3, 0.8],
        vec![0.4, 0.8],
    ];
    Trajectory::new(names, times, positions).unwrap()
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

#[test]
fn joint_states_read_back_and_every_damage_is_named() {
    let t = traj();
    let bytes = trajectory_mcap(&t, Some(&t)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let ok = write(dir.path(), "ok.mcap", &bytes);
    let js = read_joint_states(&ok, JOINT_STATES_TOPIC).unwrap();
    assert_eq!(js.len(), 4);
    assert_eq!(js[2].positions, t.positions[2]);
    assert_eq!(js[3].stamp_ns, 75_000_000);
    assert_eq!(js[0].names, t.names);
    // the trajectory topic is another type
    let e = read_joint_states(&ok, TRAJECTORY_TOPIC)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("ok.mcap") && e.contains(msgs::JOINT_TRAJECTORY),
        "{e}"
    );
    // a topic that is not there: the topics present are listed
    let e = read_joint_states(&ok, "/nope").unwrap_err().to_string();
    assert!(
        e.contains("no message on topic /nope") && e.contains("/joint_states"),
        "{e}"
    );
    // truncated, empty, not MCAP
    let cut = write(dir.path(), "cut.mcap", &bytes[..bytes.len() / 2]);
    let e = read_joint_states(&cut, JOINT_STATES_TOPIC)
        .unwrap_err()
        .to_string();
    assert!(e.contains("cut.mcap") && e.contains("truncated"), "{e}");
    let empty = write(dir.path(), "empty.mcap", b"");
    let e = read_joint_states(&empty, JOINT_STATES_TOPIC)
        .unwrap_err()
        .to_string();
    assert!(e.contains("empty"), "{e}");
    let text = write(dir.path(), "t.mcap", b"time,a\n0,1\n");
    let e = read_joint_states(&text, JOINT_STATES_TOPIC)
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a readable MCAP file"), "{e}");
    // a message cut inside its CDR body
    let short = msgs::decode::<msgs::JointState>(&msgs::encode(&msgs::Header::default()).unwrap());
    assert!(short.is_err());
}

#[test]
fn the_trajectory_message_holds_the_points_with_their_times_and_velocities() {
    let t = traj();
    let bytes = trajectory_mcap(&t, None).unwrap();
    let mut n = 0;
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        assert_eq!(m.channel.topic, TRAJECTORY_TOPIC);
        let schema = m.channel.schema.as_ref().unwrap();
        assert_eq!(schema.encoding, "ros2msg");
        assert!(std::str::from_utf8(&schema.data)
            .unwrap()
            .contains("MSG: trajectory_msgs/JointTrajectoryPoint"));
        let jt: msgs::JointTrajectory = msgs::decode(&m.data).unwrap();
        assert_eq!(jt.joint_names, t.names);
        assert_eq!(jt.points[2].positions, t.positions[2]);
        assert_eq!(
            jt.points[3].time_from_start,
            msgs::Time {
                sec: 0,
                nanosec: 75_000_000
            }
        );
        assert!((jt.points[1].velocities[0] - 6.0).abs() < 1e-12);
        assert_eq!(jt.points[3].velocities, vec![0.0, 0.0]);
        n += 1;
    }
    assert_eq!(n, 1);
}
