//! MuJoCo's error and warning hooks: record the message for the calling thread.

use super::ffi;
use std::cell::RefCell;
use std::ffi::{c_char, CStr};

thread_local! {
    /// The first error MuJoCo raised on this thread since the last [`take_error`].
    static ERROR: RefCell<Option<String>> = const { RefCell::new(None) };
    /// Warnings MuJoCo raised on this thread since the last [`take_warnings`].
    static WARNINGS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Keep at most this many warnings per thread (MuJoCo warns once per kind and mjData anyway).
const MAX_WARNINGS: usize = 64;

fn message(msg: *const c_char) -> String {
    if msg.is_null() {
        return String::from("(MuJoCo gave no message)");
    }
    // Safety: MuJoCo passes a NUL-terminated string that lives for the duration of the call.
    unsafe { CStr::from_ptr(msg) }
        .to_string_lossy()
        .into_owned()
}

/// Errors after which MuJoCo 2.2 goes on with memory it does not have: `mj_stackAlloc` hands
/// out the overflowing block anyway, and the allocators return NULL to callers that then use
/// it. Returning from the hook would let MuJoCo write out of bounds, so for these the process
/// stops, as Rust itself does on stack overflow or allocation failure. Failures to allocate
/// OpenGL objects (framebuffers, display lists) only lead to further GL calls on invalid names,
/// which OpenGL ignores: those stay recoverable errors.
fn is_fatal(text: &str) -> bool {
    const GL_OBJECTS: [&str; 4] = [
        "offscreen",
        "display lists",
        "auxiliary",
        "shadow framebuffer",
    ];
    let lower = text.to_ascii_lowercase();
    lower.contains("stack overflow")
        || (lower.contains("could not allocate") && !GL_OBJECTS.iter().any(|g| lower.contains(g)))
}

/// The `mju_user_error` hook. Must not unwind: `try_with` and `try_borrow_mut` never panic,
/// and a message that cannot be stored (thread exiting, re-entrant call) is dropped.
unsafe extern "C" fn on_error(msg: *const c_char) {
    let text = message(msg);
    if is_fatal(&text) {
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "MuJoCo fatal error: {text}\n(MuJoCo 2.2 cannot continue safely after this error; \
             aborting. Increase <size nstack=...> in the MJCF for a stack overflow.)"
        );
        std::process::abort();
    }
    let _ = ERROR.try_with(|slot| {
        if let Ok(mut slot) = slot.try_borrow_mut() {
            slot.get_or_insert(text);
        }
    });
}

/// The `mju_user_warning` hook. Must not unwind (see [`on_error`]).
unsafe extern "C" fn on_warning(msg: *const c_char) {
    let text = message(msg);
    let _ = WARNINGS.try_with(|w| {
        if let Ok(mut w) = w.try_borrow_mut() {
            if w.len() < MAX_WARNINGS {
                w.push(text);
            }
        }
    });
}

/// Install the hooks (process-wide). Called once, from `check_version`.
pub(crate) fn install() {
    // Safety: the hooks are plain global function pointers of libmujoco, written once (inside
    // a OnceLock initialiser, before any model or state exists, so no MuJoCo call reads them
    // concurrently); the functions installed are `extern "C"`, never unwind, and stay valid
    // for the life of the process.
    unsafe {
        ffi::mju_user_error = Some(on_error);
        ffi::mju_user_warning = Some(on_warning);
    }
}

/// Take the error MuJoCo raised on this thread, if any.
pub(crate) fn take_error() -> Option<String> {
    ERROR.with(|slot| slot.borrow_mut().take())
}

/// Take the warnings MuJoCo raised on this thread.
pub(crate) fn take_warnings() -> Vec<String> {
    WARNINGS.with(|w| std::mem::take(&mut *w.borrow_mut()))
}

/// Forget errors and warnings left over from earlier calls on this thread.
pub(crate) fn clear() {
    let _ = take_error();
    let _ = take_warnings();
}

#[cfg(test)]
mod tests;
