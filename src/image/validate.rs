//! [`RegionTree::validate`]: the canonical form checked in one pass over the pre-order sequence,
//! the first broken invariant named by a [`Malformation`] with the node's position.

use super::{ImageError, RegionTree, BLACK, INTERNAL, WHITE};
use core::fmt;

/// The invariant of the canonical form that a node sequence breaks, in
/// [`ImageError::Malformed`] (which gives the node's position in pre-order).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Malformation {
    /// The sequence ends before the root's subtree is complete (the position is its length).
    EndsInsideTree,
    /// An internal node at the pixel level (depth k), where cells are single pixels.
    InternalAtPixelLevel,
    /// A black leaf whose cell reaches outside the extent (the padding must stay white).
    BlackOutsideExtent {
        /// The cell's lowest pixel, per axis.
        min: Vec<u32>,
        /// The cell's side in pixels.
        side: u64,
    },
    /// A node kind other than white (0), black (1) or internal (2).
    UnknownKind {
        /// The byte found.
        kind: u8,
    },
    /// Nodes after the root's subtree is complete (the position is the first of them).
    TrailingNodes {
        /// The sequence's length.
        len: usize,
    },
    /// An internal node whose 2^D children are leaves of one colour (it should be that leaf).
    Collapsible {
        /// The children's kind (0 white, 1 black).
        colour: u8,
    },
}

impl fmt::Display for Malformation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Malformation::EndsInsideTree => f.write_str("sequence ends inside the tree"),
            Malformation::InternalAtPixelLevel => f.write_str("internal node at the pixel level"),
            Malformation::BlackOutsideExtent { min, side } => write!(
                f,
                "black leaf outside the extent (cell from {min:?}, side {side})"
            ),
            Malformation::UnknownKind { kind } => write!(f, "unknown node kind {kind}"),
            Malformation::TrailingNodes { len } => {
                write!(f, "trailing nodes after the root's subtree (length {len})")
            }
            Malformation::Collapsible { colour } => {
                let colour = if *colour == BLACK { "black" } else { "white" };
                write!(
                    f,
                    "internal node whose children are leaves of one colour ({colour})"
                )
            }
        }
    }
}

/// An open internal node of the walk: its position, the child being read, its cell's lowest
/// pixel.
type Open<const D: usize> = (usize, usize, [u32; D]);

impl<const D: usize> RegionTree<D> {
    /// Checks the canonical form: a well-formed pre-order sequence (every internal node has 2^D
    /// complete subtrees, no trailing nodes, no leaf deeper than k), no internal node whose
    /// children are leaves of one colour, and no black pixel outside the extent.
    ///
    /// Every constructor and operation returns canonical trees; this is the check tests run
    /// after each of them.
    ///
    /// # Errors
    /// [`ImageError::Malformed`] with the position of the first offending node in pre-order and
    /// the [`Malformation`] found there.
    ///
    /// # Complexity
    /// O(n) time for n nodes, one pass; memory one entry per level of the current path.
    ///
    /// ```
    /// use orthtree::image::{ImageError, ImageTree, Malformation};
    /// let err = ImageTree::from_nodes([2, 2], vec![2, 1, 0, 0]).unwrap_err();
    /// assert_eq!(
    ///     err,
    ///     ImageError::Malformed { position: 4, invariant: Malformation::EndsInsideTree }
    /// );
    /// ```
    pub fn validate(&self) -> Result<(), ImageError> {
        let mut stack: Vec<Open<D>> = Vec::new();
        let mut min = [0u32; D];
        let mut i = 0;
        loop {
            let Some(&kind) = self.nodes.get(i) else {
                return malformed(i, Malformation::EndsInsideTree);
            };
            if self.check_node(i, kind, stack.len() as u8, min)? {
                stack.push((i, 0, min));
                i += 1;
                continue;
            }
            i += 1;
            match self.close_complete(&mut stack, i)? {
                Some(next) => min = next,
                None => return Ok(()),
            }
        }
    }

    /// Whether [`RegionTree::validate`] passes.
    ///
    /// # Complexity
    /// As [`RegionTree::validate`].
    pub fn is_canonical(&self) -> bool {
        self.validate().is_ok()
    }

    /// Checks node `i` of kind `kind` at `level` with lowest pixel `min`; `true` if it is
    /// internal (its children follow).
    fn check_node(&self, i: usize, kind: u8, level: u8, min: [u32; D]) -> Result<bool, ImageError> {
        match kind {
            INTERNAL if level == self.depth => malformed(i, Malformation::InternalAtPixelLevel),
            INTERNAL => Ok(true),
            BLACK => {
                let side = 1u64 << (self.depth - level);
                let inside = (0..D).all(|a| u64::from(min[a]) + side <= u64::from(self.extent[a]));
                if inside {
                    Ok(false)
                } else {
                    let min = min.to_vec();
                    malformed(i, Malformation::BlackOutsideExtent { min, side })
                }
            }
            WHITE => Ok(false),
            kind => malformed(i, Malformation::UnknownKind { kind }),
        }
    }

    /// After a node that ends at position `i` is complete: moves to the next sibling, closing
    /// the parents it completes (each checked not to be collapsible). The next sibling's lowest
    /// pixel, or `None` when the root is complete (and must end the sequence).
    fn close_complete(
        &self,
        stack: &mut Vec<Open<D>>,
        i: usize,
    ) -> Result<Option<[u32; D]>, ImageError> {
        let n = 1usize << D;
        loop {
            let open = stack.len() as u8;
            let Some(top) = stack.last_mut() else {
                if i != self.nodes.len() {
                    let len = self.nodes.len();
                    return malformed(i, Malformation::TrailingNodes { len });
                }
                return Ok(None);
            };
            top.1 += 1;
            if top.1 < n {
                let min = super::iter::child(top.2, open - 1, self.depth, top.1 as u16);
                return Ok(Some(min));
            }
            let (start, _, _) = stack.pop().expect("non-empty");
            let first = self.nodes[start + 1];
            if i == start + 1 + n
                && first != INTERNAL
                && self.nodes[start + 1..i].iter().all(|&y| y == first)
            {
                return malformed(start, Malformation::Collapsible { colour: first });
            }
        }
    }
}

/// The error for `invariant` broken at node `position`.
fn malformed<T>(position: usize, invariant: Malformation) -> Result<T, ImageError> {
    Err(ImageError::Malformed {
        position,
        invariant,
    })
}
