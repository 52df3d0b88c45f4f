//! [`Leaves`]: the leaves of a [`PointTree`] in Morton order, each with its cell and its run of
//! points and items.

use super::PointTree;
use crate::geom::{Cell, Scalar};
use crate::query::PointSet;
use crate::tree::{traverse::PreOrder, NodeId};

/// One leaf of a [`PointTree`]: its node, cell, points and items.
#[derive(Clone, Copy, Debug)]
pub struct Leaf<'a, S, T, const D: usize> {
    /// The leaf's node.
    pub id: NodeId,
    /// Its cell.
    pub cell: Cell<D>,
    /// Its points, in Morton order.
    pub points: &'a [[S; D]],
    /// Their items.
    pub items: &'a [T],
}

/// Iterator returned by [`PointTree::leaves`].
pub struct Leaves<'a, S, T, const D: usize> {
    tree: &'a PointTree<S, T, D>,
    walk: PreOrder<'a, D>,
    /// Where the next leaf's run starts: the leaves' runs follow each other in Morton order.
    start: usize,
}

impl<'a, S: Scalar, T, const D: usize> Iterator for Leaves<'a, S, T, D> {
    type Item = Leaf<'a, S, T, D>;

    fn next(&mut self) -> Option<Self::Item> {
        let (id, cell) = self.walk.next()?;
        let run = self.start..self.start + self.tree.runs().count::<D>(id) as usize;
        self.start = run.end;
        Some(Leaf {
            id,
            cell,
            points: &self.tree.points()[run.clone()],
            items: &self.tree.items()[run],
        })
    }
}

impl<S: Scalar, T, const D: usize> PointTree<S, T, D> {
    /// The leaves in Morton order, with their cells and points.
    ///
    /// ```
    /// use orthtree::Quadtree;
    /// let t = Quadtree::builder().bucket_size(1).build(&[([0.0, 0.0], 0), ([1.0, 1.0], 1)]).unwrap();
    /// let counts: Vec<usize> = t.leaves().map(|l| l.points.len()).collect();
    /// assert_eq!(counts, [1, 0, 0, 1]);
    /// ```
    pub fn leaves(&self) -> Leaves<'_, S, T, D> {
        Leaves {
            tree: self,
            walk: self.tree.leaves(),
            start: 0,
        }
    }
}
