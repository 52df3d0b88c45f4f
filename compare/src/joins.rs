//! The workloads of `joins_compare`, as orthtree and kiddo 6 run them: periodic k-nearest on a
//! unit torus, the k-nearest self-join, all pairs within a radius and the pair counts over a
//! list of radii, on the seeded point sets of this module. Each run hands back its median times
//! and an [`Answer`] (counts and checksums) that the program checks equal across the crates
//! before it prints a time. scipy's runs are in [`scipy`](crate::scipy).
//!
//! The algorithms are the crates' own: orthtree's dual-tree joins (Gray and Moore, "N-body
//! problems in statistical learning", NIPS 2001) and its minimum-image k-nearest; kiddo's
//! per-point batch queries, its periodic-boundary-condition queries and its radius join of two
//! trees.

use crate::rivals::Answers;
use crate::timing::time;
use core::ops::ControlFlow;
use kiddo::batch::Executor;
use kiddo::dist::SquaredEuclidean;
use kiddo::ImmutableKdTree;
use orthtree::prelude::*;
use orthtree::query::{Boundary, OutsidePoints, Torus};
use orthtree::{Ball, PointTree};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicU64, Ordering};

/// What a workload answered, checked equal across the crates.
#[derive(Clone, Debug, PartialEq)]
pub enum Answer {
    /// Neighbours or pairs: their number, and the sums of their indices and squared distances
    /// where the crate reports them.
    Found(Answers),
    /// For each radius, the number of unordered pairs of distinct points within it.
    Counts(Vec<u64>),
}

impl Answer {
    /// Whether `self` and `other` agree on all they both report (see [`Answers::agrees_with`];
    /// `items`: whether the index sums must agree, false where ties may swap neighbours).
    pub fn agrees_with(&self, other: &Answer, items: bool) -> bool {
        match (self, other) {
            (Answer::Found(a), Answer::Found(b)) => a.agrees_with(b, items),
            (Answer::Counts(a), Answer::Counts(b)) => a == b,
            _ => false,
        }
    }
}

/// One crate's run of one workload: median build and query times in milliseconds, and what it
/// answered.
#[derive(Clone, Debug)]
pub struct Run {
    /// The build of the crate's tree (or trees).
    pub build_ms: f64,
    /// The workload on the built tree.
    pub query_ms: f64,
    /// Its answer.
    pub answer: Answer,
}

/// `n` points on a wavy height field in the unit cube, a stand-in for a scanned surface:
/// `x, y` uniform in `[0, 1)`, `z = 0.5 + 0.1 sin(6 pi x) sin(4 pi y)` plus uniform noise of
/// +-0.001. The same `(n, seed)` always gives the same points.
pub fn surface(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = SmallRng::seed_from_u64(seed);
    let tau = core::f64::consts::TAU;
    (0..n)
        .map(|_| {
            let (x, y): (f64, f64) = (rng.r#gen(), rng.r#gen());
            let noise = (rng.r#gen::<f64>() - 0.5) * 0.002;
            [
                x,
                y,
                0.5 + 0.1 * (3.0 * tau * x).sin() * (2.0 * tau * y).sin() + noise,
            ]
        })
        .collect()
}

/// A radius within which a point of `points` has about `want` others on average, for points on
/// a surface (the count grows as the radius squared), calibrated on a sample of 2000 points.
pub fn radius_for(points: &[[f64; 3]], want: f64) -> f64 {
    let tree = index_tree(points);
    let step = (points.len() / 2000).max(1);
    let sample: Vec<&[f64; 3]> = points.iter().step_by(step).collect();
    let mut r = (want / (core::f64::consts::PI * points.len() as f64)).sqrt();
    for _ in 0..6 {
        let total: usize = sample
            .iter()
            .map(|q| {
                let ball = Ball {
                    center: **q,
                    radius: r,
                };
                tree.query_count(ball).expect("a finite ball") - 1
            })
            .sum();
        let avg = (total as f64 / sample.len() as f64).max(0.25);
        r *= (want / avg).sqrt().clamp(0.25, 4.0);
    }
    r
}

/// `count` radii from `lo` to `hi`, evenly spaced on a log scale.
pub fn log_radii(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    let steps = count.saturating_sub(1).max(1) as f64;
    (0..count)
        .map(|i| lo * (hi / lo).powf(i as f64 / steps))
        .collect()
}

/// orthtree's point tree of `points`, the item of point `i` being `i`.
fn index_tree(points: &[[f64; 3]]) -> PointTree<f64, u32, 3> {
    PointTree::new(&entries(points)).expect("finite points")
}

/// The `(point, index)` entries of `points`.
fn entries(points: &[[f64; 3]]) -> Vec<([f64; 3], u32)> {
    points
        .iter()
        .enumerate()
        .map(|(i, p)| (*p, u32::try_from(i).expect("fewer than 2^32 points")))
        .collect()
}

/// kiddo's `ImmutableKdTree` of `points`, built on one thread (the item of point `i` is `i`).
fn kiddo_tree(points: &[[f64; 3]]) -> ImmutableKdTree<f64, 3> {
    ImmutableKdTree::builder()
        .with_serial_construction()
        .build_from_slice(points)
        .expect("fewer than 2^32 finite points")
}

/// The sums of a list of neighbours given as `(index, squared distance)`.
fn found(list: impl Iterator<Item = (u64, f64)>) -> Answers {
    let mut sums = Sums::default();
    list.for_each(|(i, d)| sums.add(i, d));
    sums.answers()
}

/// The running sums of [`found`], for answers handed to a visitor.
#[derive(Default)]
struct Sums {
    count: u64,
    items: u64,
    distance: f64,
}

impl Sums {
    fn add(&mut self, item: u64, distance: f64) {
        self.count += 1;
        self.items = self.items.wrapping_add(item);
        self.distance += distance;
    }

    fn answers(self) -> Answers {
        Answers {
            count: self.count,
            items: Some(self.items),
            distance: Some(self.distance),
        }
    }
}

/// orthtree: the `k` nearest points of each query under minimum-image distances in the periodic
/// unit cube, one thread: one [`PeriodicQueries::periodic_k_nearest`] per query in the order
/// given, or with `batch` all of them through [`BatchQueries::periodic_k_nearest_batch`], which
/// answers them in Morton order (its sort inside the timing) to a visitor. The answers are the
/// same.
pub fn orthtree_periodic(
    points: &[[f64; 3]],
    queries: &[[f64; 3]],
    k: usize,
    reps: usize,
    batch: bool,
) -> Run {
    let torus = Torus::wrapping([0.0; 3], [1.0; 3]).expect("a unit torus");
    let inside = torus
        .prepare(points, OutsidePoints::Refuse)
        .expect("points in the unit cube");
    let es = entries(&inside);
    let (build_ms, _) = time(reps, || PointTree::new(&es).expect("finite points").len());
    let tree = PointTree::new(&es).expect("finite points");
    let (query_ms, a) = time(reps, || {
        if batch {
            let mut sums = Sums::default();
            tree.periodic_k_nearest_batch(&torus, queries, k, |_, near| {
                near.iter()
                    .for_each(|nb| sums.add(u64::from(*nb.item), nb.distance));
            })
            .expect("finite queries");
            sums.answers()
        } else {
            found(queries.iter().flat_map(|q| {
                tree.periodic_k_nearest(&torus, q, k)
                    .expect("a finite query")
                    .into_iter()
                    .map(|nb| (u64::from(*nb.item), nb.distance))
            }))
        }
    });
    Run {
        build_ms,
        query_ms,
        answer: Answer::Found(a),
    }
}

/// kiddo: the same queries through its periodic boundary condition (box size 1 on every axis).
pub fn kiddo_periodic(points: &[[f64; 3]], queries: &[[f64; 3]], k: usize, reps: usize) -> Run {
    let (build_ms, _) = time(reps, || kiddo_tree(points).size());
    let tree = kiddo_tree(points);
    let nz = NonZeroUsize::new(k).expect("k >= 1");
    let (query_ms, a) = time(reps, || {
        found(queries.iter().flat_map(|q| {
            tree.query(q)
                .periodic_boundary_condition(&[1.0; 3])
                .nearest_n::<SquaredEuclidean<f64>>(nz)
                .execute()
                .into_iter()
                .map(|nb| (u64::from(nb.item), nb.distance))
        }))
    });
    Run {
        build_ms,
        query_ms,
        answer: Answer::Found(a),
    }
}

/// Whether the joins run on rayon's threads (the `rayon` feature), and how many.
pub fn threads() -> usize {
    #[cfg(feature = "rayon")]
    {
        rayon::current_num_threads()
    }
    #[cfg(not(feature = "rayon"))]
    {
        1
    }
}

/// The neighbour sums of a self-join table (slots are positions in `items`).
fn table_sums(table: &orthtree::query::KnnTable, items: &[u32]) -> Answers {
    found(
        table
            .slots()
            .iter()
            .zip(table.distances())
            .map(|(&s, &d)| (u64::from(items[s]), d)),
    )
}

/// orthtree: the `k` nearest others of every point ([`Joins::k_nearest_self`]; with the `rayon`
/// feature `par_build` and [`ParallelJoins::par_k_nearest_self`] on all threads).
pub fn orthtree_self_knn(points: &[[f64; 3]], k: usize, reps: usize) -> Run {
    let es = entries(points);
    let build = || {
        #[cfg(feature = "rayon")]
        {
            PointTree::builder().par_build(&es).expect("finite points")
        }
        #[cfg(not(feature = "rayon"))]
        {
            PointTree::builder().build(&es).expect("finite points")
        }
    };
    let (build_ms, _) = time(reps, || build().len());
    let tree = build();
    let (query_ms, a) = time(reps, || {
        #[cfg(feature = "rayon")]
        let table = tree.par_k_nearest_self(k);
        #[cfg(not(feature = "rayon"))]
        let table = tree.k_nearest_self(k);
        table_sums(&table, tree.items())
    });
    Run {
        build_ms,
        query_ms,
        answer: Answer::Found(a),
    }
}

/// kiddo: a batch query of the `k + 1` nearest of every point on its own tree (the nearest is
/// the point itself, dropped from the sums; the points have no duplicates), on all of rayon's
/// threads with the `rayon` feature (kiddo's parallel executor and build), else serially.
pub fn kiddo_self_knn(points: &[[f64; 3]], k: usize, reps: usize) -> Run {
    #[cfg(feature = "rayon")]
    let (executor, build) = (Executor::parallel(), || {
        ImmutableKdTree::<f64, 3>::builder()
            .with_parallel_construction()
            .build_from_slice(points)
            .expect("fewer than 2^32 finite points")
    });
    #[cfg(not(feature = "rayon"))]
    let (executor, build) = (Executor::serial(), || kiddo_tree(points));
    let (build_ms, _) = time(reps, || build().size());
    let tree = build();
    let nz = NonZeroUsize::new(k + 1).expect("k + 1 >= 1");
    let (query_ms, a) = time(reps, || {
        let groups = tree
            .query_batch(points)
            .nearest_n::<SquaredEuclidean<f64>>(nz)
            .with_executor(&executor)
            .execute();
        found(
            groups
                .iter()
                .flat_map(|g| g.iter().skip(1))
                .map(|nb| (u64::from(nb.item), nb.distance)),
        )
    });
    Run {
        build_ms,
        query_ms,
        answer: Answer::Found(a),
    }
}

/// orthtree: every unordered pair within `r` (inclusive), visited once and consumed (count and
/// index sum) without collecting ([`Joins::pairs_within`]), one thread.
pub fn orthtree_pairs(points: &[[f64; 3]], r: f64, reps: usize) -> Run {
    let es = entries(points);
    let (build_ms, _) = time(reps, || PointTree::new(&es).expect("finite points").len());
    let tree = PointTree::new(&es).expect("finite points");
    let items = tree.items();
    let (query_ms, a) = time(reps, || {
        let (mut count, mut sum) = (0u64, 0u64);
        let _ = tree
            .pairs_within(r, Boundary::Inclusive, |s, t, _| {
                count += 1;
                sum = sum.wrapping_add(u64::from(items[s]) + u64::from(items[t]));
                ControlFlow::<()>::Continue(())
            })
            .expect("a finite radius");
        Answers {
            count,
            items: Some(sum),
            distance: None,
        }
    });
    Run {
        build_ms,
        query_ms,
        answer: Answer::Found(a),
    }
}

/// kiddo: its radius join of two trees of the points (it refuses to join a tree with itself),
/// serial, visiting every ordered pair within `r` including each point with itself; the
/// unordered pairs `i < j` are counted and summed. The build time is that of both trees.
pub fn kiddo_pairs(points: &[[f64; 3]], r: f64, reps: usize) -> Run {
    let (build_ms, _) = time(reps, || {
        kiddo_tree(points).size() + kiddo_tree(points).size()
    });
    let (left, right) = (kiddo_tree(points), kiddo_tree(points));
    let (query_ms, a) = time(reps, || {
        let (count, sum) = (AtomicU64::new(0), AtomicU64::new(0));
        left.query_tree(&right)
            .within::<SquaredEuclidean<f64>>(r * r)
            .without_distances()
            .with_executor(&Executor::serial())
            .for_each(|pair| {
                if pair.left_item < pair.right_item {
                    count.fetch_add(1, Ordering::Relaxed);
                    sum.fetch_add(
                        u64::from(pair.left_item) + u64::from(pair.right_item),
                        Ordering::Relaxed,
                    );
                }
            });
        Answers {
            count: count.into_inner(),
            items: Some(sum.into_inner()),
            distance: None,
        }
    });
    Run {
        build_ms,
        query_ms,
        answer: Answer::Found(a),
    }
}

/// orthtree: the number of unordered pairs within each radius, in one traversal
/// ([`Joins::count_pairs_within`]), one thread.
pub fn orthtree_counts(points: &[[f64; 3]], radii: &[f64], reps: usize) -> Run {
    let es = entries(points);
    let (build_ms, _) = time(reps, || PointTree::new(&es).expect("finite points").len());
    let tree = PointTree::new(&es).expect("finite points");
    let (query_ms, counts) = time(reps, || {
        tree.count_pairs_within(radii, Boundary::Inclusive)
            .expect("sorted finite radii")
    });
    Run {
        build_ms,
        query_ms,
        answer: Answer::Counts(counts),
    }
}
