//! Step 4 of the board checks (see `check.rs`): no component lies inside another.
//!
//! For each component take its leftmost crossing with the horizontal line half a unit above its
//! lowest vertex. Half-integer lines pass through no vertex, and the edges crossing one are
//! totally ordered by x, the same on every such line they share (no two edges cross, step 3). A
//! sweep keeps them in an ordered set; a component lies inside another exactly when the nearest
//! edge to the left of its crossing has the interior of its own component on its right (it runs
//! downward, outlines being counter-clockwise by then). O(E log E) time, O(E) memory.

use super::{BoardError, Component, Point};
use std::cmp::Ordering;
use std::collections::BTreeSet;

/// A non-horizontal edge in doubled coordinates, ordered by its x on the half-integer lines it
/// crosses. Only edges crossing a common half-integer line are ever compared; since edges do not
/// cross, their order is the same on every such line.
#[derive(Clone, Copy, Debug)]
struct Crossing {
    /// Doubled y of the lower end.
    lo: i64,
    /// Doubled y of the upper end.
    hi: i64,
    /// Doubled x of the lower end.
    x_lo: i64,
    /// dx/dy: -1, 0 or 1.
    slope: i64,
    /// `true` when the edge runs downward (the interior of its counter-clockwise component is
    /// then on its right).
    down: bool,
    /// Component, from 0.
    component: usize,
    /// Unique id.
    id: usize,
}

impl Crossing {
    fn new(a: Point, b: Point, component: usize, id: usize) -> Option<Crossing> {
        let (low, high) = match a[1].cmp(&b[1]) {
            Ordering::Less => (a, b),
            Ordering::Greater => (b, a),
            Ordering::Equal => return None,
        };
        Some(Crossing {
            lo: 2 * low[1],
            hi: 2 * high[1],
            x_lo: 2 * low[0],
            slope: (high[0] - low[0]).signum(),
            down: b[1] < a[1],
            component,
            id,
        })
    }

    /// Doubled x on the line at doubled height `y`.
    fn x_at(&self, y: i64) -> i64 {
        self.x_lo + self.slope * (y - self.lo)
    }
}

impl PartialEq for Crossing {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
    }
}

impl Eq for Crossing {}

impl PartialOrd for Crossing {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Crossing {
    fn cmp(&self, other: &Self) -> Ordering {
        // The lowest half-integer line both cross (when they cross a common one at all).
        let y = self.lo.max(other.lo) + 1;
        (self.x_at(y), self.id).cmp(&(other.x_at(y), other.id))
    }
}

/// Step 4 (outlines counter-clockwise, no two edges meeting): see the module doc.
pub(super) fn check_nesting(components: &[Component]) -> Result<(), BoardError> {
    if components.len() < 2 {
        return Ok(());
    }
    let mut crossings = Vec::new();
    // (doubled y of the line, component, its leftmost crossing there)
    let mut queries: Vec<(i64, usize, Crossing)> = Vec::with_capacity(components.len());
    for (ci, c) in components.iter().enumerate() {
        let y = 2 * c.outline.iter().map(|p| p[1]).min().unwrap_or(0) + 1;
        let mut leftmost: Option<Crossing> = None;
        for (a, b) in c.edges() {
            if let Some(k) = Crossing::new(a, b, ci, crossings.len()) {
                crossings.push(k);
                if k.lo < y && y < k.hi && leftmost.is_none_or(|l| k.x_at(y) < l.x_at(y)) {
                    leftmost = Some(k);
                }
            }
        }
        // A simple polygon with non-zero area crosses the line just above its lowest point.
        if let Some(k) = leftmost {
            queries.push((y, ci, k));
        }
    }
    queries.sort_unstable_by_key(|&(y, ci, _)| (y, ci));
    let mut by_lo: Vec<usize> = (0..crossings.len()).collect();
    by_lo.sort_unstable_by_key(|&i| crossings[i].lo);
    let mut by_hi = by_lo.clone();
    by_hi.sort_unstable_by_key(|&i| crossings[i].hi);
    let mut inserted = vec![false; crossings.len()];
    let (mut next_in, mut next_out) = (0, 0);
    let mut active: BTreeSet<Crossing> = BTreeSet::new();
    for (y, ci, key) in queries {
        // Every set member crossed the previous line; those that end below this one leave first,
        // so the set stays ordered consistently.
        while next_out < by_hi.len() && crossings[by_hi[next_out]].hi < y {
            let k = crossings[by_hi[next_out]];
            if inserted[k.id] {
                active.remove(&k);
            }
            next_out += 1;
        }
        while next_in < by_lo.len() && crossings[by_lo[next_in]].lo < y {
            let k = crossings[by_lo[next_in]];
            if k.hi > y {
                active.insert(k);
                inserted[k.id] = true;
            }
            next_in += 1;
        }
        if let Some(left) = active.range(..key).next_back()
            && left.down
        {
            return Err(BoardError::ComponentInside {
                component: ci + 1,
                other: left.component + 1,
            });
        }
    }
    Ok(())
}
