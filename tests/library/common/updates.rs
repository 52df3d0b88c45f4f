//! Random update sequences for the trees with single inserts and removes (any `PointSetMut`:
//! `PointTree`, `DynamicPointTree`, ...): the operations, their strategies on a small grid (so
//! that points repeat and lie on split lines), one step applied to a tree and to a brute-force
//! model, and the one check every such tree runs after each step ([`run`]): it validates, has
//! the leaves and pairs of a `PointTree` freshly built from the model, and answers every query
//! kind as a scan of the model does.

use orthtree::prelude::*;
use orthtree::query::{Chebyshev, Manhattan, Metric, SquaredEuclidean};
use orthtree::{points::PointTreeBuilder, query::HalfSpace, Aabb, Ball, Cell, PointTree};
use proptest::prelude::*;

/// One update; coordinates are grid indices 0..=8 on [0, 1] (so many lie on split lines and
/// many repeat), items are small so (point, item) pairs repeat too.
#[derive(Clone, Debug)]
pub enum Op<const D: usize> {
    Insert([u8; D], u8),
    Remove([u8; D], u8),
    RemovePoint([u8; D]),
    /// Remove the stored pair at this position of the model (modulo its length).
    RemoveStored(usize),
}

/// The point of grid indices `g`.
pub fn coords<const D: usize>(g: [u8; D]) -> [f64; D] {
    g.map(|x| f64::from(x) / 8.0)
}

/// Sorted (point bits, item) pairs.
pub type Pairs<const D: usize> = Vec<([u64; D], u8)>;

/// The pairs of `it`, sorted, points by their bits.
pub fn sorted_pairs<'a, const D: usize>(
    it: impl Iterator<Item = (&'a [f64; D], &'a u8)>,
) -> Pairs<D> {
    let mut v: Pairs<D> = it.map(|(p, &i)| (p.map(f64::to_bits), i)).collect();
    v.sort_unstable();
    v
}

pub fn op<const D: usize>() -> impl Strategy<Value = Op<D>> {
    let g = || proptest::array::uniform::<_, D>(0u8..=8);
    prop_oneof![
        4 => (g(), 0u8..3).prop_map(|(g, i)| Op::Insert(g, i)),
        1 => (g(), 0u8..3).prop_map(|(g, i)| Op::Remove(g, i)),
        1 => g().prop_map(Op::RemovePoint),
        2 => any::<usize>().prop_map(Op::RemoveStored),
    ]
}

pub fn initial<const D: usize>() -> impl Strategy<Value = Vec<([u8; D], u8)>> {
    proptest::collection::vec((proptest::array::uniform::<_, D>(0u8..=8), 0u8..3), 0..30)
}

/// Applies `op` to `t` and to `model`, checking what the tree answers against the model.
pub fn apply<const D: usize>(
    t: &mut impl PointSetMut<D, Scalar = f64, Item = u8>,
    model: &mut Vec<([f64; D], u8)>,
    op: Op<D>,
) -> Result<(), TestCaseError> {
    match op {
        Op::Insert(g, i) => {
            t.insert(coords(g), i).unwrap();
            model.push((coords(g), i));
        }
        Op::Remove(g, i) => {
            let p = coords(g);
            let at = model.iter().position(|&(q, j)| q == p && j == i);
            prop_assert_eq!(t.remove(&p, &i), at.is_some());
            if let Some(at) = at {
                model.swap_remove(at);
            }
        }
        Op::RemovePoint(g) => {
            let p = coords(g);
            match t.remove_point(&p) {
                Some(i) => {
                    let at = model.iter().position(|&(q, j)| q == p && j == i);
                    prop_assert!(at.is_some(), "removed an item not stored at the point");
                    model.swap_remove(at.unwrap());
                }
                None => prop_assert!(model.iter().all(|&(q, _)| q != p)),
            }
        }
        Op::RemoveStored(k) => {
            if !model.is_empty() {
                let (p, i) = model.swap_remove(k % model.len());
                prop_assert!(t.remove(&p, &i));
            }
        }
    }
    Ok(())
}

/// Every leaf's cell with its sorted (point bits, item) pairs.
pub type Leaves<const D: usize> = Vec<(Cell<D>, Pairs<D>)>;

/// The leaves of a point tree, as [`Leaves`].
pub fn point_leaves<const D: usize>(t: &PointTree<f64, u8, D>) -> Leaves<D> {
    t.leaves()
        .map(|l| (l.cell, sorted_pairs(l.points.iter().zip(l.items))))
        .collect()
}

/// A tree that takes the random update sequences: how to read its leaves, and what it checks
/// beyond the shared checks after each step.
pub trait Updatable<const D: usize>: PointSetMut<D, Scalar = f64, Item = u8> {
    /// Every leaf's cell and its pairs, in the tree's leaf order.
    fn leaf_pairs(&self) -> Leaves<D>;

    /// Checks of this tree after update number `step`, beside `fresh` (a point tree built
    /// from `model`); none by default.
    fn after_step(
        &mut self,
        _step: usize,
        _fresh: &PointTree<f64, u8, D>,
        _model: &[([f64; D], u8)],
    ) -> Result<(), TestCaseError> {
        Ok(())
    }
}

/// Applies `ops` one at a time to `t` (built by `b` from `model`) and to `model`; after every
/// step `t` validates, holds the model's pairs, has the leaves of a fresh build by `b`, answers
/// every query as a scan of the model ([`check_queries`]), and passes its own
/// [`Updatable::after_step`].
pub fn run<T: Updatable<D>, const D: usize>(
    mut t: T,
    b: &PointTreeBuilder<f64, D>,
    mut model: Vec<([f64; D], u8)>,
    ops: Vec<Op<D>>,
) -> Result<(), TestCaseError> {
    for (step, op) in ops.into_iter().enumerate() {
        apply(&mut t, &mut model, op)?;
        if let Err(e) = t.validate() {
            return Err(TestCaseError::fail(format!("validate: {e}")));
        }
        prop_assert_eq!(t.len(), model.len());
        let fresh = b.build(&model).unwrap();
        prop_assert_eq!(t.leaf_pairs(), point_leaves(&fresh));
        prop_assert_eq!(sorted_pairs(t.iter()), sorted_pairs(fresh.iter()));
        check_queries(&t, &model)?;
        t.after_step(step, &fresh, &model)?;
    }
    Ok(())
}

/// The k-nearest answer under `metric` against a scan: the distances in order, each
/// neighbour's point, item and slot consistent, the slots distinct; the nearest iterator and
/// the single nearest agree.
fn check_nearest<P, M, const D: usize>(
    t: &P,
    model: &[([f64; D], u8)],
    q: &[f64; D],
    k: usize,
    metric: &M,
) -> Result<(), TestCaseError>
where
    P: PointSet<D, Scalar = f64, Item = u8>,
    M: Metric<D> + Copy,
{
    let got = t.k_nearest_by(q, k, f64::INFINITY, metric).unwrap();
    let mut want: Vec<f64> = model.iter().map(|(p, _)| metric.distance(q, p)).collect();
    want.sort_by(f64::total_cmp);
    want.truncate(k);
    let dists: Vec<f64> = got.iter().map(|n| n.distance).collect();
    prop_assert_eq!(&dists, &want);
    let mut slots: Vec<usize> = got.iter().map(|n| n.index).collect();
    for n in &got {
        prop_assert_eq!(n.point, t.point(n.index));
        prop_assert_eq!(n.item, &t.items()[n.index]);
        prop_assert_eq!(n.distance, metric.distance(q, n.point));
    }
    slots.sort_unstable();
    slots.dedup();
    prop_assert_eq!(slots.len(), got.len());
    let iter: Vec<f64> = t
        .nearest_iter_by(q, f64::INFINITY, *metric)
        .unwrap()
        .take(k)
        .map(|n| n.distance)
        .collect();
    prop_assert_eq!(iter, want.clone());
    let first = t.k_nearest_by(q, 1, f64::INFINITY, metric).unwrap();
    prop_assert_eq!(first.first().map(|n| n.distance), want.first().copied());
    Ok(())
}

/// Box, ball and half-space queries whose boundaries pass through grid points (iterator, count
/// and visitor), and nearest neighbours under three metrics from inside and outside the root
/// box, against a scan of `model`.
pub fn check_queries<P, const D: usize>(
    t: &P,
    model: &[([f64; D], u8)],
) -> Result<(), TestCaseError>
where
    P: PointSet<D, Scalar = f64, Item = u8>,
{
    let all = || model.iter().map(|(p, i)| (p, i));
    let (lo, hi) = ([0.25; D], [0.625; D]);
    let in_box = |p: &[f64; D]| (0..D).all(|a| lo[a] <= p[a] && p[a] <= hi[a]);
    let b = Aabb::new(lo, hi).unwrap();
    let want = sorted_pairs(all().filter(|(p, _)| in_box(p)));
    prop_assert_eq!(sorted_pairs(t.in_box(&b).unwrap()), want.clone());
    prop_assert_eq!(t.query_count(b).unwrap(), want.len());
    let mut seen = Vec::new();
    t.query_with(b, |p, &i| seen.push((p.map(f64::to_bits), i)))
        .unwrap();
    seen.sort_unstable();
    prop_assert_eq!(seen, want);
    let (c, r) = ([0.5; D], 0.375);
    let d2 = |p: &[f64; D], q: &[f64; D]| (0..D).map(|a| (p[a] - q[a]).powi(2)).sum::<f64>();
    prop_assert_eq!(
        sorted_pairs(t.query(Ball::new(c, r).unwrap()).unwrap()),
        sorted_pairs(all().filter(|(p, _)| d2(p, &c) <= r * r))
    );
    let mut normal = [0.0; D];
    normal[0] = 1.0;
    normal[D - 1] += 1.0;
    let plane = HalfSpace::new(normal, 0.75).unwrap();
    let below = |p: &[f64; D]| (0..D).map(|a| normal[a] * p[a]).sum::<f64>() <= 0.75;
    prop_assert_eq!(
        sorted_pairs(t.query(plane).unwrap()),
        sorted_pairs(all().filter(|(p, _)| below(p)))
    );
    prop_assert_eq!(
        t.query_count(Aabb::new([0.0; D], [1.0; D]).unwrap())
            .unwrap(),
        model.len()
    );
    for q in [[0.5; D], [0.0; D], [0.9; D], [1.7; D]] {
        check_nearest(t, model, &q, 5, &SquaredEuclidean)?;
        check_nearest(t, model, &q, 3, &Manhattan)?;
        check_nearest(t, model, &q, model.len() + 2, &Chebyshev)?;
    }
    Ok(())
}
