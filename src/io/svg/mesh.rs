//! SVG pictures of a [`Mesh`]: [`write_mesh_svg`] (streamed) and [`mesh_svg`] (a string), and
//! the two layers they add to the [`Svg`] builder, [`Svg::triangles`] and [`Svg::segments`].
//!
//! A mesh of up to [`MESH_SVG_DETAIL_TRIANGLES`] triangles is drawn triangle by triangle. A
//! larger one, whose triangles are mostly far below a pixel at the picture's 800 pixels, is
//! drawn merged (see the `merged` module), so that the file has a size bounded by the picture
//! and the board, not by the mesh.

use super::format::num;
use super::{square, Style, Svg, DEFAULT_WIDTH_PX};
use crate::hash::FastMap;
use crate::mesh::{Board, Mesh, SegmentKind};
use core::fmt::Write as _;
use std::collections::BTreeMap;
use std::io::{self, Write};
use std::path::Path;

#[path = "merged.rs"]
mod merged;

/// Meshes of up to this many triangles are drawn triangle by triangle; larger ones merged.
pub const MESH_SVG_DETAIL_TRIANGLES: usize = 50_000;

/// The fill of region 0, the board.
pub(super) const BOARD_FILL: &str = "#f4f1e6";

/// Fills of the components, cycled (the light half of Tableau 20).
const COMPONENT_FILLS: [&str; 10] = [
    "#a0cbe8", "#ffbe7d", "#ff9d9a", "#8cd17d", "#d4a6c8", "#f1ce63", "#86bcb6", "#fabfd2",
    "#d7b5a6", "#b6b0ac",
];

/// The fill colour of region `r`.
pub(super) fn region_fill(r: u32) -> &'static str {
    match r {
        0 => BOARD_FILL,
        i => COMPONENT_FILLS[(i as usize - 1) % COMPONENT_FILLS.len()],
    }
}

/// Segments per `<path>` in [`Svg::segments`]: about 40 kB of path data.
pub(super) const SEGMENTS_PER_PATH: usize = 1024;

fn finite(p: &[f64; 2]) -> bool {
    p[0].is_finite() && p[1].is_finite()
}

impl Svg {
    /// Draws each triangle as a `<polygon>` (in plane coordinates, y up); triangles with a
    /// non-finite coordinate are skipped. A stroke in the fill colour hides the hairline seams
    /// that anti-aliasing leaves between filled neighbours.
    ///
    /// ```
    /// use orthtree::io::svg::{Style, Svg};
    /// use orthtree::Aabb;
    /// let view = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
    /// let svg = Svg::new(view, 100.0)
    ///     .triangles([[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]], &Style::solid().fill("red"))
    ///     .finish();
    /// assert!(svg.contains("<polygon points=\"4,104 104,104 104,4\"/>"));
    /// ```
    pub fn triangles(
        &mut self,
        triangles: impl IntoIterator<Item = [[f64; 2]; 3]>,
        style: &Style,
    ) -> &mut Self {
        self.group(style, |svg| {
            for t in triangles {
                if t.iter().all(finite) {
                    let [a, b, c] = t.map(|p| format!("{},{}", num(svg.x(p[0])), num(svg.y(p[1]))));
                    let _ = writeln!(svg.body, "<polygon points=\"{a} {b} {c}\"/>");
                }
            }
        })
    }

    /// Draws line segments (in plane coordinates, y up) as `<path>`s of up to 1024 segments
    /// each (SVG readers limit the length of an attribute); segments with a non-finite
    /// coordinate are skipped.
    ///
    /// ```
    /// use orthtree::io::svg::{Style, Svg};
    /// use orthtree::Aabb;
    /// let view = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
    /// let svg = Svg::new(view, 100.0)
    ///     .segments([[[0.0, 0.0], [1.0, 1.0]], [[0.0, 1.0], [1.0, 0.0]]], &Style::solid())
    ///     .finish();
    /// assert!(svg.contains("<path d=\"M4 104L104 4M4 4L104 104\"/>"));
    /// ```
    pub fn segments(
        &mut self,
        segments: impl IntoIterator<Item = [[f64; 2]; 2]>,
        style: &Style,
    ) -> &mut Self {
        self.group(style, |svg| {
            let mut d = String::new();
            let mut in_path = 0;
            for [a, b] in segments {
                if finite(&a) && finite(&b) {
                    let _ = write!(
                        d,
                        "M{} {}L{} {}",
                        num(svg.x(a[0])),
                        num(svg.y(a[1])),
                        num(svg.x(b[0])),
                        num(svg.y(b[1]))
                    );
                    in_path += 1;
                    if in_path == SEGMENTS_PER_PATH {
                        let _ = writeln!(svg.body, "<path d=\"{d}\"/>");
                        (d, in_path) = (String::new(), 0);
                    }
                }
            }
            if !d.is_empty() {
                let _ = writeln!(svg.body, "<path d=\"{d}\"/>");
            }
        })
    }
}

/// [`write_mesh_svg`] into a string.
///
/// ```
/// use orthtree::io::svg::mesh_svg;
/// use orthtree::mesh::{Board, Mesh, Segment, SegmentKind};
/// let board = Board::new(1, vec![]).unwrap();
/// let mesh = Mesh {
///     vertices: vec![[0, 0], [1, 0], [1, 1], [0, 1]],
///     triangles: vec![[0, 1, 2], [0, 2, 3], [0, 2, 9]], // the last one is skipped
///     regions: vec![0, 0],
///     segments: vec![Segment { vertices: [0, 1], kind: SegmentKind::Boundary }],
/// };
/// let svg = mesh_svg(&mesh, &board);
/// assert_eq!(svg.matches("<polygon").count(), 2);
/// ```
pub fn mesh_svg(mesh: &Mesh, board: &Board) -> String {
    let mut out = Vec::new();
    write_mesh_svg(mesh, board, &mut out).expect("writing to a Vec does not fail");
    String::from_utf8(out).expect("the picture is ASCII")
}

/// [`write_mesh_svg`] to a file, through a buffer.
///
/// # Errors
/// The writer's (or the file's) I/O error.
pub fn write_mesh_svg_to(mesh: &Mesh, board: &Board, path: impl AsRef<Path>) -> io::Result<()> {
    crate::io::write_file(path, |out| write_mesh_svg(mesh, board, out))
}

/// Draws a mesh on its board to `out`, [`DEFAULT_WIDTH_PX`] wide on a white background.
///
/// Up to [`MESH_SVG_DETAIL_TRIANGLES`] triangles: the triangles
/// filled by region (the board light, each component its own colour, one `<g>` per region), every
/// mesh edge once as a thin grey line, the component outlines (the mesh's `Component` segments)
/// thick, and the board's outline. Line widths shrink on big boards (below 4 pixels per unit)
/// so that the finest cells stay visible. Triangles and segments with an index out of range are
/// skipped, so a malformed mesh still gives a picture.
///
/// More triangles: the regions filled from the board (the board light, each component's outline
/// filled in its colour: the regions of a valid mesh), the parts where triangles are smaller than
/// 4 pixels shaded grey (one path of pixel runs), every mesh edge of 4 pixels or more once as a
/// thin grey line (one group per power-of-two length), then the component outlines and the
/// board's outline. The file is then at most a few MB whatever the mesh, and is written in one
/// pass over the triangles with a bitmap of the picture's pixels.
///
/// # Errors
///
/// Only those of `out`.
///
/// # Complexity
///
/// O(T) time for T triangles; O(T) memory up to [`MESH_SVG_DETAIL_TRIANGLES`], above that O(1)
/// beyond the picture's bitmap (under 1 MB).
pub fn write_mesh_svg(mesh: &Mesh, board: &Board, out: &mut impl Write) -> io::Result<()> {
    if mesh.triangles.len() > MESH_SVG_DETAIL_TRIANGLES {
        return merged::write(mesh, board, out);
    }
    detailed(mesh, board).write(out)
}

/// The picture of a small mesh, triangle by triangle.
fn detailed(mesh: &Mesh, board: &Board) -> Svg {
    let u = board.size() as f64;
    let view = square(u);
    let mut svg = Svg::new(view, DEFAULT_WIDTH_PX);
    svg.margin(6.0).background("white");
    let point = |v: u32| mesh.vertices.get(v as usize).map(|p| p.map(|c| c as f64));
    let corners = |t: &[u32; 3]| -> Option<[[f64; 2]; 3]> {
        Some([point(t[0])?, point(t[1])?, point(t[2])?])
    };

    let mut by_region: BTreeMap<u32, Vec<[[f64; 2]; 3]>> = BTreeMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if let Some(c) = corners(tri) {
            let r = mesh.regions.get(t).copied().unwrap_or(0);
            by_region.entry(r).or_default().push(c);
        }
    }
    for (r, triangles) in by_region {
        let fill = region_fill(r);
        let style = Style::solid().fill(fill).stroke(fill).stroke_width(0.6);
        svg.triangles(triangles, &style);
    }

    let mut seen: FastMap<(u32, u32), ()> = FastMap::default();
    let mut edges = Vec::new();
    for tri in &mesh.triangles {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            if seen.insert((a.min(b), a.max(b)), ()).is_none()
                && let (Some(p), Some(q)) = (point(a), point(b))
            {
                edges.push([p, q]);
            }
        }
    }
    let (edge_px, outline_px) = line_widths(u);
    svg.segments(
        edges,
        &Style::solid().stroke("#6b6b6b").stroke_width(edge_px),
    );

    let outlines = (mesh.segments.iter())
        .filter(|s| matches!(s.kind, SegmentKind::Component(_)))
        .filter_map(|s| Some([point(s.vertices[0])?, point(s.vertices[1])?]));
    svg.segments(
        outlines,
        &Style::solid().stroke("#1a1a1a").stroke_width(outline_px),
    );
    svg.boxes([view], &Style::solid().stroke("#1a1a1a").stroke_width(1.5));
    svg
}

/// The widths of mesh edges and of component outlines on a board of side `u`: they shrink with
/// the grid on big boards, so unit cells stay visible.
fn line_widths(u: f64) -> (f64, f64) {
    let unit_px = DEFAULT_WIDTH_PX / u.max(1.0);
    let edge_px = (unit_px * 0.25).clamp(0.15, 0.5);
    let outline_px = (unit_px * 0.6).clamp(0.8, 2.2);
    (edge_px, outline_px)
}
