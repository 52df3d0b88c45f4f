//! [`PointSetMut`]: the updates of the point trees that take them (insert, and removal by
//! point, by item or by a test on the item), and [`InsertError`], the refused insert that hands
//! the item back.

use super::point_set::PointSet;
use crate::error::Error;

/// The updates of a [`PointSet`] that takes them: [`PointTree`](crate::PointTree),
/// [`DynamicPointTree`](crate::DynamicPointTree), [`CompressedTree`](crate::CompressedTree) and
/// [`SkipQuadtree`](crate::SkipQuadtree).
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{DynamicPointTree, Quadtree};
/// fn churn<P: PointSetMut<2, Scalar = f64, Item = u32>>(t: &mut P) {
///     t.insert([0.25, 0.5], 7).unwrap();
///     assert!(t.remove(&[0.25, 0.5], &7));
///     assert_eq!(t.remove_point(&[0.0, 0.0]), Some(1));
///     t.validate().unwrap();
/// }
/// let pts = [([0.0, 0.0], 1), ([1.0, 1.0], 2)];
/// churn(&mut Quadtree::new(&pts).unwrap());
/// churn(&mut DynamicPointTree::new(&pts).unwrap());
/// ```
pub trait PointSetMut<const D: usize>: PointSet<D> {
    /// Adds `item` at `point`.
    ///
    /// # Errors
    /// A NaN, infinite or inexact coordinate, or a point outside [`PointSet::domain`] (a tree
    /// never grows its root box); too many points. The set is unchanged then, and the error
    /// hands the item back ([`InsertError::item`]).
    fn insert(
        &mut self,
        point: [Self::Scalar; D],
        item: Self::Item,
    ) -> Result<(), InsertError<Self::Item>>;

    /// Removes one point at exactly `point` whose item `wanted` accepts and returns that item;
    /// `None` (and the set unchanged) if there is none. [`remove`](Self::remove) and
    /// [`remove_point`](Self::remove_point) are this with a fixed test; each tree's
    /// implementation says which of several matches goes and what it costs.
    ///
    /// ```
    /// use orthtree::prelude::*;
    /// use orthtree::Quadtree;
    /// let mut t = Quadtree::new(&[([0.0, 0.0], 1), ([0.0, 0.0], 2), ([0.0, 0.0], 3)]).unwrap();
    /// assert_eq!(t.remove_where(&[0.0, 0.0], |&i| i % 2 == 0), Some(2));
    /// assert_eq!(t.remove_where(&[0.0, 0.0], |&i| i > 5), None);
    /// assert_eq!(t.len(), 2);
    /// ```
    fn remove_where(
        &mut self,
        point: &[Self::Scalar; D],
        wanted: impl Fn(&Self::Item) -> bool,
    ) -> Option<Self::Item>;

    /// Removes one stored pair equal to (`point`, `item`); `false` if there is none.
    fn remove(&mut self, point: &[Self::Scalar; D], item: &Self::Item) -> bool
    where
        Self::Item: PartialEq,
    {
        self.remove_where(point, |t| t == item).is_some()
    }

    /// Removes one point at exactly `point` and returns its item; `None` if there is none.
    fn remove_point(&mut self, point: &[Self::Scalar; D]) -> Option<Self::Item> {
        self.remove_where(point, |_| true)
    }
}

/// An insert [`PointSetMut::insert`] refused: why, and the item, handed back unchanged.
///
/// ```
/// use orthtree::prelude::*;
/// use orthtree::{Error, Quadtree};
/// let mut t = Quadtree::new(&[([0.0, 0.0], String::from("a"))]).unwrap();
/// let refused = t.insert([f64::NAN, 0.0], String::from("kept")).unwrap_err();
/// assert!(matches!(refused.error, Error::NonFiniteCoordinate { axis: 0, .. }));
/// assert_eq!(refused.item, "kept");
/// assert_eq!(t.len(), 1);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InsertError<T> {
    /// Why the point was refused.
    pub error: Error,
    /// The item that was to be inserted.
    pub item: T,
}

impl<T> core::fmt::Display for InsertError<T> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "insert refused: {}", self.error)
    }
}

impl<T: core::fmt::Debug> std::error::Error for InsertError<T> {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

impl<T> From<InsertError<T>> for Error {
    fn from(e: InsertError<T>) -> Self {
        e.error
    }
}
