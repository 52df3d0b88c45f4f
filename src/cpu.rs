//! Runtime dispatch of the hottest loops to copies compiled for the x86-64 processors of the
//! last decade: the instructions of the x86-64-v3 level that the loops gain from (AVX and AVX2
//! for the distances of a block of points at once, BMI1, BMI2, LZCNT and POPCNT for the bit
//! masks of the candidates), chosen once per call by what the processor reports
//! ([`has_v3`]). The same source is compiled twice, so both copies compute the same values bit
//! for bit: Rust never fuses or reorders floating-point operations by itself, whatever the
//! target features (no fused multiply-add is enabled).
//!
//! Measured on the k-nearest self-join (16 nearest of each of 10^6 points on a surface, two
//! threads): a whole-program build for these features took 290-315 ms against 325-390 ms for
//! the baseline build; the dispatch gives the library's users that gain without a build flag.
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
