//! What the description reads from an MJCF text: each named joint's range, each actuator's
//! force range (by the joint it drives) and the keyframes' joint positions.

use quick_xml::events::{BytesStart, Event};

/// What [`read`] finds in a model.
pub(super) struct MjcfModel {
    /// `(joint, lower, upper)` of every named joint with a range, in document order.
    ranges: Vec<(String, f64, f64)>,
    /// `(joint, largest force magnitude)` of every actuator with a force range.
    torques: Vec<(String, f64)>,
    /// Every named joint, in document order (the order of a keyframe's `qpos`).
    joints: Vec<String>,
    /// `(keyframe, qpos)`.
    keyframes: Vec<(String, Vec<f64>)>,
}

impl MjcfModel {
    pub(super) fn range(&self, joint: &str) -> Option<(f64, f64)> {
        let r = self.ranges.iter().find(|(n, _, _)| n == joint);
        r.map(|(_, a, b)| (*a, *b))
    }

    pub(super) fn max_torque(&self, joint: &str) -> Option<f64> {
        self.torques
            .iter()
            .find(|(n, _)| n == joint)
            .map(|(_, t)| *t)
    }

    /// Every keyframe as a posture of `names` (their values picked from its `qpos`).
    pub(super) fn postures(&self, names: &[&str]) -> Result<Vec<(String, Vec<f64>)>, String> {
        let at = |name: &str| self.joints.iter().position(|j| j == name);
        let index: Vec<usize> = names
            .iter()
            .map(|n| at(n).ok_or_else(|| format!("the model has no joint `{n}`")))
            .collect::<Result<_, _>>()?;
        Ok(self
            .keyframes
            .iter()
            .map(|(n, q)| (n.clone(), index.iter().map(|&i| q[i]).collect()))
            .collect())
    }
}

/// `(name, lower, upper)` of every named `<joint>` with a `range` in an MJCF text, in
/// document order. The error says which joint's range is not `lower upper` with lower < upper.
pub fn joint_ranges(xml: &str) -> Result<Vec<(String, f64, f64)>, String> {
    Ok(read(xml)?.ranges)
}

fn attr(e: &BytesStart<'_>, key: &[u8]) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.as_ref() == key)
        .map(|a| String::from_utf8_lossy(&a.value).to_string())
}

fn numbers(text: &str) -> Option<Vec<f64>> {
    text.split_whitespace()
        .map(|x| x.parse::<f64>().ok())
        .collect()
}

/// Read a model: ranges, force ranges, keyframes. A keyframe's `qpos` lists the joints in
/// document order (every joint of these models is a hinge or a slide: one value each).
pub(super) fn read(xml: &str) -> Result<MjcfModel, String> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut joints: Vec<String> = Vec::new();
    let mut ranges = Vec::new();
    let mut torques = Vec::new();
    let mut keys: Vec<(String, Vec<f64>)> = Vec::new();
    loop {
        let e = match reader.read_event() {
            Ok(Event::Start(e)) | Ok(Event::Empty(e)) => e,
            Ok(Event::Eof) => break,
            Err(e) => return Err(format!("not well-formed XML: {e}")),
            _ => continue,
        };
        match e.name().as_ref() {
            b"joint" => {
                let Some(n) = attr(&e, b"name") else { continue };
                joints.push(n.clone());
                if let Some(r) = attr(&e, b"range") {
                    match numbers(&r).as_deref() {
                        Some([a, b]) if a.is_finite() && b.is_finite() && a < b => {
                            ranges.push((n, *a, *b))
                        }
                        Some(_) => {
                            return Err(format!(
                                "joint `{n}`: range `{r}` is not `lower upper` with lower < upper"
                            ))
                        }
                        None => return Err(format!("joint `{n}`: range `{r}` is not two numbers")),
                    }
                }
            }
            b"general" | b"position" | b"motor" => {
                if let (Some(j), Some(f)) = (attr(&e, b"joint"), attr(&e, b"forcerange")) {
                    if let Some([lo, hi]) = numbers(&f).as_deref() {
                        torques.push((j, lo.abs().max(hi.abs())));
                    }
                }
            }
            b"key" => {
                if let (Some(n), Some(q)) = (attr(&e, b"name"), attr(&e, b"qpos")) {
                    let q = numbers(&q).ok_or_else(|| format!("keyframe `{n}`: qpos `{q}`"))?;
                    keys.push((n, q));
                }
            }
            _ => {}
        }
    }
    let keyframes = keys
        .into_iter()
        .map(|(n, q)| {
            if q.len() == joints.len() {
                Ok((n, q))
            } else {
                Err(format!(
                    "keyframe `{n}` has {} joint positions; the model has {} joints",
                    q.len(),
                    joints.len()
                ))
            }
        })
        .collect::<Result<_, _>>()?;
    Ok(MjcfModel {
        ranges,
        torques,
        joints,
        keyframes,
    })
}
