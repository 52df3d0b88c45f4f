//! One adapter per crate behind the [`Rival`] trait: how it builds from the shared points and
//! answers a batch of box, radius and k-nearest queries, consuming every answer as a caller
//! would. The item of point `i` is `i`.

use kiddo::dist::SquaredEuclidean;
use kiddo::ImmutableKdTree;
use orthtree::prelude::*;
use orthtree::{Aabb, Ball, PointTree};
use rstar::{RTree, AABB};
use std::num::NonZeroUsize;

/// What a batch of queries gave: the number of answers; the sum of their items where the crate
/// hands items back; for k-nearest the sum of the squared distances where it reports them.
/// Two crates agree when every field both report is equal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Answers {
    /// Answers over the batch (for k-nearest: `k` per query, or fewer in a small set).
    pub count: u64,
    /// The items' sum (wrapping), when the crate returns items.
    pub items: Option<u64>,
    /// The squared distances' sum, when the crate returns distances.
    pub distance: Option<f64>,
}

impl Answers {
    /// Whether `self` and `other` agree on every field both report (distance sums to a relative
    /// 1e-9: the crates add them in different orders; items only when no tie can swap them).
    pub fn agrees_with(&self, other: &Answers, compare_items: bool) -> bool {
        let items = match (self.items, other.items) {
            (Some(a), Some(b)) if compare_items => a == b,
            _ => true,
        };
        let distance = match (self.distance, other.distance) {
            (Some(a), Some(b)) => (a - b).abs() <= 1e-9 * b.abs().max(1e-300),
            _ => true,
        };
        self.count == other.count && items && distance
    }
}

/// One crate's spatial index of `D`-dimensional `f64` points.
pub trait Rival<const D: usize>: Sized {
    /// The crate's name, a column of the tables.
    const NAME: &'static str;
    /// What the build takes, made from the shared points outside the timing.
    type Input;
    /// Makes the crate's input from the shared points.
    fn prepare(points: &[[f64; D]]) -> Self::Input;
    /// The timed build.
    fn build(input: &Self::Input) -> Self;
    /// The number of points held, to check that every crate got them all.
    fn size(&self) -> usize;
    /// The points in each closed box of side `side` centred on a query; `None` when the crate
    /// has no box query.
    fn boxes(&self, queries: &[[f64; D]], side: f64) -> Option<Answers>;
    /// The points within `radius` (closed) of each query.
    fn balls(&self, queries: &[[f64; D]], radius: f64) -> Answers;
    /// The `k` nearest points of each query.
    fn nearest(&self, queries: &[[f64; D]], k: usize) -> Answers;
}

/// The box of side `side` centred on `q`, as its two corners.
pub fn corners<const D: usize>(q: &[f64; D], side: f64) -> ([f64; D], [f64; D]) {
    (q.map(|x| x - side / 2.0), q.map(|x| x + side / 2.0))
}

/// orthtree's `PointTree`, default bucket size, built from `(point, index)` entries.
pub struct Orthtree<const D: usize>(pub PointTree<f64, u64, D>);

impl<const D: usize> Rival<D> for Orthtree<D> {
    const NAME: &'static str = "orthtree";
    type Input = Vec<([f64; D], u64)>;
    fn prepare(points: &[[f64; D]]) -> Self::Input {
        points
            .iter()
            .enumerate()
            .map(|(i, &p)| (p, i as u64))
            .collect()
    }
    fn build(input: &Self::Input) -> Self {
        Orthtree(PointTree::builder().build(input).expect("finite points"))
    }
    fn size(&self) -> usize {
        self.0.len()
    }
    fn boxes(&self, queries: &[[f64; D]], side: f64) -> Option<Answers> {
        let (mut count, mut items) = (0u64, 0u64);
        for q in queries {
            let (min, max) = corners(q, side);
            for (_, &i) in self.0.query(Aabb { min, max }).expect("a finite box") {
                count += 1;
                items = items.wrapping_add(i);
            }
        }
        Some(Answers {
            count,
            items: Some(items),
            distance: None,
        })
    }
    fn balls(&self, queries: &[[f64; D]], radius: f64) -> Answers {
        let (mut count, mut items) = (0u64, 0u64);
        for q in queries {
            let ball = Ball { center: *q, radius };
            for (_, &i) in self.0.query(ball).expect("a finite ball") {
                count += 1;
                items = items.wrapping_add(i);
            }
        }
        Answers {
            count,
            items: Some(items),
            distance: None,
        }
    }
    fn nearest(&self, queries: &[[f64; D]], k: usize) -> Answers {
        let (mut count, mut items, mut distance) = (0u64, 0u64, 0.0);
        for q in queries {
            if k == 1 {
                if let Some(nn) = self.0.nearest(q).expect("a finite query") {
                    count += 1;
                    distance += nn.distance;
                    items = items.wrapping_add(*nn.item);
                }
            } else {
                for nn in self.0.k_nearest(q, k).expect("a finite query") {
                    count += 1;
                    distance += nn.distance;
                    items = items.wrapping_add(*nn.item);
                }
            }
        }
        Answers {
            count,
            items: Some(items),
            distance: Some(distance),
        }
    }
}

/// kiddo's leaf bucket size (that of its `ImmutableKdTree` alias).
pub const KIDDO_BUCKET: usize = 32;

/// kiddo 6's `ImmutableKdTree` alias, the structure kiddo recommends for points known up front
/// (build once, then query): Eytzinger-ordered stems, leaves of [`KIDDO_BUCKET`] points in one
/// arena, `u32` items (the point's index), built single-threaded (its
/// builder's serial construction). It has no box query; its radius query is the unsorted one,
/// visiting each answer without collecting them.
pub struct Kiddo<const D: usize>(pub ImmutableKdTree<f64, D>);

impl<const D: usize> Rival<D> for Kiddo<D> {
    const NAME: &'static str = "kiddo";
    type Input = Vec<[f64; D]>;
    fn prepare(points: &[[f64; D]]) -> Self::Input {
        points.to_vec()
    }
    fn build(input: &Self::Input) -> Self {
        // Serial even when kiddo's `multi-threaded` feature is on (the `rayon` feature).
        Kiddo(
            ImmutableKdTree::builder()
                .with_serial_construction()
                .build_from_slice(input)
                .expect("fewer than 2^32 finite points"),
        )
    }
    fn size(&self) -> usize {
        self.0.size()
    }
    fn boxes(&self, _: &[[f64; D]], _: f64) -> Option<Answers> {
        None
    }
    fn balls(&self, queries: &[[f64; D]], radius: f64) -> Answers {
        let (mut count, mut items) = (0u64, 0u64);
        for q in queries {
            self.0
                .query(q)
                .within::<SquaredEuclidean<f64>>(radius * radius)
                .unsorted()
                .visit(|nn| {
                    count += 1;
                    items = items.wrapping_add(u64::from(nn.item));
                });
        }
        Answers {
            count,
            items: Some(items),
            distance: None,
        }
    }
    fn nearest(&self, queries: &[[f64; D]], k: usize) -> Answers {
        let (mut count, mut items, mut distance) = (0u64, 0u64, 0.0);
        let nz = NonZeroUsize::new(k).expect("k >= 1");
        for q in queries {
            if k == 1 {
                let nn = self
                    .0
                    .query(q)
                    .nearest_one::<SquaredEuclidean<f64>>()
                    .execute();
                count += 1;
                distance += nn.distance;
                items = items.wrapping_add(u64::from(nn.item));
            } else {
                for nn in self
                    .0
                    .query(q)
                    .nearest_n::<SquaredEuclidean<f64>>(nz)
                    .execute()
                {
                    count += 1;
                    distance += nn.distance;
                    items = items.wrapping_add(u64::from(nn.item));
                }
            }
        }
        Answers {
            count,
            items: Some(items),
            distance: Some(distance),
        }
    }
}

/// rstar 0.12's `RTree::bulk_load` of bare points (the copy it takes is part of the build); it
/// returns points, not items or distances, so it reports counts.
pub struct Rstar<const D: usize>(pub RTree<[f64; D]>);

impl<const D: usize> Rival<D> for Rstar<D>
where
    [f64; D]: rstar::Point<Scalar = f64>,
{
    const NAME: &'static str = "rstar";
    type Input = Vec<[f64; D]>;
    fn prepare(points: &[[f64; D]]) -> Self::Input {
        points.to_vec()
    }
    fn build(input: &Self::Input) -> Self {
        Rstar(RTree::bulk_load(input.clone()))
    }
    fn size(&self) -> usize {
        self.0.size()
    }
    fn boxes(&self, queries: &[[f64; D]], side: f64) -> Option<Answers> {
        let mut count = 0u64;
        for q in queries {
            let (lo, hi) = corners(q, side);
            count += self
                .0
                .locate_in_envelope(&AABB::from_corners(lo, hi))
                .count() as u64;
        }
        Some(Answers {
            count,
            items: None,
            distance: None,
        })
    }
    fn balls(&self, queries: &[[f64; D]], radius: f64) -> Answers {
        let mut count = 0u64;
        for q in queries {
            count += self.0.locate_within_distance(*q, radius * radius).count() as u64;
        }
        Answers {
            count,
            items: None,
            distance: None,
        }
    }
    fn nearest(&self, queries: &[[f64; D]], k: usize) -> Answers {
        // The first coordinate of each answer is read, as a caller would read the point.
        let (mut count, mut first) = (0u64, 0.0f64);
        for q in queries {
            for p in self.0.nearest_neighbor_iter(q).take(k) {
                count += 1;
                first += p[0];
            }
        }
        std::hint::black_box(first);
        Answers {
            count,
            items: None,
            distance: None,
        }
    }
}
