//! Sorting networks for the short runs the radix sort (`radix.rs`) leaves behind: Batcher's
//! odd-even merge sort ("Sorting networks and their applications", AFIPS Spring Joint Computer
//! Conference, 1968) for 8, 16 and 32 inputs, the run padded with the greatest value.
//!
//! A uniform 2D build ends with about 65 000 runs of some 15 keys. The standard library sorts runs
//! that short by insertion, whose exits are data-dependent branches that mispredict about once a
//! key (about 9 ns a key on the development machine); a network compares fixed positions with
//! branch-free minimum and maximum, 63 comparators for 16 inputs, and sorts the same runs in
//! under half the time. From 24 keys up the standard library's own networks are as fast.
//!
//! The networks for 8 and 16 inputs are written out comparator by comparator (`unrolled!`),
//! so that the values stay in registers: looping over a table of comparators goes through
//! memory and was 20% slower on the whole sort. A test checks them against `batcher`.

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

const NET32: ([(u8, u8); 191], usize) = batcher(32);

/// `unrolled!(name, PAIRS, n; (i, j), ...)` defines `fn name(run, greatest)`, which sorts a run
/// of at most `n` values through the comparators `(i, j)` written out one by one, and (in tests)
/// the list `PAIRS` of them.
macro_rules! unrolled {
    ($name:ident, $pairs:ident, $n:literal; $(($i:literal, $j:literal)),* $(,)?) => {
        #[cfg(test)]
        const $pairs: &[(u8, u8)] = &[$(($i, $j)),*];

        #[inline(always)]
        fn $name<P: Copy + Ord>(run: &mut [P], greatest: P) {
            let mut v = [greatest; $n];
            v[..run.len()].copy_from_slice(run);
            $(
                let (a, b) = (v[$i], v[$j]);
                v[$i] = a.min(b);
                v[$j] = a.max(b);
            )*
            run.copy_from_slice(&v[..run.len()]);
        }
    };
}

unrolled!(sort8, NET8, 8;
    (0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7), (1, 2), (5, 6), (0, 4),
    (1, 5), (2, 6), (3, 7), (2, 4), (3, 5), (1, 2), (3, 4), (5, 6),
);

unrolled!(sort16, NET16, 16;
    (0, 1), (2, 3), (4, 5), (6, 7), (8, 9), (10, 11), (12, 13), (14, 15), (0, 2), (1, 3), (4, 6),
    (5, 7), (8, 10), (9, 11), (12, 14), (13, 15), (1, 2), (5, 6), (9, 10), (13, 14), (0, 4),
    (1, 5), (2, 6), (3, 7), (8, 12), (9, 13), (10, 14), (11, 15), (2, 4), (3, 5), (10, 12),
    (11, 13), (1, 2), (3, 4), (5, 6), (9, 10), (11, 12), (13, 14), (0, 8), (1, 9), (2, 10),
    (3, 11), (4, 12), (5, 13), (6, 14), (7, 15), (4, 8), (5, 9), (6, 10), (7, 11), (2, 4), (3, 5),
    (6, 8), (7, 9), (10, 12), (11, 13), (1, 2), (3, 4), (5, 6), (7, 8), (9, 10), (11, 12),
    (13, 14),
);

/// The longest run [`sort_short`] sorts with a network; longer ones go to `sort_unstable`.
pub(super) const NETWORK_MAX: usize = 23;

/// Sorts `run` (any length): by a network when it has at most [`NETWORK_MAX`] values, else by
/// `sort_unstable`. `greatest` must be at least every value (it pads the network's inputs).
#[inline]
pub(super) fn sort_short<P: Copy + Ord>(run: &mut [P], greatest: P) {
    match run.len() {
        0..=1 => {}
        2..=8 => sort8(run, greatest),
        9..=16 => sort16(run, greatest),
        17..=NETWORK_MAX => through::<P, 32>(run, greatest, &NET32.0[..NET32.1]),
        _ => run.sort_unstable(),
    }
}

/// Sorts `run` (at most `N` values) through the network `pairs` for `N` inputs, a table.
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
    fn the_networks_are_batchers() {
        let (eight, sixteen) = (batcher(8), batcher(16));
        assert_eq!(NET8, &eight.0[..eight.1]);
        assert_eq!(NET16, &sixteen.0[..sixteen.1]);
        assert_eq!((NET8.len(), NET16.len(), NET32.1), (19, 63, 191));
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
                        _ => rng.r#gen(),
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
