//! [`BalanceOptions`]: what "balanced" means for [`Tree::balance`](super::Tree::balance), its
//! check [`Tree::is_balanced`](super::Tree::is_balanced) and the balanced split
//! [`Tree::split_balanced`](super::Tree::split_balanced): which leaves are adjacent (face, edge
//! or corner connectivity) and how many levels apart they may be (1 for the chapter's 2:1
//! balance, 2 for the weak balance of exercise 14.6).

use crate::geom::Connectivity;
use core::num::NonZeroU8;

/// What "balanced" means: which leaves are adjacent and how far their levels may differ.
///
/// The level difference is private so that no value outside
/// 1..=[`BalanceOptions::MAX_LEVEL_DIFFERENCE`] can be built: [`BalanceOptions::new`] gives 1 (2:1
/// balance), [`BalanceOptions::weak`] 2, and [`BalanceOptions::with_max_level_difference`] any
/// other value, checked.
///
/// ```
/// use orthtree::{tree::BalanceOptions, Connectivity};
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
