//! The k-nearest joins without their table: each point's `k` nearest neighbours are handed to a
//! function as soon as its group (see [`knn`](super::knn)) has been searched, and only the
//! function's value is kept, one per point. Statistical outlier scores, normals and the like
//! need a few numbers per point, not the `16 k` bytes per point of a [`KnnTable`]
//! (`super::knn::KnnTable`): at `10^8` points and `k = 20` the table alone would take 32 GB.
//!
//! The values come out in group order and are put into slot order by following the cycles of
//! the permutation in place ([`to_slot_order`]), which also serves the table's rows: nothing is
//! copied when the rows are already the slots (a [`PointTree`](crate::PointTree)).

use super::bounds::PairDistance;
use super::knn::{fill, groups, in_slot_order, width, Group};
use super::knn_group::Search;
use super::Join;
use crate::query::{PointSet, SpatialIndex};

/// Searches `groups` of the querying set in the other (`w` neighbours per point, at least 1),
/// one after the other with one group searcher and one group's rows (slots and distances),
/// and gives `f(slot in a, neighbour slots in b, squared distances)` for each of their points,
/// in group order and position order within a group.
fn map_groups<A, B, P, T, const D: usize>(
    join: Join<'_, A, B, P, D>,
    (groups, w): (&[Group], usize),
    mut f: impl FnMut(usize, &[usize], &[f64]) -> T,
) -> Vec<T>
where
    A: PointSet<D>,
    B: PointSet<D>,
    P: PairDistance<D>,
{
    let mut search = Search::new();
    let (mut slots, mut distances) = (Vec::new(), Vec::new());
    let mut out = Vec::with_capacity(groups.iter().map(Group::len).sum());
    let (a, qa) = (join.0, join.0.index().payloads());
    for group in groups {
        let n = group.len() * w;
        slots.resize(n, 0);
        distances.resize(n, 0.0);
        let (slots, distances) = (&mut slots[..n], &mut distances[..n]);
        fill(&mut search, join, (group, &mut *slots, &mut *distances), w);
        let rows = slots.chunks(w).zip(distances.chunks(w));
        for (i, (s, d)) in group.clone().zip(rows) {
            out.push(f(a.slot_of(i, &qa[i]), s, d));
        }
    }
    out
}

impl<A: PointSet<D>, B: PointSet<D>, P: PairDistance<D>, const D: usize> Join<'_, A, B, P, D> {
    /// `f(slot, neighbour slots, squared distances)` for every slot of the querying set, with
    /// its row of the `k`-nearest table, serially; the values in slot order.
    pub(crate) fn map_knn<T>(
        self,
        k: usize,
        mut f: impl FnMut(usize, &[usize], &[f64]) -> T,
    ) -> Vec<T> {
        let Join(a, b, _, same, _) = self;
        let w = width(k, b.len(), same);
        if w == 0 {
            return (0..a.len()).map(|s| f(s, &[], &[])).collect();
        }
        let gs = groups(a.index());
        let mut out = map_groups(self, (&gs, w), f);
        in_slot_order(a, &gs, |x, y| out.swap(x, y));
        out
    }

    /// [`Join::map_knn`] with the groups on rayon's threads; `f` is called from several threads
    /// at once, in no particular order.
    #[cfg(feature = "rayon")]
    pub(crate) fn par_map_knn<T: Send>(
        self,
        k: usize,
        f: impl Fn(usize, &[usize], &[f64]) -> T + Sync,
    ) -> Vec<T>
    where
        A: Sync,
        B: Sync,
    {
        use crate::par_tasks::{chunks, map_indices, map_ranges};
        let Join(a, b, _, same, _) = self;
        let w = width(k, b.len(), same);
        if w == 0 {
            return map_indices(a.len(), &|s| f(s, &[], &[]));
        }
        let gs = groups(a.index());
        // Runs of consecutive groups, one scratch space a run, the values concatenated in order.
        let runs = map_ranges(gs.len(), chunks(), &|run| {
            map_groups(self, (&gs[run], w), &f)
        });
        let mut out: Vec<T> = Vec::with_capacity(a.len());
        for run in runs {
            out.extend(run);
        }
        in_slot_order(a, &gs, |x, y| out.swap(x, y));
        out
    }
}

/// Puts rows into slot order: row `r` belongs to slot `order[r]` (a permutation), and
/// `swap(x, y)` exchanges rows `x` and `y`; the permutation's cycles are followed, so each row
/// moves once, with no second buffer. `order` ends as the identity.
///
/// # Complexity
/// At most `order.len()` swaps.
pub(crate) fn to_slot_order(order: &mut [usize], mut swap: impl FnMut(usize, usize)) {
    for r in 0..order.len() {
        // Row `r` goes to `order[r]`; the row found there comes to `r` and goes on in turn.
        while order[r] != r {
            let s = order[r];
            swap(r, s);
            order.swap(r, s);
        }
    }
}

/// Swaps rows `x` and `y` (different) of `width` entries each.
pub(crate) fn swap_rows<T>(rows: &mut [T], x: usize, y: usize, width: usize) {
    let (lo, hi) = (x.min(y), x.max(y));
    let (head, tail) = rows.split_at_mut(hi * width);
    head[lo * width..(lo + 1) * width].swap_with_slice(&mut tail[..width]);
}

#[cfg(test)]
mod tests {
    use super::{swap_rows, to_slot_order};

    #[test]
    fn rows_move_to_their_slots() {
        // rows in group order: row r belongs to slot order[r]
        let order = [3, 0, 4, 1, 2, 6, 5];
        let mut rows: Vec<(usize, usize)> = order.iter().flat_map(|&s| [(s, 0), (s, 1)]).collect();
        let mut o = order.to_vec();
        to_slot_order(&mut o, |x, y| swap_rows(&mut rows, x, y, 2));
        let want: Vec<(usize, usize)> = (0..7).flat_map(|s| [(s, 0), (s, 1)]).collect();
        assert_eq!(rows, want);
        assert_eq!(o, [0, 1, 2, 3, 4, 5, 6]);
        let mut single = order.to_vec();
        to_slot_order(&mut order.to_vec(), |x, y| single.swap(x, y));
        assert_eq!(single, [0, 1, 2, 3, 4, 5, 6]);
    }
}
