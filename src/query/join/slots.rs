//! The slots of a point set's index positions without the set's type ([`SlotView`]): the
//! joins' kernels take it instead of the sets, so that each is compiled once per point type,
//! index and visitor rather than once per pair of set types (the joins of four trees with each
//! other would otherwise compile sixteen copies of every kernel).

use crate::query::{PointSet, PositionSlots, SpatialIndex};

/// A set's own [`PointSet::slot_of`] by position alone, for sets without a table.
pub(crate) trait SlotAt<const D: usize> {
    /// The slot of the point at position `i` of the set's index.
    fn slot_at(&self, i: usize) -> usize;
}

impl<P: PointSet<D>, const D: usize> SlotAt<D> for P {
    fn slot_at(&self, i: usize) -> usize {
        self.slot_of(i, &self.index().payloads()[i])
    }
}

/// The slots of one side's positions, as [`PointSet::position_slots`] gives them, with
/// [`PointSet::slot_of`] behind a reference where the set has no table.
#[derive(Clone, Copy)]
pub(crate) enum SlotView<'a, const D: usize> {
    /// The slot of each position is the position.
    Same,
    /// The slot of position `i` is `table[i]`.
    Table(&'a [u32]),
    /// The set's own `slot_of`.
    Other(&'a dyn SlotAt<D>),
}

impl<'a, const D: usize> SlotView<'a, D> {
    /// The view of `set`'s slots.
    #[inline]
    pub(crate) fn of<P: PointSet<D>>(set: &'a P) -> Self {
        match set.position_slots() {
            PositionSlots::Same => SlotView::Same,
            PositionSlots::Table(t) => SlotView::Table(t),
            PositionSlots::Other => SlotView::Other(set),
        }
    }

    /// The slot of position `i`.
    #[inline(always)]
    pub(crate) fn slot(self, i: usize) -> usize {
        match self {
            SlotView::Same => i,
            SlotView::Table(t) => t[i] as usize,
            SlotView::Other(set) => set.slot_at(i),
        }
    }
}
