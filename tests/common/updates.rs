//! Random update sequences for the trees with single inserts and removes (any `PointSetMut`:
//! `PointTree`, `DynamicPointTree`, ...): the operations, their strategies on a small grid (so that points repeat
//! and lie on split lines), and one step applied to a tree and to a brute-force model.

use orthtree::prelude::*;
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
