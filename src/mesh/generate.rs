//! The mesher's driver and its step 3: the chapter's GENERATEMESH (section 14.3, Theorem 14.5),
//! with the options of [`MeshOptions`](super::MeshOptions) on top:
//!
//! 0. Divide every coordinate by the grid unit (the board scaled down; the mesh is scaled back up
//!    at the end), so a board scaled by 2^k meshes to the same triangles, scaled.
//! 1. Build a quadtree on the board's cells ([`refine`](super::refine)): the chapter splits a
//!    cell while it is larger than unit size and its closed square meets a closed component
//!    edge; the options change which cells are split, never what a leaf looks like to step 3.
//! 2. 2:1 balance with face connectivity, in the shared [`Tree::balance`]; then, where a component
//!    vertex is the midpoint of a leaf's side, the leaf across is split (and the tree balanced
//!    again) so that the midpoint is a mesh vertex (never needed in the chapter's mode).
//! 3. Triangulate each leaf: a leaf cut along its diagonal by a component edge and with only its
//!    four corners on its boundary is cut along that diagonal; any other leaf with only corners
//!    is cut along one diagonal; otherwise a Steiner point at its centre is joined to every
//!    vertex on its boundary (its corners and the midpoints of sides next to smaller leaves;
//!    balance allows at most one per side), which also makes both halves of a diagonal out of
//!    mesh edges. Every triangle has angles 45, 45 and 90 degrees, and every vertex is a grid
//!    point (a Steiner point is the centre of a leaf of side two units or more).
//! 4. Regions ([`labels`](super::labels)), from the outlines walked leaf by leaf
//!    ([`outline`](super::outline)), before step 3 so that each triangle gets its region as it
//!    is made.

use super::budget;
use super::labels::{half_touching, label_pieces, Labels};
use super::outline::{trace_outlines, Outlines, RISING};
use super::refine::{build_quadtree, input_edges, provide_midpoints, SplitRule};
use super::vertices::{Grid, Numbering};
use super::{Board, BoardError, Mesh, MeshOptions, OptionsError, Segment, SegmentKind};
use crate::geom::{Cell, Connectivity};
use crate::tree::Tree;
use std::time::{Duration, Instant};

/// What [`generate_mesh`] and [`MeshOptions::generate`] produced, with counts and times of its
/// phases.
#[derive(Clone, Debug)]
pub struct MeshOutcome {
    /// The mesh, in board coordinates.
    pub mesh: Mesh,
    /// The quadtree after balance; its root is the board, its cells of level `log2(U / unit)` are
    /// grid units.
    pub tree: Tree<2>,
    /// The grid unit the board was meshed in (see [`MeshOptions::grid_unit`]).
    pub grid_unit: i64,
    /// Leaves before balance.
    pub leaves_before_balance: usize,
    /// Time to build the quadtree.
    pub build_time: Duration,
    /// Time to balance it (with the splits that provide midpoints).
    pub balance_time: Duration,
    /// Time to triangulate the leaves and label regions.
    pub triangulate_time: Duration,
}

/// Meshes a board with the chapter's algorithm, exactly (see the module doc): grid unit 1, cells
/// meeting a component edge split down to unit size. The same as
/// `MeshOptions::new().grid_unit(1).generate(board)`; [`MeshOptions`] has the other settings.
///
/// # Errors
/// [`BoardError::TooManyTriangles`] when the mesh would have more than
/// [`DEFAULT_MAX_TRIANGLES`](super::DEFAULT_MAX_TRIANGLES) triangles (see
/// [`MeshOptions::max_triangles`]); nothing else for a validated [`Board`].
///
/// # Complexity
/// O(p(S) log U) triangles, built in O(p(S) log^2 U) (Theorem 14.5).
///
/// ```
/// use orthtree::mesh::{generate_mesh, Board, Component};
/// // the chapter's Figure 14.2: U = 16, a unit square at distance 1 from the left and top sides
/// let board = Board::new(16, vec![Component::new(vec![[1, 14], [2, 14], [2, 15], [1, 15]])]).unwrap();
/// let out = generate_mesh(&board).unwrap();
/// let area2: i64 = out.mesh.triangles.iter().map(|t| {
///     let [a, b, c] = t.map(|v| out.mesh.vertices[v as usize]);
///     (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
/// }).sum();
/// assert_eq!(area2, 2 * 16 * 16);
/// assert_eq!(out.mesh.regions.iter().filter(|&&r| r == 1).count(), 2);
/// ```
pub fn generate_mesh(board: &Board) -> Result<MeshOutcome, BoardError> {
    match MeshOptions::new().grid_unit(1).generate(board) {
        Ok(outcome) => Ok(outcome),
        Err(OptionsError::TooManyTriangles(e)) => Err(BoardError::TooManyTriangles(e)),
        Err(e) => unreachable!("unit 1 and the chapter's sizes suit every board: {e}"),
    }
}

/// Meshes `board` in grid units of `unit` with the split rule `rule` (in those units), refusing
/// a mesh of more than `max_triangles` triangles (see the `budget` module).
pub(super) fn generate(
    board: &Board,
    unit: i64,
    rule: SplitRule,
    max_triangles: u64,
) -> Result<MeshOutcome, OptionsError> {
    let start = Instant::now();
    let reduced;
    let board = if unit == 1 {
        board
    } else {
        reduced = board.scaled_down(unit);
        &reduced
    };
    budget::check(
        budget::lower_bound(board, rule.near, rule.max),
        max_triangles,
    )?;
    let edges = input_edges(board);
    let mut tree = build_quadtree(board.size(), &edges, &rule, max_triangles)?;
    let build_time = start.elapsed();
    let leaves_before_balance = tree.leaf_count();

    let start = Instant::now();
    tree.balance(Connectivity::Face);
    provide_midpoints(&mut tree, board.size(), &edges);
    let balance_time = start.elapsed();
    budget::check(2 * tree.leaf_count() as u64, max_triangles)?;

    let start = Instant::now();
    let mut cells = vec![Cell::<2>::root(); tree.node_count()];
    for (id, cell) in tree.pre_order() {
        cells[id.index()] = cell;
    }
    let grid = Grid {
        tree: &tree,
        cells: &cells,
        size: board.size(),
    };
    let numbering = Numbering::new(grid);
    budget::check(numbering.triangle_count(), max_triangles)?;
    let mut segments = Vec::new();
    let outlines = trace_outlines(&grid, &numbering, &edges, &mut segments);
    let labels = label_pieces(&grid, &outlines);
    let mut mesh = triangulate(&grid, numbering, &outlines, &labels, segments);
    if unit != 1 {
        for p in &mut mesh.vertices {
            *p = p.map(|c| c * unit);
        }
    }
    let triangulate_time = start.elapsed();
    Ok(MeshOutcome {
        mesh,
        tree,
        grid_unit: unit,
        leaves_before_balance,
        build_time,
        balance_time,
        triangulate_time,
    })
}

/// Step 3: triangles of every leaf with their regions; the board-boundary segments are added to
/// the outline segments `outline`.
fn triangulate(
    grid: &Grid,
    numbering: Numbering,
    outlines: &Outlines,
    labels: &Labels,
    outline: Vec<Segment>,
) -> Mesh {
    let (tree, u) = (grid.tree, grid.size);
    let mut triangles = Vec::with_capacity(tree.leaf_count() * 3);
    let mut regions = Vec::with_capacity(tree.leaf_count() * 3);
    let mut segments = Vec::with_capacity(outline.len() + 8);
    let mut ring = Vec::with_capacity(8);
    for (leaf, cell) in tree.leaves() {
        let (x, y, s) = super::refine::square(&cell, u);
        let vx = numbering.leaf(leaf);
        let ids = vx.corners;
        // Sides on the board's boundary (south, east, north, west): one mesh edge each, since
        // no smaller leaf lies beyond them.
        for (k, on_boundary) in [y == 0, x + s == u, y + s == u, x == 0]
            .into_iter()
            .enumerate()
        {
            if on_boundary {
                let vertices = [ids[k], ids[(k + 1) % 4]];
                segments.push(Segment {
                    vertices,
                    kind: SegmentKind::Boundary,
                });
            }
        }
        let diagonal = outlines.diagonal[leaf.index()];
        let pieces = labels.of(leaf);
        let Some(centre) = vx.centre else {
            // Half 0 first: the SE half of a rising diagonal, the SW half of a falling one.
            if diagonal == 0 || diagonal == RISING {
                triangles.extend([[ids[0], ids[1], ids[2]], [ids[0], ids[2], ids[3]]]);
            } else {
                triangles.extend([[ids[0], ids[1], ids[3]], [ids[1], ids[2], ids[3]]]);
            }
            regions.extend(if diagonal == 0 {
                [pieces[0]; 2]
            } else {
                pieces
            });
            continue;
        };
        ring.clear();
        for (k, (&corner, &mid)) in ids.iter().zip(&vx.mids).enumerate() {
            ring.push((corner, k));
            ring.extend(mid.map(|m| (m, k)));
        }
        for k in 0..ring.len() {
            let ((a, side), (b, _)) = (ring[k], ring[(k + 1) % ring.len()]);
            triangles.push([centre, a, b]);
            regions.push(match diagonal {
                0 => pieces[0],
                d => pieces[half_touching(d == RISING, side)],
            });
        }
    }
    segments.extend(outline);
    Mesh {
        vertices: numbering.coords,
        triangles,
        regions,
        segments,
    }
}
