//! [`Location`]: where a point lies with respect to a tree's domain, the one answer of every
//! `locate` (the point trees, the compressed and skip quadtrees, the planar point locator).

/// Where a query point lies: inside the domain, in the node (or face) `N` that holds it, or
/// outside the domain, first on `axis`. A point that is not a point at all (NaN, an infinity,
/// an integer `f64` cannot hold) is a [`QueryError`](super::QueryError) instead.
///
/// ```
/// use orthtree::query::Location;
/// use orthtree::{tree::NodeId, Quadtree};
/// let t = Quadtree::new(&[([0.0, 0.0], 'a'), ([1.0, 1.0], 'b')]).unwrap();
/// assert_eq!(t.locate(&[0.5, 0.5]), Ok(Location::Inside(NodeId::ROOT)));
/// assert_eq!(t.locate(&[0.5, 2.0]), Ok(Location::Outside { axis: 1 }));
/// assert!(t.locate(&[f64::NAN, 0.0]).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Location<N> {
    /// Inside the domain (its closed box), held by this node or face.
    Inside(N),
    /// Outside the domain: `axis` is the first axis on which the point lies outside its
    /// interval.
    Outside {
        /// The first axis on which the point is outside the domain.
        axis: usize,
    },
}

impl<N> Location<N> {
    /// The node or face holding the point; `None` when it lies outside the domain.
    ///
    /// ```
    /// use orthtree::query::Location;
    /// assert_eq!(Location::Inside(3).inside(), Some(3));
    /// assert_eq!(Location::<u32>::Outside { axis: 0 }.inside(), None);
    /// ```
    pub fn inside(self) -> Option<N> {
        match self {
            Location::Inside(n) => Some(n),
            Location::Outside { .. } => None,
        }
    }

    /// The location with the holder mapped by `f`.
    pub fn map<M>(self, f: impl FnOnce(N) -> M) -> Location<M> {
        match self {
            Location::Inside(n) => Location::Inside(f(n)),
            Location::Outside { axis } => Location::Outside { axis },
        }
    }
}
