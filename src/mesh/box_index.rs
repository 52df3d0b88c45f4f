//! [`BoxIndex`]: closed integer boxes in [0, U]^2 in a small quadtree (an MX-CIF quadtree: each
//! box is kept at the smallest cell that contains it), answering "does this box meet one of
//! them?". [`random_board`](super::random_board) places its components with it, instead of
//! testing each new bounding box against every earlier one.

use super::Point;

/// No node or box.
const NONE: u32 = u32::MAX;

/// One quadtree cell: its children (`NONE` when absent) and the first box kept here.
#[derive(Clone, Copy)]
struct Node {
    children: [u32; 4],
    first_box: u32,
}

/// One box and the next box of the same node.
#[derive(Clone, Copy)]
struct Stored {
    lo: Point,
    hi: Point,
    next: u32,
}

/// Closed integer boxes `[lo, hi]` in a quadtree over `[0, 2U)^2` (so every point of `[0, U]^2`
/// lies inside the root cell).
pub(crate) struct BoxIndex {
    root_side: i64,
    nodes: Vec<Node>,
    boxes: Vec<Stored>,
}

impl BoxIndex {
    /// An empty index for boxes in `[0, size]^2`.
    pub(crate) fn new(size: i64) -> Self {
        BoxIndex {
            root_side: 2 * size.max(1),
            nodes: vec![Node {
                children: [NONE; 4],
                first_box: NONE,
            }],
            boxes: Vec::new(),
        }
    }

    /// Keeps the box `[lo, hi]` (both corners inclusive, inside `[0, U]^2`).
    pub(crate) fn insert(&mut self, lo: Point, hi: Point) {
        let (mut node, mut origin, mut side) = (0usize, [0i64, 0], self.root_side);
        while side > 1 {
            let half = side / 2;
            let quadrant = |a: usize| {
                let mid = origin[a] + half;
                if hi[a] < mid {
                    Some(0)
                } else if lo[a] >= mid {
                    Some(1)
                } else {
                    None
                }
            };
            let (Some(qx), Some(qy)) = (quadrant(0), quadrant(1)) else {
                break;
            };
            let q = qx + 2 * qy;
            let child = match self.nodes[node].children[q] {
                NONE => {
                    let id = self.nodes.len() as u32;
                    self.nodes.push(Node {
                        children: [NONE; 4],
                        first_box: NONE,
                    });
                    self.nodes[node].children[q] = id;
                    id
                }
                id => id,
            };
            node = child as usize;
            origin = [origin[0] + qx as i64 * half, origin[1] + qy as i64 * half];
            side = half;
        }
        let id = self.boxes.len() as u32;
        self.boxes.push(Stored {
            lo,
            hi,
            next: self.nodes[node].first_box,
        });
        self.nodes[node].first_box = id;
    }

    /// Whether `[lo, hi]` shares a point with a box kept here (closed boxes: touching counts).
    pub(crate) fn meets(&self, lo: Point, hi: Point) -> bool {
        let overlaps =
            |a_lo: Point, a_hi: Point| (0..2).all(|a| a_lo[a] <= hi[a] && lo[a] <= a_hi[a]);
        // An explicit stack: at most 3 entries per level of a tree at most 32 levels deep.
        let mut stack = vec![(0usize, [0i64, 0], self.root_side)];
        while let Some((node, origin, side)) = stack.pop() {
            let mut b = self.nodes[node].first_box;
            while b != NONE {
                let stored = self.boxes[b as usize];
                if overlaps(stored.lo, stored.hi) {
                    return true;
                }
                b = stored.next;
            }
            let half = side / 2;
            for (q, &child) in self.nodes[node].children.iter().enumerate() {
                if child == NONE {
                    continue;
                }
                let at = [
                    origin[0] + (q & 1) as i64 * half,
                    origin[1] + (q >> 1) as i64 * half,
                ];
                if overlaps(at, [at[0] + half - 1, at[1] + half - 1]) {
                    stack.push((child as usize, at, half));
                }
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The index agrees with a scan of every box on boxes of many scales, touching included.
    #[test]
    fn agrees_with_a_linear_scan() {
        let mut state = 0x1234_5678_9abc_def0u64;
        let mut next = |bound: i64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % bound as u64) as i64
        };
        for size in [8i64, 64, 1024, 1 << 20] {
            let mut index = BoxIndex::new(size);
            let mut all: Vec<(Point, Point)> = Vec::new();
            for _ in 0..400 {
                let extent = 1 + next(size / 4);
                let lo = [next(size - extent + 1), next(size - extent + 1)];
                let hi = [lo[0] + next(extent + 1), lo[1] + next(extent + 1)];
                let scan = all
                    .iter()
                    .any(|&(l, h)| (0..2).all(|a| l[a] <= hi[a] && lo[a] <= h[a]));
                assert_eq!(index.meets(lo, hi), scan, "U = {size}, box {lo:?}..{hi:?}");
                if !scan {
                    index.insert(lo, hi);
                    all.push((lo, hi));
                    assert!(index.meets(lo, hi));
                    assert!(index.meets(hi, hi), "a corner touches");
                }
            }
            assert!(all.len() > 1, "U = {size}: some boxes placed");
        }
    }
}
