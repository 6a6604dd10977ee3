//! ROS 2 interchange through MCAP files (the default storage of rosbag2, read by Foxglove):
//! ROS 2 messages encoded in CDR (little-endian, with the 4-byte encapsulation header), their
//! channels carrying the `ros2msg` schema text so that any ROS 2 tool can decode them.
//!
//! - [`trajectory_mcap`]: a `trajectory_msgs/msg/JointTrajectory` on `/joint_trajectory`,
//!   and optionally the executed motion as `sensor_msgs/msg/JointState` on `/joint_states`.
//! - [`read_joint_states`]: the `sensor_msgs/msg/JointState` messages of one topic of an MCAP
//!   file, checked; [`import`] turns them into demonstrations.

pub mod import;
pub mod msgs;

use std::collections::BTreeMap;
use std::io::Cursor;
use std::path::Path;

use crate::trajectory::{ExportError, Trajectory};
use msgs::{Duration, Header, JointState, JointTrajectory, JointTrajectoryPoint, Time};

/// Topic of the exported trajectory.
pub const TRAJECTORY_TOPIC: &str = "/joint_trajectory";
/// Topic of the executed motion, and the default topic of an import.
pub const JOINT_STATES_TOPIC: &str = "/joint_states";

fn bag_err(path: &str, reason: impl std::fmt::Display) -> ExportError {
    ExportError::Bag {
        path: path.to_string(),
        reason: reason.to_string(),
    }
}

fn nanos(t: f64) -> u64 {
    (t * 1e9).round().max(0.0) as u64
}

/// The MCAP bytes: one `JointTrajectory` (joint names; per point positions, velocities and
/// `time_from_start`) on [`TRAJECTORY_TOPIC`], stamped 0; with `executed`, one `JointState`
/// per recorded sample on [`JOINT_STATES_TOPIC`], stamped with the sample's time from the
/// start of the motion (header stamp, log and publish times alike).
pub fn trajectory_mcap(
    t: &Trajectory,
    executed: Option<&Trajectory>,
) -> Result<Vec<u8>, ExportError> {
    let e = |e: mcap::McapError| bag_err("MCAP output", e);
    let mut w = mcap::WriteOptions::new()
        .profile("ros2")
        .library(concat!("cosco-hsom ", env!("CARGO_PKG_VERSION")))
        .create(Cursor::new(Vec::new()))
        .map_err(e)?;
    // a channel of CDR messages of type `name` (its `ros2msg` text `def`) on `topic`
    let channel = |w: &mut mcap::Writer<_>, name, def: &str, topic| {
        let schema = w.add_schema(name, "ros2msg", def.as_bytes())?;
        w.add_channel(schema, topic, "cdr", &BTreeMap::new())
    };
    let trajectory = channel(
        &mut w,
        msgs::JOINT_TRAJECTORY,
        &msgs::JOINT_TRAJECTORY_DEF,
        TRAJECTORY_TOPIC,
    )
    .map_err(e)?;
    let velocities = t.velocities();
    let msg = JointTrajectory {
        header: Header {
            stamp: Time::default(),
            frame_id: String::new(),
        },
        joint_names: t.names.clone(),
        points: t
            .times
            .iter()
            .zip(&t.positions)
            .zip(velocities)
            .map(|((&time, p), v)| JointTrajectoryPoint {
                positions: p.clone(),
                velocities: v,
                accelerations: Vec::new(),
                effort: Vec::new(),
                time_from_start: Duration::from_seconds(time),
            })
            .collect(),
    };
    let header = |channel_id, sequence, ns| mcap::records::MessageHeader {
        channel_id,
        sequence,
        log_time: ns,
        publish_time: ns,
    };
    w.write_to_known_channel(&header(trajectory, 0, 0), &msgs::encode(&msg)?)
        .map_err(e)?;
    if let Some(x) = executed {
        let states = &msgs::JOINT_STATE_DEF;
        let channel = channel(&mut w, msgs::JOINT_STATE, states, JOINT_STATES_TOPIC).map_err(e)?;
        for (i, (&time, p)) in x.times.iter().zip(&x.positions).enumerate() {
            let msg = JointState {
                header: Header {
                    stamp: Time::from_seconds(time),
                    frame_id: String::new(),
                },
                name: x.names.clone(),
                position: p.clone(),
                velocity: Vec::new(),
                effort: Vec::new(),
            };
            w.write_to_known_channel(
                &header(channel, i as u32, nanos(time)),
                &msgs::encode(&msg)?,
            )
            .map_err(e)?;
        }
    }
    w.finish().map_err(e)?;
    Ok(w.into_inner().into_inner())
}

/// One `sensor_msgs/msg/JointState` read from a bag.
#[derive(Debug, Clone, PartialEq)]
pub struct StampedJoints {
    /// Header stamp, ns.
    pub stamp_ns: i64,
    /// Joint names.
    pub names: Vec<String>,
    /// Positions, one per name.
    pub positions: Vec<f64>,
}

/// Every `sensor_msgs/msg/JointState` on `topic` of the MCAP file `path`, in file order.
/// Refused with the file named: a file that is not MCAP or is truncated, a topic absent
/// (the topics present listed) or of another type, a message that does not decode, or no
/// message at all.
pub fn read_joint_states(path: &Path, topic: &str) -> Result<Vec<StampedJoints>, ExportError> {
    let p = path.display().to_string();
    let bytes =
        std::fs::read(path).map_err(|e| bag_err(&p, format!("cannot read the bag: {e}")))?;
    if bytes.is_empty() {
        return Err(bag_err(
            &p,
            "the file is empty; expected an MCAP file (ROS 2 bag)",
        ));
    }
    if !bytes.starts_with(mcap::MAGIC) {
        return Err(bag_err(
            &p,
            "not a readable MCAP file (it does not start with MCAP's magic bytes); expected a ROS 2 bag in MCAP storage",
        ));
    }
    let stream = mcap::MessageStream::new(&bytes)
        .map_err(|e| bag_err(&p, format!("not a readable MCAP file ({e})")))?;
    let mut topics: BTreeMap<String, String> = BTreeMap::new();
    let mut out = Vec::new();
    for (i, m) in stream.enumerate() {
        let m = m.map_err(|e| {
            bag_err(
                &p,
                format!("the MCAP file is damaged or truncated after {i} messages ({e})"),
            )
        })?;
        let schema = m.channel.schema.as_ref().map_or("", |s| s.name.as_str());
        topics
            .entry(m.channel.topic.clone())
            .or_insert_with(|| schema.to_string());
        if m.channel.topic != topic {
            continue;
        }
        if schema != msgs::JOINT_STATE || m.channel.message_encoding != "cdr" {
            return Err(bag_err(
                &p,
                format!(
                    "topic {topic} carries `{schema}` encoded as `{}`; expected {} in CDR",
                    m.channel.message_encoding,
                    msgs::JOINT_STATE
                ),
            ));
        }
        let js: JointState = msgs::decode(&m.data)
            .map_err(|e| bag_err(&p, format!("message {} on {topic}: {e}", out.len())))?;
        if js.position.len() != js.name.len() {
            return Err(bag_err(
                &p,
                format!(
                    "message {} on {topic}: {} names but {} positions",
                    out.len(),
                    js.name.len(),
                    js.position.len()
                ),
            ));
        }
        out.push(StampedJoints {
            stamp_ns: js.header.stamp.nanos(),
            names: js.name,
            positions: js.position,
        });
    }
    if out.is_empty() {
        let present: Vec<String> = topics.iter().map(|(t, s)| format!("{t} ({s})")).collect();
        return Err(bag_err(
            &p,
            if present.is_empty() {
                format!(
                    "no message at all (expected {} on {topic})",
                    msgs::JOINT_STATE
                )
            } else {
                format!(
                    "no message on topic {topic}; the bag has: {}",
                    present.join(", ")
                )
            },
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests;
