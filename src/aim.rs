//! A gesture aimed at a point in space: pointing (the ray from the shoulder through the
//! gripper site passes through the target) and gaze (the top camera's optical axis passes
//! through it), through the Nao's kinematics as `models/nao_upper_body.xml` writes them (the
//! left arm's model shares its frame: the torso's, x forward, y to the robot's left, z up),
//! solved within the joint ranges nearest a held posture; and the via-points that carry a
//! reproduction's held part through the solved posture (docs/ALGORITHM.md, "Aiming").

use nalgebra::{DMatrix, DVector, Rotation3, Vector3};

use crate::condition::{Conditions, ViaPoint};
use crate::robot::Robot;

#[cfg(test)]
mod tests;

/// A point in the torso frame, metres.
pub type Point = [f64; 3];

/// One of the Nao's arms.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Arm {
    /// The left arm (`l_gripper`).
    Left,
    /// The right arm (`r_gripper`).
    Right,
}

impl Arm {
    /// `left` or `right`.
    pub fn name(self) -> &'static str {
        match self {
            Arm::Left => "left",
            Arm::Right => "right",
        }
    }

    /// +1 on the left, -1 on the right (the sign of the arm's y offsets).
    fn side(self) -> f64 {
        match self {
            Arm::Left => 1.0,
            Arm::Right => -1.0,
        }
    }

    /// Where the pointing ray starts: the ShoulderPitch joint's origin.
    pub fn shoulder(self) -> Point {
        [0.0, 0.098 * self.side(), 0.100]
    }

    /// The index of the arm's ShoulderPitch in `robot`'s postures, if `robot` has the arm.
    pub fn offset(self, robot: Robot) -> Option<usize> {
        match (robot, self) {
            (Robot::LeftArm, Arm::Left) => Some(0),
            (Robot::LeftArm, Arm::Right) => None,
            (Robot::UpperBody, Arm::Left) => Some(2),
            (Robot::UpperBody, Arm::Right) => Some(8),
        }
    }

    /// The gripper site (`l_gripper` / `r_gripper`) at the arm's joints `q` (ShoulderPitch,
    /// ShoulderRoll, ElbowYaw, ElbowRoll, WristYaw; the hand does not move it).
    pub fn gripper(self, q: &[f64]) -> Point {
        let s = self.side();
        let rot = |axis: Vector3<f64>, a: f64| {
            Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), a)
        };
        let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
        let hand_z = if s > 0.0 { -0.01231 } else { -0.01213 };
        let shoulder = rot(y, q[0]) * rot(z, q[1]);
        let elbow = shoulder * rot(x, q[2]) * rot(z, q[3]);
        let wrist = elbow * rot(x, q[4]);
        let p = Vector3::from(self.shoulder())
            + shoulder * Vector3::new(0.105, 0.015 * s, 0.0)
            + elbow * Vector3::new(0.05595, 0.0, 0.0)
            + wrist * Vector3::new(0.05775, 0.0, hand_z);
        [p.x, p.y, p.z]
    }

    /// The unit direction of the pointing ray at the arm's joints `q`.
    pub fn pointing(self, q: &[f64]) -> Point {
        let d = Vector3::from(self.gripper(q)) - Vector3::from(self.shoulder());
        let d = d.normalize();
        [d.x, d.y, d.z]
    }
}

/// The top camera (site `camera_top`) at the head's joints (HeadYaw, HeadPitch): its origin
/// and the unit direction of its optical axis.
pub fn camera(head: &[f64]) -> (Point, Point) {
    let rot = |axis: Vector3<f64>, a: f64| {
        Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), a)
    };
    let r = rot(Vector3::z(), head[0]) * rot(Vector3::y(), head[1]);
    let o = Vector3::new(0.0, 0.0, 0.1265) + r * Vector3::new(0.05871, 0.0, 0.06364);
    let d = r * rot(Vector3::y(), 0.0209435) * Vector3::x();
    ([o.x, o.y, o.z], [d.x, d.y, d.z])
}

/// The angle (rad) between the ray from `origin` along the unit `direction` and the
/// direction from `origin` to `target`.
pub fn angle_to(origin: Point, direction: Point, target: Point) -> f64 {
    let to = Vector3::from(target) - Vector3::from(origin);
    let cos = Vector3::from(direction).dot(&to) / to.norm().max(f64::MIN_POSITIVE);
    cos.clamp(-1.0, 1.0).acos()
}

/// A direction's azimuth (from x towards y, the robot's left) and elevation, degrees.
pub fn azimuth_elevation(d: Point) -> (f64, f64) {
    let horizontal = d[0].hypot(d[1]);
    (
        d[1].atan2(d[0]).to_degrees(),
        d[2].atan2(horizontal).to_degrees(),
    )
}

/// What a reproduction is aimed at.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Aim {
    /// The point the pointing arm's ray passes through during the held part.
    pub point_at: Option<Point>,
    /// The point the top camera looks at during the held part (the upper body).
    pub look_at: Option<Point>,
}

impl Aim {
    /// Neither a point nor a gaze.
    pub fn is_empty(&self) -> bool {
        self.point_at.is_none() && self.look_at.is_none()
    }
}

/// `X,Y,Z` (`--point-at`, `--look-at`): a point in metres in the torso frame.
pub fn parse_point(text: &str) -> Result<Point, String> {
    let values = text.parse::<crate::condition::PostureArg>()?.0;
    <[f64; 3]>::try_from(values.as_slice()).map_err(|_| {
        format!(
            "'{text}' has {} values: need X,Y,Z (metres, in the torso frame: x forward, y to the robot's left, z up)",
            values.len()
        )
    })
}

/// A target that cannot be aimed at, naming what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AimError {
    /// Beyond the joint ranges: the nearest direction that can be reached.
    #[error("{what} cannot aim at ({x:.3}, {y:.3}, {z:.3}) m within its joint ranges: the closest direction it reaches is azimuth {azimuth:.1} deg, elevation {elevation:.1} deg ({dx:.3}, {dy:.3}, {dz:.3}), {off:.1} deg from the target's (azimuth {target_azimuth:.1}, elevation {target_elevation:.1})", x = target[0], y = target[1], z = target[2], dx = closest[0], dy = closest[1], dz = closest[2])]
    Unreachable {
        /// `the left arm` or `the head`.
        what: String,
        /// The target.
        target: Point,
        /// The unit direction nearest the target's that the joints reach.
        closest: Point,
        /// Its azimuth, degrees.
        azimuth: f64,
        /// Its elevation, degrees.
        elevation: f64,
        /// The target's azimuth from the ray's origin, degrees.
        target_azimuth: f64,
        /// Its elevation, degrees.
        target_elevation: f64,
        /// The angle between the two, degrees.
        off: f64,
    },
    /// Too near the ray's origin to be aimed at.
    #[error("{what}: the target ({x:.3}, {y:.3}, {z:.3}) m is {distance:.3} m from {origin}; allowed from {minimum} m", x = target[0], y = target[1], z = target[2])]
    TooNear {
        /// `--point-at` or `--look-at`.
        what: String,
        /// The target.
        target: Point,
        /// Its distance from the origin.
        distance: f64,
        /// The shoulder or the camera.
        origin: String,
        /// The least distance.
        minimum: f64,
    },
    /// Farther than [`MAX_DISTANCE`] from the torso's origin.
    #[error("{what}: the target ({x}, {y}, {z}) m is {distance:.0} m away; allowed up to {MAX_DISTANCE} m (a direction that far off is the same from a nearer point on the line)", x = target[0], y = target[1], z = target[2])]
    TooFar {
        /// `--point-at` or `--look-at`.
        what: String,
        /// The target.
        target: Point,
        /// Its distance from the torso's origin.
        distance: f64,
    },
    /// A value that is not a finite number.
    #[error("{what}: ({x}, {y}, {z}) is not a point: need three finite numbers (metres)", x = target[0], y = target[1], z = target[2])]
    NonFinite {
        /// `--point-at` or `--look-at`.
        what: String,
        /// The values.
        target: Point,
    },
    /// A model whose variables are not a robot's joints, or a robot without the part.
    #[error("{0}")]
    Unsupported(String),
}

/// The least distance from the shoulder of a target to point at (beyond the outstretched
/// hand, about 0.22 m), metres.
pub const MIN_POINT_DISTANCE: f64 = 0.3;
/// The least distance from the camera of a target to look at, metres.
pub const MIN_LOOK_DISTANCE: f64 = 0.1;
/// How far inside its range a solved joint stays, rad (as the demonstrator's key poses).
pub const RANGE_MARGIN: f64 = 0.02;
/// The largest angle between the aimed ray and the target a solution may leave, rad: above
/// it the target is refused as unreachable.
const SOLVED: f64 = 1e-6;

/// The joints a solver moves, the rest of the posture fixed: an origin and unit direction
/// at each value of those joints.
struct Chain<'a> {
    ray: &'a dyn Fn(&[f64]) -> (Point, Point),
    ranges: Vec<(f64, f64)>,
}

impl Chain<'_> {
    /// The ray's residual against `target`: its direction minus the unit direction from its
    /// origin to the target.
    fn residual(&self, q: &[f64], target: Point) -> DVector<f64> {
        let (o, d) = (self.ray)(q);
        let to = (Vector3::from(target) - Vector3::from(o)).normalize();
        DVector::from_iterator(3, (0..3).map(|i| d[i] - to[i]))
    }

    fn off(&self, q: &[f64], target: Point) -> f64 {
        let (o, d) = (self.ray)(q);
        angle_to(o, d, target)
    }

    fn clamp(&self, q: &mut [f64]) {
        for (v, (lo, hi)) in q.iter_mut().zip(&self.ranges) {
            *v = v.clamp(lo + RANGE_MARGIN, hi - RANGE_MARGIN);
        }
    }

    /// Damped Gauss-Newton on the residual from `start`, each step's null-space part pulled
    /// towards `preferred` (`pull` of the way) so that of the solutions it finds one near it;
    /// the last third without the pull, to converge.
    fn descend(&self, start: &[f64], preferred: &[f64], target: Point, pull: f64) -> Vec<f64> {
        let k = start.len();
        let mut q = start.to_vec();
        self.clamp(&mut q);
        let iterations = 300;
        for it in 0..iterations {
            let r = self.residual(&q, target);
            let mut jac = DMatrix::zeros(3, k);
            for j in 0..k {
                let mut p = q.clone();
                let h = 1e-7;
                p[j] += h;
                let rp = self.residual(&p, target);
                jac.set_column(j, &((rp - &r) / h));
            }
            let damping = 1e-6;
            let jjt = &jac * jac.transpose() + DMatrix::identity(3, 3) * damping;
            let Some(inv) = jjt.try_inverse() else { break };
            let pinv = jac.transpose() * inv;
            let mut step = -(&pinv * &r);
            if it < iterations * 2 / 3 && pull > 0.0 {
                let toward =
                    DVector::from_iterator(k, preferred.iter().zip(&q).map(|(p, v)| p - v));
                step += (DMatrix::identity(k, k) - &pinv * &jac) * toward * pull;
            }
            let norm = step.norm();
            if norm > 0.2 {
                step *= 0.2 / norm;
            }
            for (v, s) in q.iter_mut().zip(step.iter()) {
                *v += s;
            }
            self.clamp(&mut q);
            if it >= iterations * 2 / 3 && norm < 1e-13 {
                break;
            }
        }
        q
    }

    /// The joints nearest `preferred` that aim the ray at `target`; or, when none does, the
    /// joints whose ray comes closest (and its angle to the target, rad).
    fn solve(&self, preferred: &[f64], target: Point) -> (Vec<f64>, f64) {
        let q = self.descend(preferred, preferred, target, 0.5);
        let off = self.off(&q, target);
        if off <= SOLVED {
            return (q, off);
        }
        // from a grid of starts over the first two joints, the ray nearest the target
        let mut best = (q, off);
        for a in 0..7 {
            for b in 0..7 {
                let mut start = preferred.to_vec();
                for (j, f) in [(0, a), (1, b)] {
                    let (lo, hi) = self.ranges[j];
                    start[j] = lo + (hi - lo) * f as f64 / 6.0;
                }
                let q = self.descend(&start, preferred, target, 0.0);
                let off = self.off(&q, target);
                if off < best.1 - 1e-12 {
                    best = (q, off);
                }
            }
        }
        if best.1 <= SOLVED {
            // reached: from there, nearest the preferred posture again
            let q = self.descend(&best.0, preferred, target, 0.5);
            let off = self.off(&q, target);
            if off <= SOLVED {
                return (q, off);
            }
        }
        best
    }
}

/// The farthest target, metres from the torso's origin.
pub const MAX_DISTANCE: f64 = 1000.0;

/// `target` is a point of finite values within [`MAX_DISTANCE`].
fn finite(what: &str, target: Point) -> Result<(), AimError> {
    if !target.iter().all(|v| v.is_finite()) {
        return Err(AimError::NonFinite {
            what: what.into(),
            target,
        });
    }
    let distance = target.iter().map(|v| v * v).sum::<f64>().sqrt();
    if distance > MAX_DISTANCE {
        return Err(AimError::TooFar {
            what: what.into(),
            target,
            distance,
        });
    }
    Ok(())
}

fn unreachable(what: String, origin: Point, closest: Point, target: Point, off: f64) -> AimError {
    let (azimuth, elevation) = azimuth_elevation(closest);
    let to = Vector3::from(target) - Vector3::from(origin);
    let (target_azimuth, target_elevation) = azimuth_elevation([to.x, to.y, to.z]);
    AimError::Unreachable {
        what,
        target,
        closest,
        azimuth,
        elevation,
        target_azimuth,
        target_elevation,
        off: off.to_degrees(),
    }
}

/// `arm`'s joints of `posture` (a posture of `robot`) changed so that the arm points at
/// `target`: ShoulderPitch, ShoulderRoll, ElbowYaw and ElbowRoll, nearest their values in
/// `posture` and within the joint ranges (by [`RANGE_MARGIN`]); WristYaw and the hand kept.
pub fn point(robot: Robot, arm: Arm, posture: &[f64], target: Point) -> Result<Vec<f64>, AimError> {
    finite("--point-at", target)?;
    let at = arm.offset(robot).ok_or_else(|| {
        AimError::Unsupported(format!("the {} has no {} arm", robot.phrase(), arm.name()))
    })?;
    let distance = (Vector3::from(target) - Vector3::from(arm.shoulder())).norm();
    if distance < MIN_POINT_DISTANCE {
        return Err(AimError::TooNear {
            what: "--point-at".into(),
            target,
            distance,
            origin: format!("the {} shoulder", arm.name()),
            minimum: MIN_POINT_DISTANCE,
        });
    }
    let wrist = posture[at + 4];
    let ray = move |q: &[f64]| {
        (
            arm.shoulder(),
            arm.pointing(&[q[0], q[1], q[2], q[3], wrist]),
        )
    };
    let chain = Chain {
        ray: &ray,
        ranges: robot.ranges()[at..at + 4].to_vec(),
    };
    let (q, off) = chain.solve(&posture[at..at + 4], target);
    if off > SOLVED {
        let (_, closest) = ray(&q);
        return Err(unreachable(
            format!("the {} arm", arm.name()),
            arm.shoulder(),
            closest,
            target,
            off,
        ));
    }
    let mut out = posture.to_vec();
    out[at..at + 4].copy_from_slice(&q);
    Ok(out)
}

/// The head's joints of `posture` (an upper-body posture) changed so that the top camera
/// looks at `target`, nearest their values in `posture` and within their ranges.
pub fn look(robot: Robot, posture: &[f64], target: Point) -> Result<Vec<f64>, AimError> {
    finite("--look-at", target)?;
    if robot != Robot::UpperBody {
        return Err(AimError::Unsupported(format!(
            "--look-at turns the head: the {} has none (give --robot upper-body)",
            robot.phrase()
        )));
    }
    let (origin, _) = camera(&posture[..2]);
    let distance = (Vector3::from(target) - Vector3::from(origin)).norm();
    if distance < MIN_LOOK_DISTANCE {
        return Err(AimError::TooNear {
            what: "--look-at".into(),
            target,
            distance,
            origin: "the top camera".into(),
            minimum: MIN_LOOK_DISTANCE,
        });
    }
    let ray = |q: &[f64]| camera(q);
    let chain = Chain {
        ray: &ray,
        ranges: robot.ranges()[..2].to_vec(),
    };
    let (q, off) = chain.solve(&posture[..2], target);
    if off > SOLVED {
        let (o, closest) = camera(&q);
        return Err(unreachable("the head".into(), o, closest, target, off));
    }
    let mut out = posture.to_vec();
    out[..2].copy_from_slice(&q);
    Ok(out)
}

/// The arm of `robot` that points in `rows` (a reproduction or demonstration of its joints):
/// the left arm's own; on the upper body, the arm whose gripper goes farthest from where it
/// starts.
pub fn pointing_arm(robot: Robot, rows: &[Vec<f64>]) -> Arm {
    if robot == Robot::LeftArm {
        return Arm::Left;
    }
    let reach = |arm: Arm| {
        let at = arm.offset(robot).expect("the upper body has both arms");
        let g = |r: &Vec<f64>| Vector3::from(arm.gripper(&r[at..at + 5]));
        let first = rows.first().map(g).unwrap_or_default();
        rows.iter()
            .map(|r| (g(r) - first).norm())
            .fold(0.0, f64::max)
    };
    if reach(Arm::Right) > reach(Arm::Left) {
        Arm::Right
    } else {
        Arm::Left
    }
}

/// The held part of `rows` in the variables `joints`: the rows about the apex (the row
/// farthest from the first) that stay within [`HOLD_BAND`] of the apex's distance from the
/// first row, first and last row inclusive.
pub fn held_span(rows: &[Vec<f64>], joints: std::ops::Range<usize>) -> (usize, usize) {
    let dist = |a: &[f64], b: &[f64]| -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let part = |r: &Vec<f64>| r[joints.clone()].to_vec();
    let Some(first) = rows.first().map(part) else {
        return (0, 0);
    };
    let (apex, reach) = (rows.iter().enumerate())
        .map(|(i, r)| (i, dist(&part(r), &first)))
        .fold((0, 0.0), |b, c| if c.1 > b.1 { c } else { b });
    let top = part(&rows[apex]);
    let near = |i: usize| dist(&part(&rows[i]), &top) <= HOLD_BAND * reach;
    let mut start = apex;
    while start > 0 && near(start - 1) {
        start -= 1;
    }
    let mut end = apex;
    while end + 1 < rows.len() && near(end + 1) {
        end += 1;
    }
    (start, end)
}

/// The mean posture of `rows` over `span` (first and last row inclusive, as [`held_span`]
/// gives it).
pub fn held_posture(rows: &[Vec<f64>], span: (usize, usize)) -> Vec<f64> {
    let part = &rows[span.0..=span.1];
    let count = part.len() as f64;
    (0..rows[0].len())
        .map(|j| part.iter().map(|r| r[j]).sum::<f64>() / count)
        .collect()
}

/// How near the apex a row of the held part stays, as a fraction of the apex's distance from
/// the first row.
pub const HOLD_BAND: f64 = 0.05;

/// How many rows apart the via-points along a held part are (0.2 s at 40 Hz).
const VIA_EVERY: usize = 8;

/// A reproduction's aim, solved: what [`via_points`] carries it through.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Aimed {
    /// The arm that points (when pointing).
    pub arm: Option<Arm>,
    /// The held part, first and last row.
    pub span: (usize, usize),
    /// The held posture of the reproduction (the mean of its held part).
    pub held: Vec<f64>,
    /// The held posture aimed: the pointing arm's and the head's joints solved.
    pub posture: Vec<f64>,
}

/// Solve `aim` for `rows` (a reproduction of `robot`'s joints, unconditioned): the held
/// part ([`held_span`], of the pointing arm's joints, or every joint but the head's when only
/// looking), its mean posture, and that posture aimed ([`point`], [`look`]).
pub fn solve(robot: Robot, rows: &[Vec<f64>], aim: &Aim) -> Result<Aimed, AimError> {
    if rows.len() < 2 {
        return Err(AimError::Unsupported(
            "the reproduction has fewer than 2 rows: nothing to aim".into(),
        ));
    }
    let arm = aim.point_at.map(|_| pointing_arm(robot, rows));
    let joints = match arm {
        Some(arm) => {
            let at = arm.offset(robot).expect("the pointing arm is the robot's");
            at..at + 4
        }
        None if robot == Robot::UpperBody => 2..rows[0].len(),
        None => 0..rows[0].len(),
    };
    let span = held_span(rows, joints);
    let held = held_posture(rows, span);
    let mut posture = held.clone();
    if let (Some(arm), Some(target)) = (arm, aim.point_at) {
        posture = point(robot, arm, &posture, target)?;
    }
    if let Some(target) = aim.look_at {
        posture = look(robot, &posture, target)?;
    }
    Ok(Aimed {
        arm,
        span,
        held,
        posture,
    })
}

/// The via-points that carry `rows` through `aimed` over its held part: every
/// [`VIA_EVERY`] rows from its first to its last, each the row with the aimed joints (the
/// pointing arm's ShoulderPitch to ElbowRoll, the head's when looking) set to the aimed
/// posture's, the other joints as the row has them.
pub fn via_points(robot: Robot, rows: &[Vec<f64>], aimed: &Aimed, aim: &Aim) -> Vec<ViaPoint> {
    let aimed_joints = aimed_joints(robot, aimed.arm, aim);
    let last = (rows.len() - 1) as f64;
    let (a, b) = aimed.span;
    let mut at: Vec<usize> = (a..=b).step_by(VIA_EVERY).collect();
    if at.last() != Some(&b) {
        at.push(b);
    }
    at.into_iter()
        .filter(|&i| i > 0)
        .map(|i| {
            let mut posture = rows[i].clone();
            for &j in &aimed_joints {
                posture[j] = aimed.posture[j];
            }
            ViaPoint {
                phase: i as f64 / last,
                posture,
            }
        })
        .collect()
}

/// The joints an aim sets: the pointing arm's ShoulderPitch to ElbowRoll, the head's when
/// looking.
fn aimed_joints(robot: Robot, arm: Option<Arm>, aim: &Aim) -> Vec<usize> {
    let mut joints: Vec<usize> = Vec::new();
    if let Some(at) = arm
        .filter(|_| aim.point_at.is_some())
        .and_then(|a| a.offset(robot))
    {
        joints.extend(at..at + 4);
    }
    if aim.look_at.is_some() {
        joints.extend(0..2);
    }
    joints
}

/// A reproduction in the loop aimed at a target that may move: the user's own via-points,
/// the aim's, and what was solved; [`Aiming::retarget`] solves a new target from the same
/// held posture and gives the via-points to follow from then on.
#[derive(Debug, Clone)]
pub struct Aiming {
    robot: Robot,
    aim: Aim,
    solved: Aimed,
    own: Vec<ViaPoint>,
    via: Vec<ViaPoint>,
}

impl Aiming {
    /// `rows` (a reproduction of `robot`'s joints through `conditions`) aimed at `aim`
    /// ([`aim_conditions`]): the conditions to start the stepper with, and the aiming.
    pub fn new(
        robot: Robot,
        rows: &[Vec<f64>],
        conditions: &Conditions,
        aim: &Aim,
    ) -> Result<(Conditions, Aiming), AimError> {
        let (aimed, solved) = aim_conditions(robot, rows, conditions, aim)?;
        let via = aimed.via[conditions.via.len()..].to_vec();
        let aiming = Aiming {
            robot,
            aim: *aim,
            solved,
            own: conditions.via.clone(),
            via,
        };
        Ok((aimed, aiming))
    }

    /// What it is aimed at.
    pub fn aim(&self) -> Aim {
        self.aim
    }

    /// What was solved for the current aim.
    pub fn solved(&self) -> &Aimed {
        &self.solved
    }

    /// Every via-point to follow: the user's, then the aim's.
    pub fn via(&self) -> Vec<ViaPoint> {
        self.own.iter().chain(&self.via).cloned().collect()
    }

    /// The same reproduction aimed at `aim` instead: solved from the same held posture (the
    /// pointing arm and the held part as at the start; a gaze may be added or dropped,
    /// pointing only when the reproduction pointed from the start), the aim's via-points at
    /// the same phases with the newly aimed joints ([`Aiming::via`]).
    pub fn retargeted(&self, aim: &Aim) -> Result<Aiming, AimError> {
        let (robot, arm) = (self.robot, self.solved.arm);
        if aim.point_at.is_some() && arm.is_none() {
            return Err(AimError::Unsupported(
                "point_at: the reproduction was not aimed with point_at at the start (its pointing arm and held part are chosen then)".into(),
            ));
        }
        let mut posture = self.solved.held.clone();
        if let (Some(arm), Some(target)) = (arm, aim.point_at) {
            posture = point(robot, arm, &posture, target)?;
        }
        if let Some(target) = aim.look_at {
            posture = look(robot, &posture, target)?;
        }
        // the joints either aim sets: those no longer aimed return to the held posture
        let both = Aim {
            point_at: aim.point_at.or(self.aim.point_at),
            look_at: aim.look_at.or(self.aim.look_at),
        };
        let joints = aimed_joints(robot, arm, &both);
        let mut next = self.clone();
        for v in &mut next.via {
            for &j in &joints {
                v.posture[j] = posture[j];
            }
        }
        next.solved.posture = posture;
        next.aim = *aim;
        Ok(next)
    }
}

/// `conditions` and the via-points that carry `rows` (a reproduction of `robot`'s joints
/// through `conditions`) through `aim`: [`solve`], then [`via_points`]; with what was solved.
pub fn aim_conditions(
    robot: Robot,
    rows: &[Vec<f64>],
    conditions: &Conditions,
    aim: &Aim,
) -> Result<(Conditions, Aimed), AimError> {
    let solved = solve(robot, rows, aim)?;
    let mut aimed = conditions.clone();
    aimed.via.extend(via_points(robot, rows, &solved, aim));
    Ok((aimed, solved))
}

/// The angle (degrees) between `arm`'s pointing ray and the direction to `target` at each
/// posture of `rows` (postures of `robot`).
pub fn pointing_errors(robot: Robot, arm: Arm, rows: &[Vec<f64>], target: Point) -> Vec<f64> {
    let at = arm.offset(robot).expect("the robot's own arm");
    (rows.iter())
        .map(|r| angle_to(arm.shoulder(), arm.pointing(&r[at..at + 5]), target).to_degrees())
        .collect()
}

/// The angle (degrees) between the top camera's optical axis and the direction to `target`
/// at each posture of `rows` (upper-body postures).
pub fn gaze_errors(rows: &[Vec<f64>], target: Point) -> Vec<f64> {
    (rows.iter())
        .map(|r| {
            let (o, d) = camera(&r[..2]);
            angle_to(o, d, target).to_degrees()
        })
        .collect()
}

/// The longest run of consecutive `values` at most `tolerance`, in values.
pub fn longest_within(values: &[f64], tolerance: f64) -> usize {
    let (mut best, mut run) = (0, 0);
    for v in values {
        run = if *v <= tolerance { run + 1 } else { 0 };
        best = best.max(run);
    }
    best
}

/// What `rows` (postures of `robot`, `rate_hz` a second) do for `aim`, in words: how long the
/// pointing arm's ray (the top camera's axis) stays within 1 degree of each target, and the
/// nearest it comes; e.g. `the left arm points within 1 deg of (1.5, 1, 0.5) m for 1.40 s
/// (nearest 0.00 deg)`.
pub fn summary(robot: Robot, rows: &[Vec<f64>], aim: &Aim, rate_hz: f64) -> Vec<String> {
    let held = |errors: Vec<f64>, who: String, verb: &str, t: Point| {
        let nearest = errors.iter().copied().fold(f64::INFINITY, f64::min);
        let seconds = longest_within(&errors, 1.0) as f64 / rate_hz;
        format!(
            "{who} {verb} within 1 deg of ({}, {}, {}) m for {seconds:.2} s (nearest {nearest:.2} deg)",
            t[0], t[1], t[2]
        )
    };
    let mut lines = Vec::new();
    if let Some(t) = aim.point_at {
        let arm = pointing_arm(robot, rows);
        let errors = pointing_errors(robot, arm, rows, t);
        lines.push(held(errors, format!("the {} arm", arm.name()), "points", t));
    }
    if let Some(t) = aim.look_at.filter(|_| robot == Robot::UpperBody) {
        lines.push(held(
            gaze_errors(rows, t),
            "the top camera".into(),
            "looks",
            t,
        ));
    }
    lines
}
