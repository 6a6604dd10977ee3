//! [`Model`]: an owned, compiled `mjModel`.

use super::{callbacks, check_version, ffi, zeroed_box, MjError, Result};
use std::ffi::{c_char, c_int, CStr, CString};
use std::path::Path;
use std::ptr::NonNull;

/// Size of the buffer MuJoCo writes a load error into.
const ERROR_BUF: usize = 1000;
/// Name under which an XML string is put into MuJoCo's virtual file system.
const VFS_NAME: &str = "cosco_hsom_model.xml";

/// A compiled MuJoCo model (`mjModel`), freed with `mj_deleteModel` on drop.
///
/// ```
/// use cosco_hsom::mujoco::Model;
/// let model = Model::from_xml_str(
///     r#"<mujoco><worldbody><body name="b"><joint name="j" type="hinge"/>
///        <geom size="0.1"/></body></worldbody></mujoco>"#,
/// )?;
/// assert_eq!(model.nq(), 1);
/// assert_eq!(model.joint_id("j"), Some(0));
/// assert_eq!(model.joint_id("nope"), None);
/// # Ok::<(), cosco_hsom::mujoco::MjError>(())
/// ```
#[derive(Debug)]
pub struct Model {
    ptr: NonNull<ffi::mjModel>,
}

// Safety: a Model owns its mjModel exclusively; the allocation has no thread affinity.
// MuJoCo's simulation functions take `const mjModel*` and never write to it, and the `&self`
// methods here only read, so sharing `&Model` between threads (Sync) and moving it (Send) is
// sound. Tests and the trainer step one Data per thread on one shared Model.
unsafe impl Send for Model {}
// Safety: see `Send` above; no `&self` method mutates the mjModel.
unsafe impl Sync for Model {}

impl Drop for Model {
    fn drop(&mut self) {
        // Safety: `ptr` came from mj_loadXML, is owned by this Model and freed exactly once.
        // Every Data borrows the Model, so none outlives it.
        unsafe { ffi::mj_deleteModel(self.ptr.as_ptr()) }
    }
}

/// MuJoCo object kinds looked up by name.
#[derive(Clone, Copy)]
enum Obj {
    Body,
    Joint,
    Site,
    Camera,
    Actuator,
    Geom,
    Key,
}

impl Obj {
    fn code(self) -> c_int {
        let code = match self {
            Obj::Body => ffi::mjtObj__mjOBJ_BODY,
            Obj::Joint => ffi::mjtObj__mjOBJ_JOINT,
            Obj::Site => ffi::mjtObj__mjOBJ_SITE,
            Obj::Camera => ffi::mjtObj__mjOBJ_CAMERA,
            Obj::Actuator => ffi::mjtObj__mjOBJ_ACTUATOR,
            Obj::Geom => ffi::mjtObj__mjOBJ_GEOM,
            Obj::Key => ffi::mjtObj__mjOBJ_KEY,
        };
        code as c_int
    }
}

/// Heap-allocated, zeroed `mjVFS` (about 2 MB: never on the stack), released with
/// `mj_deleteVFS` on drop.
struct Vfs(Box<ffi::mjVFS>);

impl Vfs {
    fn new() -> Vfs {
        // Safety: mjVFS is plain old data (ints, chars, raw pointers); all-zero is a valid
        // value for every field.
        let mut vfs = unsafe { zeroed_box::<ffi::mjVFS>() };
        // Safety: `vfs` points to a valid, writable mjVFS.
        unsafe { ffi::mj_defaultVFS(&mut *vfs) };
        Vfs(vfs)
    }

    /// Add a file `name` with `bytes` as its content.
    fn add(&mut self, name: &CStr, bytes: &[u8]) -> Result<()> {
        let size = c_int::try_from(bytes.len()).map_err(|_| MjError::TooLarge {
            what: "MJCF text",
            size: bytes.len(),
        })?;
        // Safety: the VFS is valid; `name` is NUL-terminated. On success MuJoCo allocated
        // `size` bytes for the new file at index nfile - 1.
        let status = unsafe { ffi::mj_makeEmptyFileVFS(&mut *self.0, name.as_ptr(), size) };
        match status {
            0 => {}
            1 => {
                return Err(MjError::TooLarge {
                    what: "MuJoCo virtual file system (full)",
                    size: bytes.len(),
                })
            }
            _ => {
                return Err(MjError::Runtime {
                    message: format!("virtual file {name:?} already exists"),
                })
            }
        }
        let index = (self.0.nfile - 1) as usize;
        let dst = self.0.filedata[index] as *mut u8;
        if dst.is_null() {
            return Err(MjError::Runtime {
                message: "MuJoCo could not allocate the virtual file".into(),
            });
        }
        // Safety: MuJoCo allocated exactly `bytes.len()` bytes at `dst` for this file; the
        // regions do not overlap.
        unsafe { std::ptr::copy_nonoverlapping(bytes.as_ptr(), dst, bytes.len()) };
        Ok(())
    }
}

impl Drop for Vfs {
    fn drop(&mut self) {
        // Safety: frees the file buffers MuJoCo allocated; the Box frees the struct.
        unsafe { ffi::mj_deleteVFS(&mut *self.0) }
    }
}

impl Model {
    /// Load and compile an MJCF file. The error names the path and carries MuJoCo's message.
    pub fn from_xml_path(path: &Path) -> Result<Model> {
        check_version()?;
        let shown = path.display().to_string();
        let c_path = CString::new(path.as_os_str().as_encoded_bytes())
            .map_err(|_| MjError::NulByte { what: "model path" })?;
        if !path.is_file() {
            return Err(MjError::Load {
                path: shown,
                message: "no such file".into(),
            });
        }
        Self::load(&c_path, None, shown)
    }

    /// Load and compile MJCF given as a string, through MuJoCo's virtual file system (2.2 has
    /// no loader from memory). Files the XML refers to (meshes, includes) are looked up
    /// relative to the working directory.
    pub fn from_xml_str(xml: &str) -> Result<Model> {
        check_version()?;
        let name = CString::new(VFS_NAME).expect("constant has no NUL");
        let mut vfs = Vfs::new();
        vfs.add(&name, xml.as_bytes())?;
        Self::load(&name, Some(&vfs), "<string>".into())
    }

    fn load(file: &CStr, vfs: Option<&Vfs>, shown: String) -> Result<Model> {
        let mut err = [0 as c_char; ERROR_BUF];
        let vfs_ptr = vfs.map_or(std::ptr::null(), |v| &*v.0 as *const ffi::mjVFS);
        callbacks::clear();
        // Safety: `file` is NUL-terminated, `vfs_ptr` is null or a valid VFS that outlives the
        // call, `err` is a writable buffer of the size given.
        let raw = unsafe {
            ffi::mj_loadXML(file.as_ptr(), vfs_ptr, err.as_mut_ptr(), ERROR_BUF as c_int)
        };
        // MuJoCo's compiler reports through its own thread-local hooks (which take precedence
        // over ours on this thread during the call) into `err`; ours only see engine errors.
        let hook_error = callbacks::take_error();
        // Safety: MuJoCo writes a NUL-terminated message into `err`, which was zeroed and
        // whose last byte it never overwrites.
        let message = unsafe { CStr::from_ptr(err.as_ptr()) }
            .to_string_lossy()
            .trim()
            .to_string();
        match NonNull::new(raw) {
            Some(ptr) => Ok(Model { ptr }),
            None => Err(MjError::Load {
                path: shown,
                message: if !message.is_empty() {
                    message
                } else {
                    hook_error.unwrap_or_else(|| "MuJoCo gave no reason".into())
                },
            }),
        }
    }

    /// The raw pointer, for the rendering layer.
    pub(crate) fn as_ptr(&self) -> *const ffi::mjModel {
        self.ptr.as_ptr()
    }

    fn raw(&self) -> &ffi::mjModel {
        // Safety: `ptr` is valid and not mutated while `self` is borrowed.
        unsafe { self.ptr.as_ref() }
    }

    /// Number of generalized coordinates.
    pub fn nq(&self) -> usize {
        self.raw().nq as usize
    }
    /// Number of degrees of freedom.
    pub fn nv(&self) -> usize {
        self.raw().nv as usize
    }
    /// Number of actuators.
    pub fn nu(&self) -> usize {
        self.raw().nu as usize
    }
    /// Number of joints.
    pub fn njnt(&self) -> usize {
        self.raw().njnt as usize
    }
    /// Number of sites.
    pub fn nsite(&self) -> usize {
        self.raw().nsite as usize
    }
    /// Number of bodies, the world body included.
    pub fn nbody(&self) -> usize {
        self.raw().nbody as usize
    }
    /// Number of geoms, the world's included.
    pub fn ngeom(&self) -> usize {
        self.raw().ngeom as usize
    }
    /// Number of keyframes.
    pub fn nkey(&self) -> usize {
        self.raw().nkey as usize
    }
    /// Number of cameras defined in the model.
    pub fn ncam(&self) -> usize {
        self.raw().ncam as usize
    }
    /// Simulation timestep in seconds (`<option timestep>`).
    pub fn timestep(&self) -> f64 {
        self.raw().opt.timestep
    }
    /// Largest off-screen render size, `<visual><global offwidth offheight>`.
    pub fn offscreen_size(&self) -> (usize, usize) {
        let g = &self.raw().vis.global;
        (g.offwidth.max(0) as usize, g.offheight.max(0) as usize)
    }

    fn name2id(&self, obj: Obj, name: &str) -> Option<usize> {
        let c = CString::new(name).ok()?;
        // Safety: valid model, valid object type, NUL-terminated name.
        let id = unsafe { ffi::mj_name2id(self.as_ptr(), obj.code(), c.as_ptr()) };
        usize::try_from(id).ok()
    }

    fn id2name(&self, obj: Obj, id: usize, count: usize) -> Option<String> {
        if id >= count {
            return None;
        }
        // Safety: valid model, type, and an id checked against the object count.
        let p = unsafe { ffi::mj_id2name(self.as_ptr(), obj.code(), id as c_int) };
        if p.is_null() {
            return None;
        }
        // Safety: a non-null result points into the model's NUL-separated name buffer.
        Some(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
    }

    /// Id of the joint called `name`.
    pub fn joint_id(&self, name: &str) -> Option<usize> {
        self.name2id(Obj::Joint, name)
    }
    /// Id of the actuator called `name`.
    pub fn actuator_id(&self, name: &str) -> Option<usize> {
        self.name2id(Obj::Actuator, name)
    }
    /// Id of the site called `name`.
    pub fn site_id(&self, name: &str) -> Option<usize> {
        self.name2id(Obj::Site, name)
    }
    /// Id of the body called `name`.
    pub fn body_id(&self, name: &str) -> Option<usize> {
        self.name2id(Obj::Body, name)
    }
    /// Id of the camera called `name`.
    pub fn camera_id(&self, name: &str) -> Option<usize> {
        self.name2id(Obj::Camera, name)
    }
    /// Id of the geom called `name`.
    pub fn geom_id(&self, name: &str) -> Option<usize> {
        self.name2id(Obj::Geom, name)
    }
    /// Id of the keyframe called `name`.
    pub fn key_id(&self, name: &str) -> Option<usize> {
        self.name2id(Obj::Key, name)
    }
    /// Name of joint `id` (None when out of range or unnamed).
    pub fn joint_name(&self, id: usize) -> Option<String> {
        self.id2name(Obj::Joint, id, self.njnt())
    }
    /// Name of actuator `id` (None when out of range or unnamed).
    pub fn actuator_name(&self, id: usize) -> Option<String> {
        self.id2name(Obj::Actuator, id, self.nu())
    }
    /// Name of site `id` (None when out of range or unnamed).
    pub fn site_name(&self, id: usize) -> Option<String> {
        self.id2name(Obj::Site, id, self.nsite())
    }
    /// Name of body `id` (None when out of range or unnamed).
    pub fn body_name(&self, id: usize) -> Option<String> {
        self.id2name(Obj::Body, id, self.nbody())
    }
    /// Name of camera `id` (None when out of range or unnamed).
    pub fn camera_name(&self, id: usize) -> Option<String> {
        self.id2name(Obj::Camera, id, self.ncam())
    }

    /// Name of keyframe `id` (None when out of range or unnamed).
    pub fn key_name(&self, id: usize) -> Option<String> {
        self.id2name(Obj::Key, id, self.nkey())
    }
    /// Name of geom `id` (None when out of range or unnamed).
    pub fn geom_name(&self, id: usize) -> Option<String> {
        self.id2name(Obj::Geom, id, self.ngeom())
    }

    /// Read element `i` of a model array of `len` elements.
    ///
    /// # Safety
    /// `p` must be the model array with `len` elements that the caller names.
    unsafe fn at<T: Copy>(p: *const T, i: usize, len: usize) -> T {
        assert!(i < len, "index {i} out of range 0..{len}");
        // Safety: guaranteed by the caller and the bounds check above.
        unsafe { *p.add(i) }
    }

    /// Entry `id` of a `(low, high)` range array of `n` objects, `None` when its `limited`
    /// flag is 0. Panics when `id >= n`.
    ///
    /// # Safety
    /// `limited` (`n` entries) and `range` (`2 n`) must be the model arrays the caller names.
    unsafe fn limited_range(
        limited: *const ffi::mjtByte,
        range: *const f64,
        id: usize,
        n: usize,
    ) -> Option<(f64, f64)> {
        // Safety: guaranteed by the caller.
        unsafe {
            if Self::at(limited, id, n) == 0 {
                return None;
            }
            Some((
                Self::at(range, 2 * id, 2 * n),
                Self::at(range, 2 * id + 1, 2 * n),
            ))
        }
    }

    /// Range of joint `id`, `None` when the joint is not limited.
    ///
    /// # Panics
    /// When `id >= njnt()` (ids come from [`Model::joint_id`]).
    pub fn joint_range(&self, id: usize) -> Option<(f64, f64)> {
        let m = self.raw();
        // Safety: jnt_limited has njnt entries, jnt_range 2*njnt.
        unsafe { Self::limited_range(m.jnt_limited, m.jnt_range, id, self.njnt()) }
    }
    /// Address of joint `id`'s first coordinate in `qpos`. Panics when `id >= njnt()`.
    pub fn joint_qpos_adr(&self, id: usize) -> usize {
        // Safety: jnt_qposadr has njnt entries.
        unsafe { Self::at(self.raw().jnt_qposadr, id, self.njnt()) as usize }
    }
    /// Address of joint `id`'s first degree of freedom in `qvel`. Panics when `id >= njnt()`.
    pub fn joint_dof_adr(&self, id: usize) -> usize {
        // Safety: jnt_dofadr has njnt entries.
        unsafe { Self::at(self.raw().jnt_dofadr, id, self.njnt()) as usize }
    }
    /// Control range of actuator `id`, `None` when not limited. Panics when `id >= nu()`.
    pub fn actuator_ctrl_range(&self, id: usize) -> Option<(f64, f64)> {
        let m = self.raw();
        // Safety: actuator_ctrllimited has nu entries, actuator_ctrlrange 2*nu.
        unsafe { Self::limited_range(m.actuator_ctrllimited, m.actuator_ctrlrange, id, self.nu()) }
    }
    /// Force range of actuator `id`, `None` when not limited. Panics when `id >= nu()`.
    pub fn actuator_force_range(&self, id: usize) -> Option<(f64, f64)> {
        let m = self.raw();
        // Safety: actuator_forcelimited has nu entries, actuator_forcerange 2*nu.
        unsafe {
            Self::limited_range(
                m.actuator_forcelimited,
                m.actuator_forcerange,
                id,
                self.nu(),
            )
        }
    }
    /// The joint actuator `id` drives, when its transmission is a joint. Panics when
    /// `id >= nu()`.
    pub fn actuator_joint(&self, id: usize) -> Option<usize> {
        let m = self.raw();
        let n = self.nu();
        // Safety: actuator_trntype has nu entries, actuator_trnid 2*nu.
        let (kind, target) = unsafe {
            (
                Self::at(m.actuator_trntype, id, n),
                Self::at(m.actuator_trnid, 2 * id, 2 * n),
            )
        };
        let is_joint = kind == ffi::mjtTrn__mjTRN_JOINT as c_int
            || kind == ffi::mjtTrn__mjTRN_JOINTINPARENT as c_int;
        if is_joint {
            usize::try_from(target).ok()
        } else {
            None
        }
    }
    /// Mass of body `id` in kg. Panics when `id >= nbody()`.
    pub fn body_mass(&self, id: usize) -> f64 {
        // Safety: body_mass has nbody entries.
        unsafe { Self::at(self.raw().body_mass, id, self.nbody()) }
    }
    /// The parent of body `id` (the world's is itself, 0). Panics when `id >= nbody()`.
    pub fn body_parent(&self, id: usize) -> usize {
        // Safety: body_parentid has nbody entries.
        unsafe { Self::at(self.raw().body_parentid, id, self.nbody()) as usize }
    }
    /// The body joint `id` moves. Panics when `id >= njnt()`.
    pub fn joint_body(&self, id: usize) -> usize {
        // Safety: jnt_bodyid has njnt entries.
        unsafe { Self::at(self.raw().jnt_bodyid, id, self.njnt()) as usize }
    }
    /// The body geom `id` belongs to. Panics when `id >= ngeom()`.
    pub fn geom_body(&self, id: usize) -> usize {
        // Safety: geom_bodyid has ngeom entries.
        unsafe { Self::at(self.raw().geom_bodyid, id, self.ngeom()) as usize }
    }
    /// `n` consecutive numbers of entry `id` of a model array holding `stride` numbers per
    /// object for `count` objects.
    ///
    /// # Safety
    /// `p` must be the model array the caller names, with `stride * count` numbers.
    unsafe fn row<const N: usize>(
        p: *const f64,
        id: usize,
        stride: usize,
        count: usize,
    ) -> [f64; N] {
        assert!(id < count, "index {id} out of range 0..{count}");
        assert!(N <= stride);
        // Safety: guaranteed by the caller and the bounds checks above.
        std::array::from_fn(|k| unsafe { *p.add(stride * id + k) })
    }
    /// Centre of mass of body `id` in the body's frame (`body_ipos`). Panics when
    /// `id >= nbody()`.
    pub fn body_ipos(&self, id: usize) -> [f64; 3] {
        // Safety: body_ipos has 3 numbers per body.
        unsafe { Self::row(self.raw().body_ipos, id, 3, self.nbody()) }
    }
    /// Orientation of body `id`'s principal inertia axes in the body's frame (`body_iquat`,
    /// w x y z). Panics when `id >= nbody()`.
    pub fn body_iquat(&self, id: usize) -> [f64; 4] {
        // Safety: body_iquat has 4 numbers per body.
        unsafe { Self::row(self.raw().body_iquat, id, 4, self.nbody()) }
    }
    /// Principal moments of inertia of body `id` about its centre of mass (`body_inertia`,
    /// kg m^2, along the axes of [`Model::body_iquat`]). Panics when `id >= nbody()`.
    pub fn body_inertia(&self, id: usize) -> [f64; 3] {
        // Safety: body_inertia has 3 numbers per body.
        unsafe { Self::row(self.raw().body_inertia, id, 3, self.nbody()) }
    }
    /// Armature (reflected rotor inertia) of degree of freedom `dof`. Panics when
    /// `dof >= nv()`.
    pub fn dof_armature(&self, dof: usize) -> f64 {
        // Safety: dof_armature has nv entries.
        unsafe { Self::at(self.raw().dof_armature, dof, self.nv()) }
    }
    /// The first gain parameter of actuator `id` (`gainprm[0]`: kp of a position servo).
    /// Panics when `id >= nu()`.
    pub fn actuator_gain(&self, id: usize) -> f64 {
        // Safety: actuator_gainprm has mjNGAIN numbers per actuator.
        let [g] = unsafe {
            Self::row(
                self.raw().actuator_gainprm,
                id,
                ffi::mjNGAIN as usize,
                self.nu(),
            )
        };
        g
    }
    /// The first three bias parameters of actuator `id` (`biasprm[0..3]`: 0, -kp, -kv of a
    /// position servo). Panics when `id >= nu()`.
    pub fn actuator_bias(&self, id: usize) -> [f64; 3] {
        // Safety: actuator_biasprm has mjNBIAS numbers per actuator.
        unsafe {
            Self::row(
                self.raw().actuator_biasprm,
                id,
                ffi::mjNBIAS as usize,
                self.nu(),
            )
        }
    }
    /// Vertical field of view of camera `id` in degrees. Panics when `id >= ncam()`.
    pub fn camera_fovy(&self, id: usize) -> f64 {
        // Safety: cam_fovy has ncam entries.
        unsafe { Self::at(self.raw().cam_fovy, id, self.ncam()) }
    }
    /// Positions of keyframe `id` (`nq` numbers). Panics when `id >= nkey()`.
    pub fn key_qpos(&self, id: usize) -> Vec<f64> {
        self.key_array(self.raw().key_qpos, id, self.nq())
    }
    /// Controls of keyframe `id` (`nu` numbers). Panics when `id >= nkey()`.
    pub fn key_ctrl(&self, id: usize) -> Vec<f64> {
        self.key_array(self.raw().key_ctrl, id, self.nu())
    }
    fn key_array(&self, p: *const f64, id: usize, width: usize) -> Vec<f64> {
        let n = self.nkey();
        assert!(id < n, "keyframe id {id} out of range 0..{n}");
        // Safety: key_qpos and key_ctrl hold `width` (nq or nu) numbers per keyframe.
        (0..width)
            .map(|k| unsafe { Self::at(p, width * id + k, width * n) })
            .collect()
    }
}
