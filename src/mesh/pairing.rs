//! Half-edge pairing, shared by [`HalfEdges::new`](super::HalfEdges::new) and
//! [`Mesh::validate`](super::Mesh::validate): the half-edges of the chosen triangles sorted by
//! their undirected edge, and the twin of each half-edge found among its edge's half-edges.
//!
//! Half-edge `3t + i` runs from `triangles[t][i]` to `triangles[t][(i + 1) % 3]`. The keys are
//! sorted by a counting sort on the edge's smaller vertex followed by a sort of each vertex's few
//! edges, not by hashing or one large sort: O(n + V) plus O(d log d) per vertex of degree d,
//! which keeps the validation of a mesh with a million triangles well under a second.

/// The "no half-edge" value in the twin array.
pub(super) const NONE: u32 = u32::MAX;

/// Why some edge's half-edges cannot be paired (the first such edge in key order).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) enum PairDefect {
    /// Two half-edges run the same way along one edge: these two.
    SameDirection([u32; 2]),
    /// More than two half-edges on one edge: all of them, in index order.
    Crowded(Vec<u32>),
}

/// The half-edges of the chosen triangles, paired.
pub(super) struct Pairing {
    /// (undirected edge key, half-edge), sorted: the key holds the smaller vertex in its high 32
    /// bits, the larger in its low 32 bits.
    pub(super) keys: Vec<(u64, u32)>,
    /// The twin of each half-edge of every triangle, [`NONE`] for half-edges with no twin, on an
    /// edge with a defect, or of a triangle left out.
    pub(super) twins: Vec<u32>,
    /// The first edge, in key order, whose half-edges do not pair.
    pub(super) defect: Option<PairDefect>,
}

/// The sort key of the undirected edge `a`-`b`.
pub(super) fn edge_key(a: u32, b: u32) -> u64 {
    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
}

/// The two vertices of an edge key, smaller first.
pub(super) fn key_vertices(key: u64) -> [u32; 2] {
    [(key >> 32) as u32, key as u32]
}

/// Pairs the half-edges of the triangles `t` with `include(t)`, whose vertex indices must all
/// be below `vertices`; `3 * triangles.len()` must fit a `u32` below [`NONE`].
///
/// # Panics
/// If an included triangle has a vertex index of `vertices` or more (callers check first).
///
/// # Complexity
/// O(T + V) time plus O(d log d) per vertex of degree d, for T triangles and V vertices;
/// 16 bytes per included half-edge and 8 per vertex while sorting, 4 per half-edge kept.
pub(super) fn pair(
    triangles: &[[u32; 3]],
    vertices: usize,
    include: impl Fn(usize) -> bool,
) -> Pairing {
    let keys = sorted_keys(triangles, vertices, include);
    let origin = |h: u32| triangles[h as usize / 3][h as usize % 3];
    let mut twins = vec![NONE; 3 * triangles.len()];
    let mut defect = None;
    for group in keys.chunk_by(|x, y| x.0 == y.0) {
        let found = match *group {
            [_] => None,
            [(_, g), (_, h)] if origin(g) == origin(h) => Some(PairDefect::SameDirection([g, h])),
            [(_, g), (_, h)] => {
                twins[g as usize] = h;
                twins[h as usize] = g;
                None
            }
            _ => Some(PairDefect::Crowded(group.iter().map(|x| x.1).collect())),
        };
        if defect.is_none() {
            defect = found;
        }
    }
    Pairing {
        keys,
        twins,
        defect,
    }
}

/// The (edge key, half-edge) pairs of the included triangles, sorted as `sort_unstable` would:
/// counted by the edge's smaller vertex, placed, then each vertex's run sorted.
fn sorted_keys(
    triangles: &[[u32; 3]],
    vertices: usize,
    include: impl Fn(usize) -> bool,
) -> Vec<(u64, u32)> {
    let half_edges = || {
        (triangles.iter().enumerate())
            .filter(|&(t, _)| include(t))
            .flat_map(|(t, tri)| {
                (0..3).map(move |i| ((3 * t + i) as u32, edge_key(tri[i], tri[(i + 1) % 3])))
            })
    };
    let mut start = vec![0u32; vertices + 1];
    for (_, key) in half_edges() {
        start[(key >> 32) as usize + 1] += 1;
    }
    for v in 0..vertices {
        start[v + 1] += start[v];
    }
    let mut keys = vec![(0u64, 0u32); start[vertices] as usize];
    let mut next = start.clone();
    for (h, key) in half_edges() {
        let slot = &mut next[(key >> 32) as usize];
        keys[*slot as usize] = (key, h);
        *slot += 1;
    }
    for v in 0..vertices {
        keys[start[v] as usize..start[v + 1] as usize].sort_unstable();
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_twins_and_names_the_first_defect() {
        // the unit square cut along its diagonal: one interior edge 0-2
        let square = [[0, 1, 2], [0, 2, 3]];
        let p = pair(&square, 4, |_| true);
        assert_eq!(p.defect, None);
        assert_eq!((p.twins[2], p.twins[3]), (3, 2));
        assert_eq!(p.twins.iter().filter(|&&t| t == NONE).count(), 4);
        let mut sorted = p.keys.clone();
        sorted.sort_unstable();
        assert_eq!(p.keys, sorted);
        // a triangle left out is not paired
        let p = pair(&square, 4, |t| t == 0);
        assert_eq!((p.keys.len(), p.twins[2]), (3, NONE));
        // a flipped copy of a triangle runs its edges the same way
        let p = pair(&[[0, 1, 2], [1, 2, 0]], 3, |_| true);
        assert_eq!(p.defect, Some(PairDefect::SameDirection([0, 5])));
        // three triangles on the edge 0-1
        let fan = [[0, 1, 2], [1, 0, 3], [0, 1, 4]];
        let p = pair(&fan, 5, |_| true);
        assert_eq!(p.defect, Some(PairDefect::Crowded(vec![0, 3, 6])));
        assert_eq!(key_vertices(edge_key(7, 3)), [3, 7]);
    }
}
