//! Morton (z-order) keys: interleaving the bits of D integer coordinates into one `u64`.
//!
//! Bit `j` of the coordinate on axis `a` becomes bit `j * D + a` of the key, so that at every level
//! the D bits of a cell's child index (bit `a` set for the upper half along axis `a`, the numbering
//! of DESIGN.md and of p4est) form one digit. Sorting by key lists cells and points in z-order.
//! D = 2 and D = 3 use the classic magic-number bit spreading; other D a per-bit loop.

/// Interleaves the low `bits` bits of each coordinate; `bits * D` must be at most 64.
///
/// ```
/// use orthtree::geom::morton::{interleave, deinterleave};
/// // x = 0b01, y = 0b10: digits (y1 x1)(y0 x0) = (1 0)(0 1)
/// assert_eq!(interleave([0b01, 0b10], 2), 0b1001);
/// assert_eq!(deinterleave::<2>(0b1001, 2), [0b01, 0b10]);
/// ```
#[inline]
pub fn interleave<const D: usize>(coords: [u32; D], bits: u32) -> u64 {
    debug_assert!(bits as usize * D <= 64);
    coords.iter().enumerate().fold(0, |key, (a, &c)| {
        key | spread::<D>(mask(c as u64, bits)) << a
    })
}

/// The low `64 / D` bits of `v` spread to every `D`-th bit from bit 0 (for D = 1, `v` itself):
/// `spread::<D>(c) << a` is the coordinate `c` on axis `a` in a key, so OR-ing those over the
/// axes is [`interleave`] at the finest level. Lets a caller build keys one axis at a time.
#[inline]
pub(crate) fn spread<const D: usize>(v: u64) -> u64 {
    match D {
        1 => v,
        2 => spread2(v),
        3 => spread3(v),
        _ => {
            let bits = 64 / D as u32;
            (0..bits).fold(0, |key, j| key | ((v >> j) & 1) << (j as usize * D))
        }
    }
}

/// The inverse of [`interleave`].
#[inline]
pub fn deinterleave<const D: usize>(key: u64, bits: u32) -> [u32; D] {
    let mut coords = [0u32; D];
    for j in 0..bits {
        for (a, c) in coords.iter_mut().enumerate() {
            *c |= (((key >> (j as usize * D + a)) & 1) as u32) << j;
        }
    }
    coords
}

#[inline]
fn mask(v: u64, bits: u32) -> u64 {
    v & u64::MAX.checked_shr(64 - bits.min(64)).unwrap_or(0)
}

/// Spreads the low 32 bits of `v` to the even bit positions.
#[inline]
fn spread2(mut v: u64) -> u64 {
    v &= 0xFFFF_FFFF;
    v = (v | (v << 16)) & 0x0000_FFFF_0000_FFFF;
    v = (v | (v << 8)) & 0x00FF_00FF_00FF_00FF;
    v = (v | (v << 4)) & 0x0F0F_0F0F_0F0F_0F0F;
    v = (v | (v << 2)) & 0x3333_3333_3333_3333;
    (v | (v << 1)) & 0x5555_5555_5555_5555
}

/// Spreads the low 21 bits of `v` to every third bit position.
#[inline]
fn spread3(mut v: u64) -> u64 {
    v &= 0x1F_FFFF;
    v = (v | (v << 32)) & 0x001F_0000_0000_FFFF;
    v = (v | (v << 16)) & 0x001F_0000_FF00_00FF;
    v = (v | (v << 8)) & 0x100F_00F0_0F00_F00F;
    v = (v | (v << 4)) & 0x10C3_0C30_C30C_30C3;
    (v | (v << 2)) & 0x1249_2492_4924_9249
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn slow<const D: usize>(coords: [u32; D], bits: u32) -> u64 {
        let mut key = 0u64;
        for j in 0..bits {
            for (a, &c) in coords.iter().enumerate() {
                key |= (((c >> j) & 1) as u64) << (j as usize * D + a);
            }
        }
        key
    }

    #[test]
    fn fast_paths_match_the_bit_loop() {
        let mut rng = rand::rngs::SmallRng::seed_from_u64(7);
        for _ in 0..10_000 {
            let c2 = [rng.r#gen::<u32>(), rng.r#gen::<u32>()];
            assert_eq!(interleave(c2, 32), slow(c2, 32));
            assert_eq!(deinterleave::<2>(interleave(c2, 32), 32), c2);
            let c3 = [
                rng.r#gen::<u32>() >> 11,
                rng.r#gen::<u32>() >> 11,
                rng.r#gen::<u32>() >> 11,
            ];
            assert_eq!(interleave(c3, 21), slow(c3, 21));
            assert_eq!(deinterleave::<3>(interleave(c3, 21), 21), c3);
            let c5 = [rng.r#gen::<u32>() & 0xFFF; 5];
            assert_eq!(deinterleave::<5>(interleave(c5, 12), 12), c5);
        }
        assert_eq!(interleave([u32::MAX], 32), u32::MAX as u64);
    }
}
