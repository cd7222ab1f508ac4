//! Which build of a hot loop to run: the cloth's stencils and solves and soft-step's sub-steps
//! are compiled twice, once with AVX2 (`#[target_feature(enable = "avx2")]`, no fused
//! multiply–add, so both builds give the same bits) and once plain; [`avx2`] picks at run time.

/// Whether to run the AVX2 builds: true only when the CPU has AVX2 (with the OS's support for
/// its registers, as `is_x86_feature_detected` checks); a test may switch them off on its
/// thread ([`set_plain`]) to compare the two builds' bits.
#[cfg(target_arch = "x86_64")]
#[inline]
pub(crate) fn avx2() -> bool {
    #[cfg(test)]
    if PLAIN.with(std::cell::Cell::get) {
        return false;
    }
    std::arch::is_x86_feature_detected!("avx2")
}

#[cfg(test)]
thread_local! {
    /// Tests: run the plain builds on this thread even on a CPU with AVX2.
    static PLAIN: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Tests: run the plain builds on this thread (`true`) or the AVX2 ones where the CPU has it.
#[cfg(test)]
pub(crate) fn set_plain(plain: bool) {
    PLAIN.with(|p| p.set(plain));
}
