//! The slots of a point set's index positions without the set's type ([`SlotView`]): the
//! joins' kernels take it instead of the sets, so that each is compiled once per point type,
//! index and visitor rather than once per pair of set types (the joins of four trees with each
//! other would otherwise compile sixteen copies of every kernel).

use crate::query::PositionSlots;

/// The slots of one side's positions, as [`PointSet::position_slots`] gives them, with
/// [`PointSet::slot_of`] behind a reference where the set has no table.
///
/// [`PointSet::position_slots`]: crate::query::PointSet::position_slots
/// [`PointSet::slot_of`]: crate::query::PointSet::slot_of
#[derive(Clone, Copy)]
pub(crate) enum SlotView<'a> {
    /// The slot of each position is the position.
    Same,
    /// The slot of position `i` is `table[i]`.
    Table(&'a [u32]),
    /// The set's own `slot_of`.
    Other(&'a dyn Fn(usize) -> usize),
}

impl<'a> SlotView<'a> {
    /// The view of `slots`, with `slot_of` for [`PositionSlots::Other`].
    #[inline]
    pub(crate) fn of(slots: PositionSlots<'a>, slot_of: &'a dyn Fn(usize) -> usize) -> Self {
        match slots {
            PositionSlots::Same => SlotView::Same,
            PositionSlots::Table(t) => SlotView::Table(t),
            PositionSlots::Other => SlotView::Other(slot_of),
        }
    }

    /// The slot of position `i`.
    #[inline(always)]
    pub(crate) fn slot(self, i: usize) -> usize {
        match self {
            SlotView::Same => i,
            SlotView::Table(t) => t[i] as usize,
            SlotView::Other(f) => f(i),
        }
    }
}
