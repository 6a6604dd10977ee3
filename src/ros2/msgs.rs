//! The ROS 2 messages this crate writes and reads, as serde structs laid out field by field
//! as their `.msg` definitions (CDR follows the declaration order), with those definitions
//! (the `ros2msg` schema text MCAP channels carry: the message, then each nested type after a
//! line of `=` and `MSG: package/Type`).

use byteorder::LittleEndian;
use serde::{Deserialize, Serialize};

/// Schema name of the trajectory.
pub const JOINT_TRAJECTORY: &str = "trajectory_msgs/msg/JointTrajectory";
/// Schema name of the joint states.
pub const JOINT_STATE: &str = "sensor_msgs/msg/JointState";

const SEP: &str =
    "================================================================================\n";

/// `builtin_interfaces/Time`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Time {
    /// Seconds.
    pub sec: i32,
    /// Nanoseconds, 0..1e9.
    pub nanosec: u32,
}

impl Time {
    /// From seconds (>= 0).
    pub fn from_seconds(t: f64) -> Time {
        let ns = (t.max(0.0) * 1e9).round() as i64;
        Time {
            sec: (ns / 1_000_000_000) as i32,
            nanosec: (ns % 1_000_000_000) as u32,
        }
    }

    /// In nanoseconds.
    pub fn nanos(&self) -> i64 {
        self.sec as i64 * 1_000_000_000 + self.nanosec as i64
    }
}

/// `builtin_interfaces/Duration` (same layout as `Time`).
pub type Duration = Time;

/// `std_msgs/Header`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// Stamp.
    pub stamp: Time,
    /// Frame.
    pub frame_id: String,
}

/// `trajectory_msgs/JointTrajectoryPoint`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointTrajectoryPoint {
    /// Positions.
    pub positions: Vec<f64>,
    /// Velocities.
    pub velocities: Vec<f64>,
    /// Accelerations (empty).
    pub accelerations: Vec<f64>,
    /// Efforts (empty).
    pub effort: Vec<f64>,
    /// Time from the start of the trajectory.
    pub time_from_start: Duration,
}

/// `trajectory_msgs/JointTrajectory`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointTrajectory {
    /// Header.
    pub header: Header,
    /// Joint names.
    pub joint_names: Vec<String>,
    /// Points.
    pub points: Vec<JointTrajectoryPoint>,
}

/// `sensor_msgs/JointState`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointState {
    /// Header.
    pub header: Header,
    /// Joint names.
    pub name: Vec<String>,
    /// Positions.
    pub position: Vec<f64>,
    /// Velocities (may be empty).
    pub velocity: Vec<f64>,
    /// Efforts (may be empty).
    pub effort: Vec<f64>,
}

const HEADER_DEF: &str = "MSG: std_msgs/Header\n\
# Standard metadata for higher-level stamped data types.\n\
builtin_interfaces/Time stamp\n\
string frame_id\n";

const TIME_DEF: &str = "MSG: builtin_interfaces/Time\n\
int32 sec\n\
uint32 nanosec\n";

const DURATION_DEF: &str = "MSG: builtin_interfaces/Duration\n\
int32 sec\n\
uint32 nanosec\n";

/// The `ros2msg` text of `trajectory_msgs/msg/JointTrajectory` and its nested types.
pub static JOINT_TRAJECTORY_DEF: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
    format!(
        "std_msgs/Header header\nstring[] joint_names\nJointTrajectoryPoint[] points\n\
         {SEP}{HEADER_DEF}{SEP}{TIME_DEF}{SEP}MSG: trajectory_msgs/JointTrajectoryPoint\n\
         float64[] positions\nfloat64[] velocities\nfloat64[] accelerations\nfloat64[] effort\n\
         builtin_interfaces/Duration time_from_start\n{SEP}{DURATION_DEF}"
    )
});

/// The `ros2msg` text of `sensor_msgs/msg/JointState` and its nested types.
pub static JOINT_STATE_DEF: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
    format!(
        "std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\n\
         float64[] effort\n{SEP}{HEADER_DEF}{SEP}{TIME_DEF}"
    )
});

/// CDR_LE encapsulation header (representation identifier 0x0001, options 0).
const CDR_LE: [u8; 4] = [0, 1, 0, 0];
/// CDR_BE.
const CDR_BE: [u8; 4] = [0, 0, 0, 0];

/// A message serialised as ROS 2 does: the encapsulation header, then little-endian CDR.
pub fn encode<T: Serialize>(msg: &T) -> Result<Vec<u8>, crate::trajectory::ExportError> {
    let body = cdr_encoding::to_vec::<T, LittleEndian>(msg).map_err(|e| {
        crate::trajectory::ExportError::Bag {
            path: "MCAP output".into(),
            reason: format!("CDR encoding: {e}"),
        }
    })?;
    let mut v = Vec::with_capacity(body.len() + 4);
    v.extend_from_slice(&CDR_LE);
    v.extend(body);
    Ok(v)
}

/// A message decoded from ROS 2 CDR (either byte order), refused with a reason when the
/// header is unknown or the bytes do not hold the message.
pub fn decode<T: for<'de> Deserialize<'de>>(data: &[u8]) -> Result<T, String> {
    if data.len() < 4 {
        return Err(format!("{} bytes: too short for a CDR message", data.len()));
    }
    let (head, body) = data.split_at(4);
    let r = if head[..2] == CDR_LE[..2] {
        cdr_encoding::from_bytes::<T, LittleEndian>(body)
    } else if head[..2] == CDR_BE[..2] {
        cdr_encoding::from_bytes::<T, byteorder::BigEndian>(body)
    } else {
        return Err(format!(
            "encapsulation {:02x}{:02x}: expected plain CDR (0001 little-endian or 0000 big-endian)",
            head[0], head[1]
        ));
    };
    r.map(|(m, _)| m)
        .map_err(|e| format!("does not decode as the message ({e})"))
}
