use super::*;

#[test]
fn mju_error_is_recorded_for_the_calling_thread_and_returns() {
    crate::mujoco::check_version().unwrap();
    clear();
    let msg = std::ffi::CString::new("synthetic error for the test").unwrap();
    // Safety: our hook is installed (check_version); it records and returns.
    unsafe { ffi::mju_error(msg.as_ptr()) };
    assert_eq!(
        take_error().as_deref(),
        Some("synthetic error for the test")
    );
    assert_eq!(take_error(), None, "taking the error clears it");
    let other = std::thread::spawn(take_error).join().unwrap();
    assert_eq!(other, None, "errors are per thread");
}

#[test]
fn mju_warning_is_recorded() {
    crate::mujoco::check_version().unwrap();
    clear();
    let msg = std::ffi::CString::new("synthetic warning").unwrap();
    // Safety: our hook is installed; it records and returns.
    unsafe { ffi::mju_warning(msg.as_ptr()) };
    assert_eq!(take_warnings(), vec!["synthetic warning".to_string()]);
}

#[test]
fn fatal_messages_are_recognised() {
    assert!(is_fatal("Stack overflow: max = 1000"));
    assert!(is_fatal("Could not allocate mjData buffer"));
    assert!(is_fatal("mj_makeEmptyFileVFS: could not allocate memory"));
    assert!(!is_fatal("Could not allocate offscreen framebuffer"));
    assert!(!is_fatal("Pre-allocated contact buffer is full"));
}
