//! [`Data`]: the simulation state of one [`Model`].

use super::{callbacks, ffi, MjError, Model, Result};
use std::ffi::CStr;
use std::ptr::NonNull;

/// Warnings that mean the simulation diverged (MuJoCo then resets the state itself).
const INSTABILITY: [u32; 3] = [
    ffi::mjtWarning__mjWARN_BADQACC,
    ffi::mjtWarning__mjWARN_BADQPOS,
    ffi::mjtWarning__mjWARN_BADQVEL,
];

/// One contact MuJoCo found between two geoms in the last step or [`Data::forward`].
#[derive(Debug, Clone, PartialEq)]
pub struct Contact {
    /// The two geoms' ids (MuJoCo's order).
    pub geom: [usize; 2],
    /// The two geoms' names (`None` for an unnamed geom).
    pub geom_name: [Option<String>; 2],
    /// The bodies the two geoms belong to.
    pub body: [usize; 2],
    /// The two bodies' names (`None` for an unnamed body; the world body is `world`).
    pub body_name: [Option<String>; 2],
    /// Signed distance between the geoms' surfaces in metres (MuJoCo's `dist`): negative when
    /// they penetrate, at most the pair's margin otherwise.
    pub dist: f64,
    /// The contact point in world coordinates (midway between the two surfaces).
    pub pos: [f64; 3],
    /// The contact normal in world coordinates, pointing from the first geom to the second.
    pub normal: [f64; 3],
    /// Whether the contact takes part in the dynamics: `false` for one that lies within the
    /// pair's `gap` (MuJoCo's `exclude` = 1: detected, but no force).
    pub active: bool,
}

impl Contact {
    /// Whether one of the two geoms belongs to the body called `name`.
    pub fn touches(&self, name: &str) -> bool {
        self.body_name.iter().any(|b| b.as_deref() == Some(name))
    }

    /// Whether the contact is between the bodies called `a` and `b` (in either order).
    pub fn between(&self, a: &str, b: &str) -> bool {
        let [x, y] = [self.body_name[0].as_deref(), self.body_name[1].as_deref()];
        (x == Some(a) && y == Some(b)) || (x == Some(b) && y == Some(a))
    }
}

/// The simulation state (`mjData`) of a [`Model`], freed with `mj_deleteData` on drop.
///
/// ```
/// use cosco_hsom::mujoco::{Data, Model};
/// let model = Model::from_xml_str(
///     r#"<mujoco><worldbody><body><joint type="hinge" axis="0 1 0"/>
///        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/></body></worldbody></mujoco>"#,
/// )?;
/// let mut data = Data::new(&model)?;
/// for _ in 0..10 {
///     data.step()?;
/// }
/// assert!((data.time() - 10.0 * model.timestep()).abs() < 1e-12);
/// assert!(data.qpos()[0] != 0.0); // the pendulum fell under gravity
/// # Ok::<(), cosco_hsom::mujoco::MjError>(())
/// ```
pub struct Data<'m> {
    model: &'m Model,
    ptr: NonNull<ffi::mjData>,
    /// Set when MuJoCo raised an error during a call on this state (see the module docs).
    poisoned: Option<String>,
}

// Safety: a Data owns its mjData exclusively and the allocation has no thread affinity; the
// Model it borrows is Sync. The error hooks record into the thread that makes the call, which
// is the thread that then reads the record, wherever the Data was created.
// Data is deliberately not Sync: rendering hands the mjData to mjv_updateScene as a mutable
// pointer (it uses the mjData stack), so two threads reading one `&Data` would race.
unsafe impl Send for Data<'_> {}

impl std::fmt::Debug for Data<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Data")
            .field("time", &self.time())
            .field("nq", &self.model.nq())
            .field("poisoned", &self.poisoned)
            .finish()
    }
}

impl Drop for Data<'_> {
    fn drop(&mut self) {
        // Safety: `ptr` came from mj_makeData, is owned by this Data and freed exactly once.
        unsafe { ffi::mj_deleteData(self.ptr.as_ptr()) }
    }
}

impl<'m> Data<'m> {
    /// Allocate a state for `model`, at the model's reference configuration (`qpos0`).
    pub fn new(model: &'m Model) -> Result<Data<'m>> {
        callbacks::clear();
        // Safety: the model is valid for 'm, which outlives the returned Data.
        let raw = unsafe { ffi::mj_makeData(model.as_ptr()) };
        let error = callbacks::take_error();
        match (NonNull::new(raw), error) {
            (Some(ptr), None) => Ok(Data {
                model,
                ptr,
                poisoned: None,
            }),
            (Some(ptr), Some(message)) => {
                // Safety: MuJoCo returned a pointer it allocated; free it, do not use it.
                unsafe { ffi::mj_deleteData(ptr.as_ptr()) };
                Err(MjError::Runtime { message })
            }
            (None, error) => Err(MjError::Runtime {
                message: error.unwrap_or_else(|| "mj_makeData could not allocate the state".into()),
            }),
        }
    }

    /// The model this state belongs to.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    /// The raw pointer, for the rendering layer.
    pub(crate) fn as_ptr(&self) -> *const ffi::mjData {
        self.ptr.as_ptr()
    }

    /// The raw pointer for MuJoCo calls that write the state.
    #[allow(dead_code)] // part of the layer's crate-internal API; no caller yet
    pub(crate) fn as_mut_ptr(&mut self) -> *mut ffi::mjData {
        self.ptr.as_ptr()
    }

    fn raw(&self) -> &ffi::mjData {
        // Safety: `ptr` is valid; shared access while `self` is borrowed.
        unsafe { self.ptr.as_ref() }
    }

    /// A slice over an mjData array of `len` numbers.
    fn slice(&self, p: *const f64, len: usize) -> &[f64] {
        if len == 0 || p.is_null() {
            return &[];
        }
        // Safety: `p` is an array of the mjData with `len` elements (sizes from the model),
        // valid as long as `self` is borrowed.
        unsafe { std::slice::from_raw_parts(p, len) }
    }

    fn slice_mut(&mut self, p: *mut f64, len: usize) -> &mut [f64] {
        if len == 0 || p.is_null() {
            return &mut [];
        }
        // Safety: as in `slice`, and `&mut self` guarantees exclusive access.
        unsafe { std::slice::from_raw_parts_mut(p, len) }
    }

    /// Simulation time in seconds.
    pub fn time(&self) -> f64 {
        self.raw().time
    }
    /// Generalized positions (`nq`).
    pub fn qpos(&self) -> &[f64] {
        self.slice(self.raw().qpos, self.model.nq())
    }
    /// Generalized positions, writable (call [`Data::forward`] to update kinematics).
    pub fn qpos_mut(&mut self) -> &mut [f64] {
        let (p, n) = (self.raw().qpos, self.model.nq());
        self.slice_mut(p, n)
    }
    /// Generalized velocities (`nv`).
    pub fn qvel(&self) -> &[f64] {
        self.slice(self.raw().qvel, self.model.nv())
    }
    /// Generalized velocities, writable.
    pub fn qvel_mut(&mut self) -> &mut [f64] {
        let (p, n) = (self.raw().qvel, self.model.nv());
        self.slice_mut(p, n)
    }
    /// Actuator controls (`nu`).
    pub fn ctrl(&self) -> &[f64] {
        self.slice(self.raw().ctrl, self.model.nu())
    }
    /// Actuator controls, writable.
    pub fn ctrl_mut(&mut self) -> &mut [f64] {
        let (p, n) = (self.raw().ctrl, self.model.nu());
        self.slice_mut(p, n)
    }
    /// External forces and torques applied to the bodies (`6 nbody`: per body a force, then a
    /// torque, world frame, at the body's centre of mass), writable: they act at every step
    /// until changed.
    pub fn xfrc_applied_mut(&mut self) -> &mut [f64] {
        let (p, n) = (self.raw().xfrc_applied, 6 * self.model.nbody());
        self.slice_mut(p, n)
    }
    /// Actuator forces of the last step (`nu`).
    pub fn actuator_force(&self) -> &[f64] {
        self.slice(self.raw().actuator_force, self.model.nu())
    }
    /// Bias forces (Coriolis, centrifugal, gravity) of the last step (`nv`).
    pub fn qfrc_bias(&self) -> &[f64] {
        self.slice(self.raw().qfrc_bias, self.model.nv())
    }

    fn vec3(&self, p: *const f64, id: usize, count: usize, what: &str) -> [f64; 3] {
        assert!(id < count, "{what} id {id} out of range 0..{count}");
        let s = self.slice(p, 3 * count);
        [s[3 * id], s[3 * id + 1], s[3 * id + 2]]
    }

    /// World position of site `id` (after a step or [`Data::forward`]). Panics when
    /// `id >= nsite()`.
    pub fn site_xpos(&self, site: usize) -> [f64; 3] {
        self.vec3(self.raw().site_xpos, site, self.model.nsite(), "site")
    }
    /// World orientation of site `id`, row-major 3x3. Panics when `id >= nsite()`.
    pub fn site_xmat(&self, site: usize) -> [f64; 9] {
        let n = self.model.nsite();
        assert!(site < n, "site id {site} out of range 0..{n}");
        let s = self.slice(self.raw().site_xmat, 9 * n);
        let mut out = [0.0; 9];
        out.copy_from_slice(&s[9 * site..9 * site + 9]);
        out
    }
    /// World position of body `id`'s frame. Panics when `id >= nbody()`.
    pub fn body_xpos(&self, body: usize) -> [f64; 3] {
        self.vec3(self.raw().xpos, body, self.model.nbody(), "body")
    }
    /// World position of body `id`'s centre of mass. Panics when `id >= nbody()`.
    pub fn body_xipos(&self, body: usize) -> [f64; 3] {
        self.vec3(self.raw().xipos, body, self.model.nbody(), "body")
    }
    /// World position of joint `id`'s anchor. Panics when `id >= njnt()`.
    pub fn xanchor(&self, joint: usize) -> [f64; 3] {
        self.vec3(self.raw().xanchor, joint, self.model.njnt(), "joint")
    }
    /// World direction of joint `id`'s axis. Panics when `id >= njnt()`.
    pub fn xaxis(&self, joint: usize) -> [f64; 3] {
        self.vec3(self.raw().xaxis, joint, self.model.njnt(), "joint")
    }

    /// World position of camera `id`. Panics when `id >= ncam()`.
    pub fn cam_xpos(&self, camera: usize) -> [f64; 3] {
        self.vec3(self.raw().cam_xpos, camera, self.model.ncam(), "camera")
    }
    /// World orientation of camera `id`, row-major 3x3 (columns: the image's right, its up,
    /// and the direction opposite to the view). Panics when `id >= ncam()`.
    pub fn cam_xmat(&self, camera: usize) -> [f64; 9] {
        let n = self.model.ncam();
        assert!(camera < n, "camera id {camera} out of range 0..{n}");
        let s = self.slice(self.raw().cam_xmat, 9 * n);
        let mut out = [0.0; 9];
        out.copy_from_slice(&s[9 * camera..9 * camera + 9]);
        out
    }

    /// Every contact MuJoCo detected in the last step or [`Data::forward`], those within a
    /// pair's `gap` (no force, [`Contact::active`] false) included. Geoms with a `margin`
    /// report contacts up to that distance apart, which measures clearances.
    pub fn detected_contacts(&self) -> Vec<Contact> {
        let raw = self.raw();
        let n = usize::try_from(raw.ncon).unwrap_or(0);
        if n == 0 || raw.contact.is_null() {
            return Vec::new();
        }
        // Safety: mj_collision filled `ncon` entries of the `contact` array (its capacity,
        // nconmax, bounds ncon); they stay valid while `self` is borrowed.
        let raw_contacts = unsafe { std::slice::from_raw_parts(raw.contact, n) };
        let model = self.model;
        raw_contacts
            .iter()
            .filter_map(|c| {
                let geom = [
                    usize::try_from(c.geom1).ok()?,
                    usize::try_from(c.geom2).ok()?,
                ];
                let body = geom.map(|g| model.geom_body(g));
                Some(Contact {
                    geom,
                    geom_name: geom.map(|g| model.geom_name(g)),
                    body,
                    body_name: body.map(|b| model.body_name(b)),
                    dist: c.dist,
                    pos: c.pos,
                    normal: [c.frame[0], c.frame[1], c.frame[2]],
                    active: c.exclude == 0,
                })
            })
            .collect()
    }

    /// The active contacts of the last step or [`Data::forward`]: the ones that take part in
    /// the dynamics (see [`Data::detected_contacts`] for those within a gap too).
    pub fn contacts(&self) -> Vec<Contact> {
        let mut all = self.detected_contacts();
        all.retain(|c| c.active);
        all
    }

    /// How many times MuJoCo raised each warning (`mjtWarning` order) on this state.
    pub fn warning_counts(&self) -> [i32; 8] {
        let mut out = [0; 8];
        for (o, w) in out.iter_mut().zip(self.raw().warning.iter()) {
            *o = w.number;
        }
        out
    }

    fn check_poison(&self) -> Result<()> {
        match &self.poisoned {
            Some(message) => Err(MjError::Poisoned {
                message: message.clone(),
            }),
            None => Ok(()),
        }
    }

    /// Run one MuJoCo call, then turn a raised error or an instability warning into `Err`.
    fn run(
        &mut self,
        call: unsafe extern "C" fn(*const ffi::mjModel, *mut ffi::mjData),
    ) -> Result<()> {
        self.check_poison()?;
        callbacks::clear();
        let time = self.time();
        let before = self.warning_counts();
        // Safety: `call` is mj_step or mj_forward; model and data are valid and belong
        // together, and `&mut self` gives exclusive access to the data.
        unsafe { call(self.model.as_ptr(), self.ptr.as_ptr()) };
        if let Some(message) = callbacks::take_error() {
            self.poisoned = Some(message.clone());
            return Err(MjError::Runtime { message });
        }
        let after = self.warning_counts();
        for kind in INSTABILITY {
            let k = kind as usize;
            if after[k] > before[k] {
                let warnings = callbacks::take_warnings();
                let message = warnings
                    .into_iter()
                    .last()
                    .unwrap_or_else(|| warning_text(kind, self.raw().warning[k].lastinfo));
                return Err(MjError::Unstable { time, message });
            }
        }
        Ok(())
    }

    /// Advance the simulation by one timestep (`mj_step`).
    ///
    /// `Err(Unstable)` when the state diverged (MuJoCo has then reset it to `qpos0`),
    /// `Err(Runtime)` when MuJoCo raised an error (this state is then poisoned until
    /// [`Data::reset`]).
    pub fn step(&mut self) -> Result<()> {
        self.run(ffi::mj_step)
    }

    /// Recompute everything derived from the state without integrating (`mj_forward`), e.g.
    /// site positions after writing `qpos`.
    pub fn forward(&mut self) -> Result<()> {
        self.run(ffi::mj_forward)
    }

    /// Reset the state to keyframe `key` of the model (`mj_resetDataKeyframe`: time, `qpos`,
    /// `qvel`, `act`, `ctrl` and mocap poses from the keyframe) and clear the poison. Call
    /// [`Data::forward`] for the derived quantities. Panics when `key >= nkey()`.
    pub fn reset_to_key(&mut self, key: usize) {
        let n = self.model.nkey();
        assert!(key < n, "keyframe id {key} out of range 0..{n}");
        // Safety: valid model and data, exclusive access, a keyframe id checked above.
        unsafe { ffi::mj_resetDataKeyframe(self.model.as_ptr(), self.ptr.as_ptr(), key as i32) };
        self.poisoned = None;
    }

    /// Reset the state to the model's defaults (`mj_resetData`) and clear the poison.
    pub fn reset(&mut self) {
        // Safety: valid model and data, exclusive access.
        unsafe { ffi::mj_resetData(self.model.as_ptr(), self.ptr.as_ptr()) };
        self.poisoned = None;
    }
}

/// MuJoCo's text for warning `kind` with `info`.
fn warning_text(kind: u32, info: i32) -> String {
    // Safety: `kind` is a valid mjtWarning; the result is a static NUL-terminated string.
    let p = unsafe { ffi::mju_warningText(kind as i32, info) };
    if p.is_null() {
        return format!("MuJoCo warning {kind}");
    }
    // Safety: non-null, NUL-terminated (see above).
    unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
}

#[cfg(test)]
mod tests;
