//! [`DistError`]: every way a collective operation of [`crate::dist`] refuses its input. Each
//! is agreed on by every rank before any exchange that depends on it (an error flag gathered
//! from every rank, then the offending input sent from the lowest failing rank, so that every
//! rank builds the same error value), so a bad input on one rank never leaves another waiting.

use crate::error::Error;
use crate::query::QueryError;

/// A collective operation refused, with the same value on every rank.
///
/// ```
/// use orthtree::{dist::DistError, Error};
/// let e = DistError::Input { rank: 2, error: Error::ZeroBucketSize };
/// assert_eq!(e.to_string(), "rank 2: the bucket size must be at least 1");
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum DistError {
    /// The input of rank `rank` was refused: a point (its index in that rank's input) or a
    /// setting, as the single-process build would refuse it.
    Input {
        /// The lowest rank whose input was refused.
        rank: usize,
        /// The error, naming the point by its index on that rank.
        error: Error,
    },
    /// The ranks were given different settings (bucket size, maximum depth, root box).
    SettingsDiffer {
        /// The lowest rank whose settings differ from rank 0's.
        rank: usize,
    },
    /// More points in total than the distributed tree can number.
    TooManyPoints {
        /// The total number of points over all ranks.
        len: u64,
        /// The largest total allowed.
        limit: u64,
    },
    /// One rank would send or receive more 8-byte words in one exchange than MPI can count
    /// (an `i32`).
    MessageTooLarge {
        /// The lowest rank over the limit.
        rank: usize,
        /// The words it would send or receive.
        words: u64,
        /// The limit.
        limit: u64,
    },
    /// Query `index` of rank `rank`'s batch was refused, as the single-process query would
    /// refuse it.
    Query {
        /// The lowest rank with a bad query.
        rank: usize,
        /// The query's position in that rank's batch.
        index: usize,
        /// What is wrong with it.
        error: QueryError,
    },
    /// Weight `index` of rank `rank` is negative, NaN or infinite.
    InvalidWeight {
        /// The lowest rank with a bad weight.
        rank: usize,
        /// The weight's position on that rank.
        index: usize,
        /// The weight (compared by its bits).
        value: crate::geom::FloatBits,
    },
    /// A rank gave a number of weights other than its number of elements.
    WeightCount {
        /// The lowest rank whose count is wrong.
        rank: usize,
        /// The weights it gave.
        weights: usize,
        /// Its elements.
        elements: usize,
    },
    /// The leaves given to a forest ([`DistForest::new`](super::DistForest::new)) do not tile
    /// the root cube in Morton order, one contiguous run per rank.
    Leaves {
        /// The lowest rank where the order breaks.
        rank: usize,
        /// The leaf's position on that rank (the rank's leaf count when the run ends too early).
        index: usize,
        /// What is wrong there.
        problem: LeafProblem,
    },
    /// A partition's target table is not one first position per rank, non-decreasing from 0
    /// to the total, plus the total.
    InvalidTargets {
        /// The first entry that breaks it.
        index: usize,
    },
}

impl core::fmt::Display for DistError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            DistError::Input { rank, error } => write!(f, "rank {rank}: {error}"),
            DistError::SettingsDiffer { rank } => {
                write!(f, "rank {rank}: the build settings differ from rank 0's")
            }
            DistError::TooManyPoints { len, limit } => write!(
                f,
                "{len} points in total exceed the {limit} a distributed tree holds"
            ),
            DistError::MessageTooLarge { rank, words, limit } => write!(
                f,
                "rank {rank}: {words} words in one exchange exceed MPI's count limit {limit}"
            ),
            DistError::Query { rank, index, error } => {
                write!(f, "rank {rank}: query {index} of the batch: {error}")
            }
            DistError::InvalidWeight { rank, index, value } => write!(
                f,
                "rank {rank}: weight {index} is {value}, not a finite non-negative number"
            ),
            DistError::WeightCount {
                rank,
                weights,
                elements,
            } => write!(
                f,
                "rank {rank}: {weights} weights given for {elements} elements"
            ),
            DistError::Leaves {
                rank,
                index,
                problem,
            } => write!(f, "rank {rank}: leaf {index}: {problem}"),
            DistError::InvalidTargets { index } => write!(
                f,
                "entry {index} of the partition targets breaks the order 0 <= ... <= total"
            ),
        }
    }
}

/// How the leaves of a forest fail to tile the root cube in Morton order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LeafProblem {
    /// The leaf overlaps the leaf before it or comes before it in Morton order (on the same rank,
    /// or, for a rank's first leaf, the last leaf of the ranks before it).
    Overlap,
    /// Part of the root cube between the previous leaf (on this rank or the ranks before) and
    /// this one is covered by no leaf; at the rank's leaf count, the part after its last leaf.
    Gap,
}

impl core::fmt::Display for LeafProblem {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            LeafProblem::Overlap => "overlaps the leaf before it or precedes it in Morton order",
            LeafProblem::Gap => "leaves part of the root cube before it uncovered",
        })
    }
}

impl std::error::Error for DistError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            DistError::Input { error, .. } => Some(error),
            DistError::Query { error, .. } => Some(error),
            _ => None,
        }
    }
}
