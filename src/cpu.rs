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
