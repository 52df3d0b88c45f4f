//! Sorting networks for short runs: Batcher's odd-even merge sort ("Sorting networks and their
//! applications", AFIPS Spring Joint Computer Conference, 1968) for up to 32 inputs, the run
//! padded with the greatest value. Two users: the short runs the radix sort leaves behind
//! (`points/radix.rs`) and each point's candidates in the k-nearest joins
//! (`query/join/knn_cands.rs`).
//!
//! A uniform 2D build ends with about 65 000 runs of some 15 keys. The standard library sorts runs
//! that short by insertion, whose exits are data-dependent branches that mispredict about once a
//! key (about 9 ns a key on the development machine); a network compares fixed positions with
//! branch-free minimum and maximum, 63 comparators for 16 inputs, and sorts the same runs in
//! under half the time.
//!
//! The networks for 8 and 16 inputs are written out comparator by comparator (`unrolled!`),
//! so that the values stay in registers: looping over a table of comparators goes through
//! memory and was 20% slower on the whole sort. Those for 24 and 32 inputs are loops with fixed
//! bounds ([`padded`] through [`batcher`]), which the compiler lays out in a straight line the
//! same way. Tests check the written-out ones against [`batcher`] and every width by the 0-1
//! principle and on random runs.

/// Calls `exchange(i, j)` for each comparator of Batcher's odd-even merge sort for `n` inputs
/// (a power of two), in order: sorted runs of `p` are merged into runs of `2p` by comparators at
/// distances `p, p/2, .., 1`, each between places of the same run of `2p`. Inlined with a
/// constant `n`, its loops have fixed bounds and the compiler lays the comparators out in a
/// straight line.
#[inline(always)]
fn batcher(n: usize, mut exchange: impl FnMut(usize, usize)) {
    let mut p = 1;
    while p < n {
        let mut d = p;
        while d >= 1 {
            let mut j = d % p;
            while j + d < n {
                for i in j..(j + d).min(n - d) {
                    if i / (2 * p) == (i + d) / (2 * p) {
                        exchange(i, i + d);
                    }
                }
                j += 2 * d;
            }
            d /= 2;
        }
        p *= 2;
    }
}

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

/// The most values [`sort_by_network`] sorts with a network.
pub(crate) const WIDEST: usize = 32;

/// Sorts `run` by the network of the smallest width among 8, 16, 24 and 32 that holds it; a run
/// longer than [`WIDEST`] goes to `sort_unstable`. `greatest` must be at least every value (it
/// pads the network's inputs).
#[inline(always)]
pub(crate) fn sort_by_network<P: Copy + Ord>(run: &mut [P], greatest: P) {
    match run.len() {
        0..=1 => {}
        2..=8 => sort8(run, greatest),
        9..=16 => sort16(run, greatest),
        17..=24 => padded::<P, 24>(run, greatest),
        25..=WIDEST => padded::<P, WIDEST>(run, greatest),
        _ => run.sort_unstable(),
    }
}

/// Sorts `run` (at most `W` values, `W` at most [`WIDEST`]) by Batcher's network of [`WIDEST`]
/// places ([`batcher`]) with the exchanges that reach a place from `W` on left out: a place from
/// `W` on holds `greatest`, which no exchange moves (the larger value goes to the later place),
/// so the exchanges left out would change nothing.
#[inline(always)]
fn padded<P: Copy + Ord, const W: usize>(run: &mut [P], greatest: P) {
    let mut a = [greatest; WIDEST];
    a[..run.len()].copy_from_slice(run);
    batcher(WIDEST, |i, j| {
        if j < W {
            let (x, y) = (a[i], a[j]);
            a[i] = x.min(y);
            a[j] = x.max(y);
        }
    });
    run.copy_from_slice(&a[..run.len()]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn the_networks_are_batchers() {
        let pairs = |n: usize| {
            let mut out = Vec::new();
            batcher(n, |i, j| out.push((i as u8, j as u8)));
            out
        };
        assert_eq!(NET8, &pairs(8)[..]);
        assert_eq!(NET16, &pairs(16)[..]);
        assert_eq!(
            (NET8.len(), NET16.len(), pairs(WIDEST).len()),
            (19, 63, 191)
        );
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
                sort_by_network(&mut run, u8::MAX);
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
                sort_by_network(&mut run, u64::MAX);
                assert_eq!(run, expected);
            }
        }
    }
}
