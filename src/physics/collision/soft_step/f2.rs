//! Two lanes of f64 for `lanes`: add, subtract, multiply, negate and a per-lane select, each
//! lane's result the scalar operation's to the bit (SSE2 on x86-64, plain arrays elsewhere).

pub(super) use imp::F2;

/// Two lanes of f64 (SSE2 on x86-64, where every lane operation is the scalar one).
#[cfg(target_arch = "x86_64")]
mod imp {
    use std::arch::x86_64::*;

    #[derive(Debug, Clone, Copy)]
    pub struct F2(__m128d);

    impl F2 {
        #[inline(always)]
        pub fn new(x: f64, y: f64) -> F2 {
            // SAFETY: SSE2 is part of the x86-64 baseline.
            unsafe { F2(_mm_set_pd(y, x)) }
        }
        /// The SSE2 register.
        #[inline(always)]
        pub fn raw(self) -> __m128d {
            self.0
        }
        /// Of an SSE2 register.
        #[inline(always)]
        pub fn of_raw(x: __m128d) -> F2 {
            F2(x)
        }
        #[inline(always)]
        pub fn lane(self, i: usize) -> f64 {
            if i == 0 {
                // SAFETY: SSE2 is part of the x86-64 baseline.
                unsafe { _mm_cvtsd_f64(self.0) }
            } else {
                // SAFETY: SSE2 is part of the x86-64 baseline.
                unsafe { _mm_cvtsd_f64(_mm_unpackhi_pd(self.0, self.0)) }
            }
        }
        #[inline(always)]
        pub fn add(self, b: F2) -> F2 {
            // SAFETY: SSE2 is part of the x86-64 baseline.
            unsafe { F2(_mm_add_pd(self.0, b.0)) }
        }
        #[inline(always)]
        pub fn sub(self, b: F2) -> F2 {
            // SAFETY: SSE2 is part of the x86-64 baseline.
            unsafe { F2(_mm_sub_pd(self.0, b.0)) }
        }
        #[inline(always)]
        pub fn mul(self, b: F2) -> F2 {
            // SAFETY: SSE2 is part of the x86-64 baseline.
            unsafe { F2(_mm_mul_pd(self.0, b.0)) }
        }
        /// `−x`: the sign bit flipped, as the scalar negation does.
        #[inline(always)]
        pub fn neg(self) -> F2 {
            // SAFETY: SSE2 is part of the x86-64 baseline.
            unsafe { F2(_mm_xor_pd(self.0, _mm_set1_pd(-0.0))) }
        }
        /// Lane i of `new` where `live[i]`, else of `old` (bit for bit).
        #[inline(always)]
        pub fn pick(live: [bool; 2], new: F2, old: F2) -> F2 {
            // SAFETY: SSE2 is part of the x86-64 baseline.
            let m = unsafe {
                _mm_castsi128_pd(_mm_set_epi64x(-i64::from(live[1]), -i64::from(live[0])))
            };
            // SAFETY: SSE2 is part of the x86-64 baseline.
            unsafe { F2(_mm_or_pd(_mm_and_pd(m, new.0), _mm_andnot_pd(m, old.0))) }
        }
    }
}

/// Two lanes of f64 (plain arrays elsewhere).
#[cfg(not(target_arch = "x86_64"))]
mod imp {
    #[derive(Debug, Clone, Copy)]
    pub struct F2([f64; 2]);

    impl F2 {
        #[inline(always)]
        pub fn new(x: f64, y: f64) -> F2 {
            F2([x, y])
        }
        #[inline(always)]
        pub fn lane(self, i: usize) -> f64 {
            self.0[i]
        }
        #[inline(always)]
        pub fn add(self, b: F2) -> F2 {
            F2([self.0[0] + b.0[0], self.0[1] + b.0[1]])
        }
        #[inline(always)]
        pub fn sub(self, b: F2) -> F2 {
            F2([self.0[0] - b.0[0], self.0[1] - b.0[1]])
        }
        #[inline(always)]
        pub fn mul(self, b: F2) -> F2 {
            F2([self.0[0] * b.0[0], self.0[1] * b.0[1]])
        }
        #[inline(always)]
        pub fn neg(self) -> F2 {
            F2([-self.0[0], -self.0[1]])
        }
        #[inline(always)]
        pub fn pick(live: [bool; 2], new: F2, old: F2) -> F2 {
            let lane = |i: usize| if live[i] { new.0[i] } else { old.0[i] };
            F2([lane(0), lane(1)])
        }
    }
}
