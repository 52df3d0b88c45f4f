//! The reference 2:1 balance: the chapter's BALANCEQUADTREE (section 14.2, Theorem 14.4) generalised to D
//! dimensions, to face, edge and corner connectivity, and to the weak balance of exercise 14.6
//! (adjacent leaves may differ by a factor 4, i.e. two levels).
//!
//! A worklist holds leaves to examine. A leaf must be split when some leaf adjacent to it (under
//! the chosen connectivity) is more than `max_level_difference` levels deeper; that is found with
//! [`Tree::neighbor`]: the same-level neighbour has an internal descendant touching the shared
//! side `max_level_difference` levels down. After a split, its 2^D children are examined, and so
//! is every neighbour leaf now too coarse next to them. Every split is forced, so the result is
//! the coarsest balanced refinement.
//!
//! The crate's [`Tree::balance`] (in `ripple.rs`) gives the same tree faster; this one stays as the
//! oracle it is tested against, and is where [`BalanceOptions`] lives.
//!
//! Splits: the chapter's charging argument carries over to D dimensions and to every connectivity
//! and ratio: each split cell has an original (pre-balance) cell among its 3^D - 1 same-size
//! neighbours, so balancing a tree of m nodes makes at most (3^D - 1) m splits (8m in 2D).
//! Time: O((d + 1)(m + splits)) with d the depth.

use super::{NodeId, Tree};
use crate::geom::{Connectivity, Direction};
use core::num::NonZeroU8;

/// What "balanced" means: which leaves are adjacent and how far their levels may differ.
///
/// The level difference is private so that no value outside
/// 1..=[`BalanceOptions::MAX_LEVEL_DIFFERENCE`] can be built: [`BalanceOptions::new`] gives 1 (2:1
/// balance), [`BalanceOptions::weak`] 2, and [`BalanceOptions::with_max_level_difference`] any
/// other value, checked.
///
/// ```
/// use orthtree::{BalanceOptions, Connectivity};
/// let strict = BalanceOptions::new(Connectivity::Face); // the chapter's 2:1 balance
/// let weak = strict.weak();                              // exercise 14.6: factor 4
/// assert_eq!((strict.max_level_difference(), weak.max_level_difference()), (1, 2));
/// let three = strict.with_max_level_difference(3).unwrap();
/// assert_eq!(three.max_level_difference(), 3);
/// let err = strict.with_max_level_difference(0).unwrap_err();
/// assert_eq!(err.to_string(), "max_level_difference 0 is outside 1..=32");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BalanceOptions {
    /// Which leaves count as adjacent.
    pub connectivity: Connectivity,
    /// The largest allowed difference in level between adjacent leaves, in
    /// 1..=[`BalanceOptions::MAX_LEVEL_DIFFERENCE`].
    max_level_difference: NonZeroU8,
}

impl BalanceOptions {
    /// The largest level difference accepted: the deepest level of any tree
    /// ([`crate::Cell::MAX_LEVEL`] is at most 32), beyond which every tree is balanced.
    pub const MAX_LEVEL_DIFFERENCE: u8 = 32;

    /// 2:1 balance with `connectivity`.
    pub const fn new(connectivity: Connectivity) -> Self {
        BalanceOptions {
            connectivity,
            max_level_difference: NonZeroU8::MIN,
        }
    }

    /// The same, weakened to a factor 4 between adjacent leaves.
    pub const fn weak(self) -> Self {
        BalanceOptions {
            max_level_difference: NonZeroU8::MIN.saturating_add(1),
            ..self
        }
    }

    /// The same with `max_level_difference` levels allowed between adjacent leaves (1 is 2:1
    /// balance, 2 the weak balance of exercise 14.6).
    ///
    /// # Errors
    /// [`LevelDifferenceError`] when `max_level_difference` is 0 or above
    /// [`BalanceOptions::MAX_LEVEL_DIFFERENCE`].
    pub const fn with_max_level_difference(
        self,
        max_level_difference: u8,
    ) -> Result<Self, LevelDifferenceError> {
        match NonZeroU8::new(max_level_difference) {
            Some(k) if max_level_difference <= Self::MAX_LEVEL_DIFFERENCE => Ok(BalanceOptions {
                max_level_difference: k,
                ..self
            }),
            _ => Err(LevelDifferenceError {
                value: max_level_difference,
            }),
        }
    }

    /// The largest allowed difference in level between adjacent leaves: 1 is 2:1 balance, 2 is
    /// the weak (4:1) balance of exercise 14.6.
    #[inline]
    pub const fn max_level_difference(&self) -> u8 {
        self.max_level_difference.get()
    }
}

/// Why [`BalanceOptions::with_max_level_difference`] refused: the level difference is 0 or above
/// [`BalanceOptions::MAX_LEVEL_DIFFERENCE`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LevelDifferenceError {
    /// The level difference asked for.
    pub value: u8,
}

impl core::fmt::Display for LevelDifferenceError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "max_level_difference {} is outside 1..={}",
            self.value,
            BalanceOptions::MAX_LEVEL_DIFFERENCE
        )
    }
}

impl std::error::Error for LevelDifferenceError {}

impl From<Connectivity> for BalanceOptions {
    fn from(connectivity: Connectivity) -> Self {
        BalanceOptions::new(connectivity)
    }
}

impl<const D: usize> Tree<D> {
    /// The chapter's BALANCEQUADTREE, generalised: the same result as [`Tree::balance`], by a
    /// worklist of leaves and neighbour searches below each neighbour. Kept as the reference that
    /// [`Tree::balance`] is tested against; slower by a constant factor.
    ///
    /// Refines the tree to the coarsest balanced tree containing it and returns the leaves it
    /// split, in the order it split them (each split leaf's children follow from
    /// [`Tree::children`]; the list may hold leaves created by earlier splits in it).
    ///
    /// Complexity: at most (3^D - 1) m splits for a tree of m nodes (Theorem 14.4, generalised
    /// in the module doc), O(d + 1) per neighbour query.
    pub fn balance_chapter(&mut self, options: impl Into<BalanceOptions>) -> Vec<NodeId> {
        let options = options.into();
        let k = options.max_level_difference();
        let directions: Vec<Direction> = Direction::all::<D>(options.connectivity).collect();
        let mut work: Vec<NodeId> = self.leaves().map(|(id, _)| id).collect();
        let mut split = Vec::new();
        while let Some(leaf) = work.pop() {
            if !self.is_leaf(leaf) || !self.must_split(leaf, &directions, k) {
                continue;
            }
            let first = self.split(leaf);
            split.push(leaf);
            let child_level = self.level(first);
            work.extend(self.children(leaf));
            for &d in &directions {
                if let Some(n) = self.neighbor(leaf, d) {
                    if self.is_leaf(n) && self.level(n) + k < child_level {
                        work.push(n);
                    }
                }
            }
        }
        split
    }

    /// The reference check for [`Tree::is_balanced`]: for every leaf and direction, looks for a
    /// too-deep leaf below the neighbour. `true` when no two adjacent leaves (under `options`'
    /// connectivity) differ by more than `options.max_level_difference()` levels. O((d + 1) m).
    pub fn is_balanced_chapter(&self, options: impl Into<BalanceOptions>) -> bool {
        let options = options.into();
        let directions: Vec<Direction> = Direction::all::<D>(options.connectivity).collect();
        self.leaves()
            .all(|(leaf, _)| !self.must_split(leaf, &directions, options.max_level_difference()))
    }

    /// `true` when some leaf adjacent to `leaf` in one of `directions` is more than `k` levels
    /// deeper.
    fn must_split(&self, leaf: NodeId, directions: &[Direction], k: u8) -> bool {
        let level = self.level(leaf);
        directions.iter().any(|&d| {
            let Some(n) = self.neighbor(leaf, d) else {
                return false;
            };
            if self.level(n) != level || self.is_leaf(n) {
                return false;
            }
            let mut too_deep = false;
            self.touching_leaves(n, d.opposite(), k as usize, |v| {
                too_deep |= !self.is_leaf(v);
            });
            too_deep
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weak_balance_allows_two_levels() {
        let mut t = Tree::<2>::new();
        let f = t.split(NodeId::ROOT);
        let g = t.split(f); // SW at level 1 split: level-2 leaves next to level-1 SE
        assert!(t.is_balanced_chapter(Connectivity::Corner));
        t.split(NodeId(g.0 + 3)); // level-3 leaves touch SE (level 1) at a corner... and face
        assert!(!t.is_balanced_chapter(Connectivity::Face));
        assert!(t.is_balanced_chapter(BalanceOptions::new(Connectivity::Corner).weak()));
        let split = t.balance_chapter(BalanceOptions::new(Connectivity::Face).weak());
        assert!(split.is_empty());
        let split = t.balance_chapter(Connectivity::Face);
        assert_eq!(split.len(), 2); // SE and NW
        assert!(t.is_balanced_chapter(Connectivity::Face));
        // NE (level 1) still touches a level-3 leaf at the centre point
        assert!(!t.is_balanced_chapter(Connectivity::Corner));
        assert_eq!(t.balance_chapter(Connectivity::Corner).len(), 1);
        assert!(t.is_balanced_chapter(Connectivity::Corner));
    }
}
