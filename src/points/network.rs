//! Sorting networks for the short runs the radix sort (`radix.rs`) leaves behind: Batcher's
//! odd-even merge sort ("Sorting networks and their applications", AFIPS Spring Joint Computer
//! Conference, 1968) for 8, 16 and 32 inputs, the run padded with the greatest value.
//!
//! A uniform 2D build ends with about 65 000 runs of some 15 keys. The standard library sorts runs
//! that short by insertion, whose exits are data-dependent branches that mispredict about once a
//! key (about 9 ns a key on the development machine); a network compares fixed positions with
//! branch-free minimum and maximum, 63 comparators for 16 inputs, and sorts the same runs in
//! under half the time. From 24 keys up the standard library's own networks are as fast.

/// The comparators of Batcher's odd-even merge sort for `n` inputs (a power of two, at most 32),
/// in order, and how many there are.
const fn batcher(n: usize) -> ([(u8, u8); 191], usize) {
    let mut pairs = [(0u8, 0u8); 191];
    let mut count = 0;
    let mut p = 1;
    while p < n {
        let mut k = p;
        while k >= 1 {
            let mut j = k % p;
            while j + k < n {
                let mut i = 0;
                while i < k && i + j + k < n {
                    // only within one merged block of 2p inputs
                    if (i + j) / (2 * p) == (i + j + k) / (2 * p) {
                        pairs[count] = ((i + j) as u8, (i + j + k) as u8);
                        count += 1;
                    }
                    i += 1;
                }
                j += 2 * k;
            }
            k /= 2;
        }
        p *= 2;
    }
    (pairs, count)
}

const NET8: ([(u8, u8); 191], usize) = batcher(8);
const NET16: ([(u8, u8); 191], usize) = batcher(16);
const NET32: ([(u8, u8); 191], usize) = batcher(32);

/// The longest run [`sort_short`] sorts with a network; longer ones go to `sort_unstable`.
pub(super) const NETWORK_MAX: usize = 23;

/// Sorts `run` (any length): by a network when it has at most [`NETWORK_MAX`] values, else by
/// `sort_unstable`. `greatest` must be at least every value (it pads the network's inputs).
#[inline]
pub(super) fn sort_short<P: Copy + Ord>(run: &mut [P], greatest: P) {
    match run.len() {
        0..=1 => {}
        2..=8 => through::<P, 8>(run, greatest, &NET8.0[..NET8.1]),
        9..=16 => through::<P, 16>(run, greatest, &NET16.0[..NET16.1]),
        17..=NETWORK_MAX => through::<P, 32>(run, greatest, &NET32.0[..NET32.1]),
        _ => run.sort_unstable(),
    }
}

/// Sorts `run` (at most `N` values) through the network `pairs` for `N` inputs.
#[inline(always)]
fn through<P: Copy + Ord, const N: usize>(run: &mut [P], greatest: P, pairs: &[(u8, u8)]) {
    let mut v = [greatest; N];
    v[..run.len()].copy_from_slice(run);
    for &(i, j) in pairs {
        let (a, b) = (v[i as usize], v[j as usize]);
        v[i as usize] = a.min(b);
        v[j as usize] = a.max(b);
    }
    run.copy_from_slice(&v[..run.len()]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn the_networks_have_batchers_sizes() {
        assert_eq!((NET8.1, NET16.1, NET32.1), (19, 63, 191));
    }

    /// The 0-1 principle: a network that sorts every sequence of zeros and ones sorts every
    /// sequence; checked for every length up to 16, every 0-1 input.
    #[test]
    fn sorts_every_zero_one_input_up_to_16() {
        for m in 0..=16usize {
            for bits in 0..1u32 << m {
                let mut run: Vec<u8> = (0..m).map(|i| (bits >> i & 1) as u8).collect();
                let mut expected = run.clone();
                expected.sort_unstable();
                sort_short(&mut run, u8::MAX);
                assert_eq!(run, expected, "length {m}, input {bits:b}");
            }
        }
    }

    #[test]
    fn sorts_random_runs_with_repeats_and_extremes() {
        let mut rng = rand::rngs::SmallRng::seed_from_u64(11);
        for m in 0..=40usize {
            for _ in 0..500 {
                let mut run: Vec<u64> = (0..m)
                    .map(|_| match rng.gen_range(0..4) {
                        0 => u64::MAX,
                        1 => rng.gen_range(0..4),
                        _ => rng.gen(),
                    })
                    .collect();
                let mut expected = run.clone();
                expected.sort_unstable();
                sort_short(&mut run, u64::MAX);
                assert_eq!(run, expected);
            }
        }
    }
}
