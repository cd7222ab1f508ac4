//! Four lanes of f64 for `lanes`' pairs of runs between two bodies each: lanes
//! `[A of run x, A of run y, B of run x, B of run y]`, so that a pair of rows keeps its four
//! bodies' v and ω in six registers (`Quad`). Each lane's add, subtract and multiply is the
//! scalar operation's to the bit.
//!
//! Two builds, as everything after detection (`physics::simd`): [`Avx`] (one AVX register,
//! taken only inside the AVX2 build, where its intrinsics inline) and [`Plain`] (two SSE2
//! halves, any x86-64 CPU; plain arrays elsewhere). Both give the same bits.

use super::f2::F2;

/// Four lanes of f64: the two halves `lo` (lanes 0, 1) and `hi` (lanes 2, 3) are two lanes of
/// [`F2`].
pub(super) trait Quad: Copy {
    /// Lanes `[lo₀, lo₁, hi₀, hi₁]`.
    fn join(lo: F2, hi: F2) -> Self;
    /// The four numbers `x` as lanes 0..4.
    fn load(x: &[f64; 4]) -> Self;
    fn lo(self) -> F2;
    fn hi(self) -> F2;
    fn add(self, b: Self) -> Self;
    fn mul(self, b: Self) -> Self;
    /// Lanes 2 and 3 negated (the sign bit flipped, as the scalar negation does).
    fn neg_hi(self) -> Self;
    /// Lanes 0 and 2 of `new` where `live[0]`, 1 and 3 where `live[1]`, the others of `old`.
    fn pick(live: [bool; 2], new: Self, old: Self) -> Self;
    /// The four lanes (tests).
    #[cfg(test)]
    fn lanes(self) -> [f64; 4];
}

/// Two halves of SSE2 (or plain arrays): any CPU.
#[derive(Debug, Clone, Copy)]
pub(super) struct Plain(F2, F2);

impl Quad for Plain {
    #[inline(always)]
    fn join(lo: F2, hi: F2) -> Self {
        Plain(lo, hi)
    }
    #[inline(always)]
    fn load(x: &[f64; 4]) -> Self {
        Plain(F2::new(x[0], x[1]), F2::new(x[2], x[3]))
    }
    #[inline(always)]
    fn lo(self) -> F2 {
        self.0
    }
    #[inline(always)]
    fn hi(self) -> F2 {
        self.1
    }
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        Plain(self.0.add(b.0), self.1.add(b.1))
    }
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        Plain(self.0.mul(b.0), self.1.mul(b.1))
    }
    #[inline(always)]
    fn neg_hi(self) -> Self {
        Plain(self.0, self.1.neg())
    }
    #[inline(always)]
    fn pick(live: [bool; 2], new: Self, old: Self) -> Self {
        Plain(F2::pick(live, new.0, old.0), F2::pick(live, new.1, old.1))
    }
    #[cfg(test)]
    fn lanes(self) -> [f64; 4] {
        [self.0.lane(0), self.0.lane(1), self.1.lane(0), self.1.lane(1)]
    }
}

#[cfg(target_arch = "x86_64")]
pub(super) use avx::Avx;

/// One AVX register. Its functions are only called from the AVX2 build of the sweeps
/// (`soft_step::solve_avx2`, checked at run time), into which they and their intrinsics inline.
#[cfg(target_arch = "x86_64")]
mod avx {
    use super::{Quad, F2};
    use std::arch::x86_64::*;

    #[derive(Debug, Clone, Copy)]
    pub struct Avx(__m256d);

    impl Quad for Avx {
        #[inline(always)]
        fn join(lo: F2, hi: F2) -> Self {
            // SAFETY: only run where the CPU has AVX2 (module doc).
            unsafe { Avx(_mm256_set_m128d(hi.raw(), lo.raw())) }
        }
        #[inline(always)]
        fn load(x: &[f64; 4]) -> Self {
            // SAFETY: only run where the CPU has AVX2; x is four f64.
            unsafe { Avx(_mm256_loadu_pd(x.as_ptr())) }
        }
        #[inline(always)]
        fn lo(self) -> F2 {
            // SAFETY: only run where the CPU has AVX2.
            unsafe { F2::of_raw(_mm256_castpd256_pd128(self.0)) }
        }
        #[inline(always)]
        fn hi(self) -> F2 {
            // SAFETY: only run where the CPU has AVX2.
            unsafe { F2::of_raw(_mm256_extractf128_pd::<1>(self.0)) }
        }
        #[inline(always)]
        fn add(self, b: Self) -> Self {
            // SAFETY: only run where the CPU has AVX2.
            unsafe { Avx(_mm256_add_pd(self.0, b.0)) }
        }
        #[inline(always)]
        fn mul(self, b: Self) -> Self {
            // SAFETY: only run where the CPU has AVX2.
            unsafe { Avx(_mm256_mul_pd(self.0, b.0)) }
        }
        #[inline(always)]
        fn neg_hi(self) -> Self {
            // SAFETY: only run where the CPU has AVX2.
            unsafe { Avx(_mm256_xor_pd(self.0, _mm256_set_pd(-0.0, -0.0, 0.0, 0.0))) }
        }
        #[inline(always)]
        fn pick(live: [bool; 2], new: Self, old: Self) -> Self {
            let (x, y) = (-i64::from(live[0]), -i64::from(live[1]));
            // SAFETY: only run where the CPU has AVX2.
            unsafe {
                let mask = _mm256_castsi256_pd(_mm256_set_epi64x(y, x, y, x));
                Avx(_mm256_blendv_pd(old.0, new.0, mask))
            }
        }
        #[cfg(test)]
        fn lanes(self) -> [f64; 4] {
            let mut out = [0.0; 4];
            // SAFETY: only run where the CPU has AVX2; out is four f64.
            unsafe { _mm256_storeu_pd(out.as_mut_ptr(), self.0) };
            out
        }
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;

    /// The AVX register and the two halves give the same lanes, bit for bit, for every
    /// operation (on a CPU with AVX2).
    #[test]
    fn both_builds_give_the_same_lanes() {
        if !crate::physics::simd::avx2() {
            return;
        }
        let x = [1.5, -0.0, 3.0e-300, 7.25];
        let y = [0.1, 2.0, -1.0e300, -7.25];
        let check = |a: [f64; 4], b: [f64; 4]| {
            assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
        };
        let (p, q) = (Plain::load(&x), Plain::load(&y));
        let (a, b) = (Avx::load(&x), Avx::load(&y));
        check(p.add(q).lanes(), a.add(b).lanes());
        check(p.mul(q).lanes(), a.mul(b).lanes());
        check(p.neg_hi().lanes(), a.neg_hi().lanes());
        check(p.neg_hi().lanes(), [x[0], x[1], -x[2], -x[3]]);
        for live in [[true, false], [false, true], [true, true], [false, false]] {
            check(Plain::pick(live, p, q).lanes(), Avx::pick(live, a, b).lanes());
        }
        let j = Avx::join(p.hi(), p.lo());
        check(Plain::join(p.hi(), p.lo()).lanes(), j.lanes());
        check(
            [a.lo().lane(0), a.lo().lane(1), a.hi().lane(0), a.hi().lane(1)],
            x,
        );
    }
}
