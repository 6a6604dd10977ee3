use std::cell::Cell;

thread_local! {
    /// The instruction set the kernels use on this thread (tests only).
    pub(crate) static FORCED: Cell<Option<pulp::Arch>> = const { Cell::new(None) };
}

/// Every instruction set this CPU can run: the x86-64 baseline (scalar lanes), AVX2, AVX-512.
pub(crate) fn available() -> Vec<pulp::Arch> {
    let mut v = vec![pulp::Arch::Scalar];
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    {
        v.extend(pulp::x86::V3::try_new().map(pulp::Arch::V3));
        v.extend(pulp::x86::V4::try_new().map(pulp::Arch::V4));
    }
    v
}

/// Run `f` with the kernels on each available instruction set in turn.
pub(crate) fn on_every_arch(mut f: impl FnMut(&str)) {
    for a in available() {
        FORCED.with(|c| c.set(Some(a)));
        f(&format!("{a:?}"));
    }
    FORCED.with(|c| c.set(None));
}
