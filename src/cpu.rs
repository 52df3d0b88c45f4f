//! Runtime dispatch of the hottest loops to copies compiled for the x86-64 processors of the
//! last decade: the instructions of the x86-64-v3 level that the loops gain from (AVX and AVX2
//! for the distances of a block of points at once, BMI1, BMI2, LZCNT and POPCNT for the bit
//! masks of the candidates), and for the radius joins' leaf kernel those of the v4 level too
//! (AVX-512: the eight distances of a block's lane group in one vector), chosen once per call
//! by what the processor reports ([`has_v3`], [`has_v4`]); the radius kernel has a v3 copy
//! too, for the processors with AVX2 and without AVX-512. The same source is compiled into
//! each copy ([`compiled_copy`]), so all copies compute the same values bit for bit: Rust
//! never fuses or reorders floating-point operations by itself, whatever the target features
//! (no fused multiply-add is enabled).
//!
//! Measured on the k-nearest self-join (16 nearest of each of 10^6 points on a surface, two
//! threads): a whole-program build for the v3 features took 290-315 ms against 325-390 ms for
//! the baseline build, and the dispatch 289-298 against 321-336 (AVX-512 gave the self-join
//! nothing more). On all pairs within a radius (about 10 per point, 10^6 points, one thread)
//! on a processor with AVX-512 the v3 copy gained 3%, the v4 copy 9% (107-110 ms against
//! 117-121); on an AMD EPYC with AVX2 and without AVX-512 the v3 copy
//! gained 3% (151-155 ms against 156-158, a whole-program v3 build 148-150). The dispatch
//! gives the library's users these gains without a build flag.
//! A copy is entered through an `unsafe` call (a function compiled for instructions the
//! processor may lack); [`has_v3`] or [`has_v4`] is checked before each, and the tests run
//! every copy the processor has on the same inputs as the baseline copy and compare answers.

/// Whether this processor has every feature the fast copies are compiled with (their
/// `#[target_feature(enable = "avx,avx2,bmi1,bmi2,lzcnt,popcnt")]`); always `false` off
/// x86-64.
#[inline]
pub(crate) fn has_v3() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("avx")
            && std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("bmi1")
            && std::is_x86_feature_detected!("bmi2")
            && std::is_x86_feature_detected!("lzcnt")
            && std::is_x86_feature_detected!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Whether this processor also has the AVX-512 features the radius joins' copy is compiled
/// with (`avx512f,avx512vl,avx512bw,avx512dq` beside those of [`has_v3`]); always `false` off
/// x86-64.
#[inline]
pub(crate) fn has_v4() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        has_v3()
            && std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512vl")
            && std::is_x86_feature_detected!("avx512bw")
            && std::is_x86_feature_detected!("avx512dq")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Defines a copy of a function compiled for a level's target features: `name = work for
/// "features", [generics] (arguments) -> output` makes `fn name`, which calls the
/// `#[inline(always)]` function `work` with its arguments, so that `work`'s body is compiled
/// into it for those features. Calling the copy is `unsafe`: the caller checks [`has_v3`] or
/// [`has_v4`] first.
macro_rules! compiled_copy {
    (
        $(#[$attr:meta])*
        $name:ident = $work:ident for $features:literal,
        [$($generics:tt)*] ($($arg:ident: $ty:ty),* $(,)?) $(-> $out:ty)?
        $(where [$($bounds:tt)*])?
    ) => {
        $(#[$attr])*
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $features)]
        #[allow(clippy::too_many_arguments)]
        fn $name<$($generics)*>($($arg: $ty),*) $(-> $out)? $(where $($bounds)*)? {
            $work($($arg),*)
        }
    };
}
pub(crate) use compiled_copy;

/// The comparison of a lane group's eight distances with one bound, packed into the bits of a
/// byte: the step of the radius joins' kernel that each copy compiles its own way. The
/// portable form packs the eight answers by a multiplication, which the compiler turns into a
/// long run of shuffles; the AVX form is two compares and two sign-bit extractions.
pub(crate) trait Compare: Copy {
    /// Bit `l` set when `d[l] <= bound` (never for a NaN, as `<=`).
    fn le_bits(self, d: &[f64; 8], bound: f64) -> u64;
}

/// The comparison in plain Rust, for every processor.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Portable;

impl Compare for Portable {
    #[inline(always)]
    fn le_bits(self, d: &[f64; 8], bound: f64) -> u64 {
        let hit: [u8; 8] = core::array::from_fn(|l| u8::from(d[l] <= bound));
        // Byte `l`'s low bit lands on bit `56 + l`: every partial product on a distinct bit.
        u64::from_le_bytes(hit).wrapping_mul(0x0102_0408_1020_4080) >> 56
    }
}

/// The comparison by AVX instructions; a value exists only where [`has_v3`] found them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx(());

impl Avx {
    /// The token, when this processor has the features of the v3 copies.
    #[inline]
    pub(crate) fn detected() -> Option<Avx> {
        has_v3().then_some(Avx(()))
    }
}

impl Compare for Avx {
    #[inline(always)]
    fn le_bits(self, d: &[f64; 8], bound: f64) -> u64 {
        #[cfg(target_arch = "x86_64")]
        {
            // SAFETY: an `Avx` is made only by `Avx::detected`, after `has_v3` found AVX.
            #[allow(unsafe_code)]
            unsafe {
                le_bits_avx(d, bound)
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            Portable.le_bits(d, bound)
        }
    }
}

/// [`Compare::le_bits`] by AVX: `_CMP_LE_OQ` is `<=` with NaN false, as in Rust.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
fn le_bits_avx(d: &[f64; 8], bound: f64) -> u64 {
    use core::arch::x86_64::{
        _mm256_cmp_pd, _mm256_movemask_pd, _mm256_set1_pd, _mm256_set_pd, _CMP_LE_OQ,
    };
    let b = _mm256_set1_pd(bound);
    let lo = _mm256_set_pd(d[3], d[2], d[1], d[0]);
    let hi = _mm256_set_pd(d[7], d[6], d[5], d[4]);
    let lo = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(lo, b));
    let hi = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(hi, b));
    (lo | hi << 4) as u64
}

/// Which copy of the radius kernel this processor runs, with the token of the comparison the
/// fast copies use. Made only by [`Level::detected`] (and, for the tests, by
/// `Level::fast_available`), so a fast level exists only where the processor has its features.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Level(Tier);

/// The levels, private so that none is made without the check.
#[derive(Clone, Copy, Debug)]
enum Tier {
    Baseline,
    V3(Avx),
    V4(Avx),
}

impl Level {
    /// The baseline copy, which every processor runs.
    #[cfg(test)]
    pub(crate) const BASELINE: Level = Level(Tier::Baseline);

    /// The fastest level this processor has.
    #[inline]
    pub(crate) fn detected() -> Level {
        match Avx::detected() {
            Some(avx) if has_v4() => Level(Tier::V4(avx)),
            Some(avx) => Level(Tier::V3(avx)),
            None => Level(Tier::Baseline),
        }
    }

    /// Every fast level this processor can run (none, v3, or v3 and v4).
    #[cfg(test)]
    pub(crate) fn fast_available() -> Vec<Level> {
        let mut out = Vec::new();
        if let Some(avx) = Avx::detected() {
            out.push(Level(Tier::V3(avx)));
            if has_v4() {
                out.push(Level(Tier::V4(avx)));
            }
        }
        out
    }

    /// The comparison token of the fast copies; `None` at the baseline.
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    #[inline]
    pub(crate) fn avx(self) -> Option<Avx> {
        match self.0 {
            Tier::Baseline => None,
            Tier::V3(avx) | Tier::V4(avx) => Some(avx),
        }
    }

    /// Whether the AVX-512 copy may run: only for a level made after [`has_v4`] found its
    /// features.
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    #[inline]
    pub(crate) fn v4(self) -> bool {
        matches!(self.0, Tier::V4(_))
    }
}

#[cfg(test)]
mod tests {
    use super::{Avx, Compare, Portable};

    /// The AVX comparison answers as the portable one on ties, signed zeros, infinities, NaN
    /// and subnormals, lane by lane.
    #[test]
    fn the_avx_comparison_agrees_with_the_portable_one() {
        let Some(avx) = Avx::detected() else {
            return;
        };
        let values = [
            0.0,
            -0.0,
            f64::from_bits(1),
            1.0,
            1.0f64.next_up(),
            1.0f64.next_down(),
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let mut checked = 0;
        for &bound in &values {
            for rot in 0..values.len() {
                let d: [f64; 8] = core::array::from_fn(|l| values[(l + rot) % values.len()]);
                let want = Portable.le_bits(&d, bound);
                assert_eq!(avx.le_bits(&d, bound), want, "bound {bound} d {d:?}");
                checked += u64::from(want.count_ones());
            }
        }
        assert!(checked > 0);
    }
}
