//! Runtime dispatch of the hottest loops to copies compiled for the x86-64 processors of the
//! last decade: the instructions of the x86-64-v3 level that the loops gain from (AVX and AVX2
//! for the distances of a block of points at once, BMI1, BMI2, LZCNT and POPCNT for the bit
//! masks of the candidates), and for the radius joins' leaf kernel those of the v4 level too
//! (AVX-512: the eight distances of a block's lane group in one vector), chosen once per call
//! by what the processor reports ([`has_v3`], [`has_v4`]). The same source is compiled twice, so both copies compute the same values bit
//! for bit: Rust never fuses or reorders floating-point operations by itself, whatever the
//! target features (no fused multiply-add is enabled).
//!
//! Measured on the k-nearest self-join (16 nearest of each of 10^6 points on a surface, two
//! threads): a whole-program build for the v3 features took 290-315 ms against 325-390 ms for
//! the baseline build, and the dispatch 289-298 against 321-336 (AVX-512 gave the self-join
//! nothing more). On all pairs within a radius (about 10 per point, 10^6 points, one thread)
//! the v3 copy gained 3%, the v4 copy 9% (107-110 ms against 117-121). The dispatch gives the
//! library's users these gains without a build flag.
//! A copy is entered through an `unsafe` call (a function compiled for instructions the
//! processor may lack); [`has_v3`] is checked before each, and the tests run both copies on
//! the same inputs and compare their answers.

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
