//! [`Renderer`]: OSMesa context + MuJoCo scene, camera, options and GPU context.

use super::{RenderError, Result};
use crate::mujoco::{callbacks, ffi, zeroed_box, Data, MjError, Model};
use image::RgbImage;
use std::ffi::c_int;
use std::path::Path;
use std::ptr::NonNull;

/// Geoms the scene can hold (MuJoCo's simulate uses 10000; our arms need a few dozen).
const MAX_GEOM: c_int = 2000;
/// Multisampling used when asked for and the model says `offsamples="0"`.
const DEFAULT_SAMPLES: c_int = 4;
/// Shadow map size used when asked for and the model says `shadowsize="0"`.
const DEFAULT_SHADOW_SIZE: c_int = 4096;

/// What and how to render.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels (at most the model's `offwidth`).
    pub width: usize,
    /// Image height in pixels (at most the model's `offheight`).
    pub height: usize,
    /// Cast shadows (a second render pass per light: about 3x slower with llvmpipe).
    pub shadows: bool,
    /// Multisample anti-aliasing (`offsamples` of the model, 4 if it says 0).
    pub multisample: bool,
    /// A camera of the model by name, or `None` for MuJoCo's free camera framing the model.
    pub camera: Option<String>,
}

impl Default for RenderOptions {
    /// 640x480 (MuJoCo's default off-screen size), shadows and multisampling on, free camera.
    fn default() -> Self {
        RenderOptions {
            width: 640,
            height: 480,
            shadows: true,
            multisample: true,
            camera: None,
        }
    }
}

/// An OSMesa context with its own colour buffer.
struct OsMesa {
    ctx: NonNull<ffi::osmesa_context>,
    /// The default framebuffer OSMesa renders into (RGBA). MuJoCo draws into its own
    /// off-screen framebuffer object, but OSMesa needs a current buffer.
    buffer: Vec<u8>,
    width: c_int,
    height: c_int,
}

impl OsMesa {
    fn new(width: usize, height: usize) -> Result<OsMesa> {
        // Safety: plain constructor; a null share list is allowed. Returns null on failure.
        let ctx = unsafe {
            ffi::OSMesaCreateContextExt(ffi::OSMESA_RGBA, 24, 8, 0, std::ptr::null_mut())
        };
        let ctx = NonNull::new(ctx).ok_or_else(|| {
            RenderError::Context("OSMesaCreateContextExt failed (is libosmesa6 installed?)".into())
        })?;
        let mut gl = OsMesa {
            ctx,
            buffer: vec![0; width * height * 4],
            width: width as c_int,
            height: height as c_int,
        };
        gl.make_current()?;
        Ok(gl)
    }

    /// Make this context current on the calling thread (several renderers may share a thread).
    fn make_current(&mut self) -> Result<()> {
        // Safety: the context is alive; the buffer holds width*height RGBA bytes and lives as
        // long as the context (both owned by self; the Vec's heap block never moves).
        let ok = unsafe {
            ffi::OSMesaMakeCurrent(
                self.ctx.as_ptr(),
                self.buffer.as_mut_ptr().cast(),
                ffi::GL_UNSIGNED_BYTE,
                self.width,
                self.height,
            )
        };
        if ok == 0 {
            return Err(RenderError::Context("OSMesaMakeCurrent failed".into()));
        }
        Ok(())
    }
}

impl Drop for OsMesa {
    fn drop(&mut self) {
        // Safety: the context was created by OSMesaCreateContextExt and is destroyed once;
        // the GPU context using it has been freed before (see Renderer's Drop).
        unsafe { ffi::OSMesaDestroyContext(self.ctx.as_ptr()) }
    }
}

/// The abstract scene (`mjvScene`), freed with `mjv_freeScene` (no GL needed).
struct Scene(Box<ffi::mjvScene>);

impl Drop for Scene {
    fn drop(&mut self) {
        // Safety: the scene was made by mjv_makeScene (or only defaulted, which frees nothing).
        unsafe { ffi::mjv_freeScene(&mut *self.0) }
    }
}

/// Renders a [`Model`]'s state into images, off-screen, with no display.
///
/// Each renderer owns an OSMesa context and makes it current on every call, so several
/// renderers can live in one thread, and one renderer per thread in several threads.
/// A renderer is bound to its thread (it is neither `Send` nor `Sync`): an OpenGL context is
/// current on one thread at a time.
///
/// Shadows are a scene flag, switched at no cost by [`Renderer::set_shadows`];
/// multisampling is a property of MuJoCo's off-screen framebuffer, so
/// [`Renderer::set_multisample`] re-creates the GPU context (tens of milliseconds).
pub struct Renderer<'m> {
    model: &'m Model,
    scene: Scene,
    con: Box<ffi::mjrContext>,
    cam: ffi::mjvCamera,
    opt: ffi::mjvOption,
    width: usize,
    height: usize,
    multisample: bool,
    rgb: Vec<u8>,
    // Declared last: dropped after the GPU context is freed in Drop.
    gl: OsMesa,
}

impl std::fmt::Debug for Renderer<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Renderer")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("shadows", &self.shadows())
            .field("multisample", &self.multisample)
            .finish()
    }
}

impl<'m> Renderer<'m> {
    /// Create a renderer for `model`.
    ///
    /// Errors: a size of zero or larger than the model's `<visual><global offwidth
    /// offheight>`, an unknown camera name, or an OpenGL context that cannot be made.
    pub fn new(model: &'m Model, opts: RenderOptions) -> Result<Renderer<'m>> {
        crate::mujoco::check_version()?;
        let RenderOptions {
            width,
            height,
            shadows,
            multisample,
            camera,
        } = opts;
        if width == 0 || height == 0 {
            return Err(RenderError::EmptySize { width, height });
        }
        let (max_width, max_height) = model.offscreen_size();
        if width > max_width || height > max_height {
            return Err(RenderError::TooLarge {
                width,
                height,
                max_width,
                max_height,
            });
        }
        let camera_id = match &camera {
            None => None,
            Some(name) => Some(model.camera_id(name).ok_or_else(|| {
                let names: Vec<String> = (0..model.ncam())
                    .filter_map(|i| model.camera_name(i))
                    .collect();
                RenderError::CameraNotFound {
                    name: name.clone(),
                    available: if names.is_empty() {
                        "none".into()
                    } else {
                        names.join(", ")
                    },
                }
            })?),
        };

        let gl = OsMesa::new(width, height)?;

        // Safety: mjvScene is plain data; zero is a valid (empty) value before mjv_defaultScene.
        let mut scene = Scene(unsafe { zeroed_box::<ffi::mjvScene>() });
        callbacks::clear();
        // Safety: valid scene and model; MuJoCo allocates the geom buffers.
        unsafe {
            ffi::mjv_defaultScene(&mut *scene.0);
            ffi::mjv_makeScene(model.as_ptr(), &mut *scene.0, MAX_GEOM);
        }
        if let Some(message) = callbacks::take_error() {
            return Err(MjError::Runtime { message }.into());
        }

        let mut cam = ffi::mjvCamera::default();
        let mut opt = ffi::mjvOption::default();
        // Safety: valid out-pointers and model.
        unsafe {
            ffi::mjv_defaultOption(&mut opt);
            ffi::mjv_defaultCamera(&mut cam);
            match camera_id {
                Some(id) => {
                    cam.type_ = ffi::mjtCamera__mjCAMERA_FIXED as c_int;
                    cam.fixedcamid = id as c_int;
                }
                None => ffi::mjv_defaultFreeCamera(model.as_ptr(), &mut cam),
            }
        }

        let con = gpu_context(model, width, height, multisample)?;
        let mut renderer = Renderer {
            model,
            scene,
            con,
            cam,
            opt,
            width,
            height,
            multisample,
            rgb: vec![0; width * height * 3],
            gl,
        };
        renderer.set_shadows(shadows);
        Ok(renderer)
    }

    /// Image width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }
    /// Image height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }
    /// Whether shadows are drawn.
    pub fn shadows(&self) -> bool {
        self.scene.0.flags[ffi::mjtRndFlag__mjRND_SHADOW as usize] != 0
    }
    /// Whether multisampling is on.
    pub fn multisample(&self) -> bool {
        self.multisample
    }

    /// Switch shadows on or off (a scene flag: immediate, no re-creation).
    pub fn set_shadows(&mut self, on: bool) {
        self.scene.0.flags[ffi::mjtRndFlag__mjRND_SHADOW as usize] = u8::from(on);
    }

    /// Switch multisampling on or off. Re-creates MuJoCo's GPU context (its off-screen
    /// framebuffer has a fixed sample count); nothing happens when the setting is unchanged.
    pub fn set_multisample(&mut self, on: bool) -> Result<()> {
        if on == self.multisample {
            return Ok(());
        }
        self.gl.make_current()?;
        let con = gpu_context(self.model, self.width, self.height, on)?;
        let old = std::mem::replace(&mut self.con, con);
        free_gpu_context(old);
        // The new context is current after mjr_makeContext; nothing else refers to the old.
        self.multisample = on;
        Ok(())
    }

    /// Render `data` (its kinematics as of the last step or forward) into an image, top row
    /// first.
    pub fn render(&mut self, data: &Data) -> Result<RgbImage> {
        if !std::ptr::eq(data.model(), self.model) {
            return Err(RenderError::WrongModel);
        }
        self.gl.make_current()?;
        let viewport = ffi::mjrRect {
            left: 0,
            bottom: 0,
            width: self.width as c_int,
            height: self.height as c_int,
        };
        callbacks::clear();
        // Safety: this renderer's GL context is current; model, scene, camera, option and GPU
        // context are valid and were made for this model (checked above). mjv_updateScene takes
        // a mutable mjData: it only writes MuJoCo's scratch stack and warning counters, which no
        // Rust reference covers, and Data is not Sync, so no other thread reads it meanwhile.
        // `rgb` holds width*height*3 bytes, the size of the viewport read back.
        unsafe {
            ffi::mjv_updateScene(
                self.model.as_ptr(),
                data.as_ptr() as *mut ffi::mjData,
                &self.opt,
                std::ptr::null(),
                &mut self.cam,
                ffi::mjtCatBit__mjCAT_ALL as c_int,
                &mut *self.scene.0,
            );
            ffi::mjr_setBuffer(ffi::mjtFramebuffer__mjFB_OFFSCREEN as c_int, &mut *self.con);
            ffi::mjr_render(viewport, &mut *self.scene.0, &*self.con);
            ffi::mjr_readPixels(
                self.rgb.as_mut_ptr(),
                std::ptr::null_mut(),
                viewport,
                &*self.con,
            );
        }
        if let Some(message) = callbacks::take_error() {
            return Err(MjError::Runtime { message }.into());
        }
        // MuJoCo reads rows bottom-up: flip them.
        let row = self.width * 3;
        let mut pixels = Vec::with_capacity(self.rgb.len());
        for r in self.rgb.chunks_exact(row).rev() {
            pixels.extend_from_slice(r);
        }
        Ok(
            RgbImage::from_raw(self.width as u32, self.height as u32, pixels)
                .expect("buffer has width*height*3 bytes"),
        )
    }

    /// Render `data` and save the frame as a PNG at `path` (atomically).
    pub fn render_to_png(&mut self, data: &Data, path: &Path) -> Result<()> {
        let frame = self.render(data)?;
        save_png(&frame, path)
    }
}

impl Drop for Renderer<'_> {
    fn drop(&mut self) {
        // mjr_freeContext deletes GL objects by name on the *current* context: make ours
        // current first. If that fails, another renderer's context may be current, whose
        // objects must not be deleted: skip it. The GL objects die with the OSMesa context
        // below; only the small skin-buffer name arrays of a model with skins would leak.
        if self.gl.make_current().is_ok() {
            // Safety: `con` was made by gpu_context and is freed once, on its own GL context.
            unsafe { ffi::mjr_freeContext(&mut *self.con) }
        }
        // Then the fields drop: the scene (mjv_freeScene), and last the OSMesa context.
    }
}

/// Make MuJoCo's GPU context for `model` on the current GL context, off-screen buffer
/// selected, with or without multisampling, and with a shadow map.
///
/// The off-screen framebuffer is made exactly `width` x `height` (already checked against the
/// model's `offwidth` x `offheight`): llvmpipe clears and resolves the whole framebuffer every
/// frame, so a 1280x960 buffer for a 320x240 image would cost several times the render.
fn gpu_context(
    model: &Model,
    width: usize,
    height: usize,
    multisample: bool,
) -> Result<Box<ffi::mjrContext>> {
    // Safety: mjModel is a plain C struct (bindgen derives Copy); the shallow copy shares the
    // model's arrays, is only read by mjr_makeContext while `model` is borrowed, and is never
    // freed. Only its visual settings are changed: buffer size, samples and shadow size.
    let mut vis_model: ffi::mjModel = unsafe { *model.as_ptr() };
    vis_model.vis.global.offwidth = width as c_int;
    vis_model.vis.global.offheight = height as c_int;
    let quality = &mut vis_model.vis.quality;
    quality.offsamples = match (multisample, quality.offsamples) {
        (false, _) => 0,
        (true, 0) => DEFAULT_SAMPLES,
        (true, n) => n,
    };
    if quality.shadowsize == 0 {
        quality.shadowsize = DEFAULT_SHADOW_SIZE;
    }
    // Safety: mjrContext is plain data; zero is valid before mjr_defaultContext.
    let mut con = unsafe { zeroed_box::<ffi::mjrContext>() };
    callbacks::clear();
    // Safety: a GL context is current on this thread (callers make it so); `vis_model` is a
    // valid model (see above); `con` is a defaulted context.
    unsafe {
        ffi::mjr_defaultContext(&mut *con);
        ffi::mjr_makeContext(
            &vis_model,
            &mut *con,
            ffi::mjtFontScale__mjFONTSCALE_100 as c_int,
        );
        ffi::mjr_setBuffer(ffi::mjtFramebuffer__mjFB_OFFSCREEN as c_int, &mut *con);
    }
    let error = callbacks::take_error();
    if error.is_some() || con.currentBuffer != ffi::mjtFramebuffer__mjFB_OFFSCREEN as c_int {
        free_gpu_context(con);
        return Err(RenderError::Context(error.unwrap_or_else(|| {
            "MuJoCo could not select its off-screen framebuffer".into()
        })));
    }
    Ok(con)
}

/// Free a GPU context made by [`gpu_context`]; its GL context must be current.
fn free_gpu_context(mut con: Box<ffi::mjrContext>) {
    // Safety: `con` was defaulted (and perhaps made) by MuJoCo; freeing a defaulted context is
    // a no-op, and the caller made the owning GL context current.
    unsafe { ffi::mjr_freeContext(&mut *con) }
}

/// Save `image` as a PNG at `path`, atomically (temp file + rename).
pub fn save_png(image: &RgbImage, path: &Path) -> Result<()> {
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .map_err(|source| RenderError::Encode {
            what: "PNG",
            source,
        })?;
    crate::fsutil::write_atomic(path, &bytes).map_err(|source| RenderError::Io {
        path: path.to_path_buf(),
        source,
    })
}
