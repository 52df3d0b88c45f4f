//! Serde for the topology [`Tree`]: its arrays as stored (`raw.rs` in `tree`), read back through
//! [`Tree::from_raw_parts`], which checks levels, block parents and then [`Tree::validate`].

use crate::tree::raw::{OwnedRawTree, RawTree};
use crate::Tree;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The arena's arrays (also the `tree` field of a point tree): slices written, vectors read
/// back.
#[derive(Serialize, Deserialize)]
pub(super) struct TreeFields<W, B> {
    dimension: usize,
    first_child: W,
    level: B,
    block_parent: W,
    free_blocks: W,
    live_blocks: W,
    depth: u8,
}

/// The arena's arrays, by reference.
pub(super) type TreeRef<'a> = TreeFields<&'a [u32], &'a [u8]>;

/// The arena's arrays as read, not yet checked.
pub(super) type TreeOwned = TreeFields<Vec<u32>, Vec<u8>>;

impl<'a> TreeRef<'a> {
    pub(super) fn new<const D: usize>(raw: RawTree<'a>) -> Self {
        TreeRef {
            dimension: D,
            first_child: raw.first_child,
            level: raw.level,
            block_parent: raw.block_parent,
            free_blocks: raw.free_blocks,
            live_blocks: raw.live_blocks,
            depth: raw.depth,
        }
    }
}

impl TreeOwned {
    /// The arrays, once the dimension is checked to be `D`.
    pub(super) fn into_raw<E: serde::de::Error, const D: usize>(self) -> Result<OwnedRawTree, E> {
        if self.dimension != D {
            return Err(E::custom(format!(
                "tree: dimension {}, expected {D}",
                self.dimension
            )));
        }
        Ok(OwnedRawTree {
            first_child: self.first_child,
            level: self.level,
            block_parent: self.block_parent,
            free_blocks: self.free_blocks,
            live_blocks: self.live_blocks,
            depth: self.depth,
        })
    }
}

impl<const D: usize> Serialize for Tree<D> {
    fn serialize<Se: Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        TreeRef::new::<D>(self.raw_parts()).serialize(s)
    }
}

impl<'de, const D: usize> Deserialize<'de> for Tree<D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let raw = TreeOwned::deserialize(d)?.into_raw::<De::Error, D>()?;
        Tree::from_raw_parts(raw).map_err(|e| De::Error::custom(format!("tree: {e}")))
    }
}
