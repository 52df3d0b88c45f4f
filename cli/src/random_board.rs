//! `--random SEED,U,COUNT` of `orthtree mesh` and `orthtree heat`: the arguments of
//! [`try_random_board`], checked as they are parsed (U a power of two from 8 to 2^30, COUNT at
//! most the board's capacity), so that drawing the board cannot fail for a reason the
//! command line could have named.

use crate::limits;
use crate::Failure;
use orthtree::mesh::{random_board_capacity, try_random_board, Board};

/// The arguments of [`try_random_board`].
#[derive(Clone, Copy, Debug)]
pub struct RandomBoard {
    /// The seed.
    pub seed: u64,
    /// The board's side U.
    pub size: i64,
    /// The number of components.
    pub count: usize,
}

impl RandomBoard {
    /// `SEED,U,COUNT`, each checked; the count against the board's capacity
    /// ([`random_board_capacity`]).
    pub fn parse(raw: &str) -> Result<Self, String> {
        let parts: Vec<&str> = raw.split(',').collect();
        let [seed, size, count] = parts[..] else {
            return Err("expected SEED,U,COUNT (three numbers separated by commas)".into());
        };
        let seed = limits::parse_number(seed, 0, u64::MAX).map_err(|e| format!("SEED: {e}"))?;
        let size: i64 = limits::parse_number(size, 8, 1 << 30).map_err(|e| format!("U: {e}"))?;
        if size & (size - 1) != 0 {
            return Err(format!("U {size}: expected a power of two from 8 to 2^30"));
        }
        let count: usize =
            limits::parse_number(count, 0, usize::MAX).map_err(|e| format!("COUNT: {e}"))?;
        let capacity = random_board_capacity(size);
        if count as u64 > capacity {
            return Err(format!(
                "COUNT {count}: at most {capacity} components fit a board of side {size}"
            ));
        }
        Ok(RandomBoard { seed, size, count })
    }

    /// The board, with the name the summaries give it.
    ///
    /// # Errors
    /// [`Failure::Input`] with [`try_random_board`]'s refusal (which [`RandomBoard::parse`]
    /// leaves no room for).
    pub fn draw(&self) -> Result<(Board, String), Failure> {
        let RandomBoard { seed, size, count } = *self;
        try_random_board(seed, size, count)
            .map(|b| (b, format!("random_board({seed}, {size}, {count})")))
            .map_err(|e| Failure::Input(e.to_string()))
    }
}
