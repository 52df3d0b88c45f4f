//! SVG pictures of a [`Mesh`]: [`mesh_svg`], and the two layers it adds to the [`Svg`] builder,
//! [`Svg::triangles`] and [`Svg::segments`].

use super::format::num;
use super::{Style, Svg, DEFAULT_WIDTH_PX};
use crate::geom::Aabb;
use crate::hash::FastMap;
use crate::mesh::{Board, Mesh, SegmentKind};
use core::fmt::Write as _;
use std::collections::BTreeMap;

/// The fill of region 0, the board.
const BOARD_FILL: &str = "#f4f1e6";

/// Fills of the components, cycled (the light half of Tableau 20).
const COMPONENT_FILLS: [&str; 10] = [
    "#a0cbe8", "#ffbe7d", "#ff9d9a", "#8cd17d", "#d4a6c8", "#f1ce63", "#86bcb6", "#fabfd2",
    "#d7b5a6", "#b6b0ac",
];

/// The fill colour of region `r`.
fn region_fill(r: u32) -> &'static str {
    match r {
        0 => BOARD_FILL,
        i => COMPONENT_FILLS[(i as usize - 1) % COMPONENT_FILLS.len()],
    }
}

/// Segments per `<path>` in [`Svg::segments`]: about 40 kB of path data.
const SEGMENTS_PER_PATH: usize = 1024;

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
        self.open_group(style);
        for t in triangles {
            if t.iter().all(finite) {
                let [a, b, c] = t.map(|p| format!("{},{}", num(self.x(p[0])), num(self.y(p[1]))));
                let _ = writeln!(self.body, "<polygon points=\"{a} {b} {c}\"/>");
            }
        }
        self.close_group();
        self
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
        self.open_group(style);
        let mut d = String::new();
        let mut in_path = 0;
        for [a, b] in segments {
            if finite(&a) && finite(&b) {
                let _ = write!(
                    d,
                    "M{} {}L{} {}",
                    num(self.x(a[0])),
                    num(self.y(a[1])),
                    num(self.x(b[0])),
                    num(self.y(b[1]))
                );
                in_path += 1;
                if in_path == SEGMENTS_PER_PATH {
                    let _ = writeln!(self.body, "<path d=\"{d}\"/>");
                    (d, in_path) = (String::new(), 0);
                }
            }
        }
        if !d.is_empty() {
            let _ = writeln!(self.body, "<path d=\"{d}\"/>");
        }
        self.close_group();
        self
    }
}

/// Draws a mesh on its board, [`DEFAULT_WIDTH_PX`] wide on a white background: the triangles
/// filled by region (the board light, each component its own colour, one `<g>` per region), every
/// mesh edge once as a thin grey line, the component outlines (the mesh's `Component` segments)
/// thick, and the board's outline. Line widths shrink on big boards (below 4 pixels per unit)
/// so that the finest cells stay visible. Triangles and segments with an index out of range are
/// skipped, so a malformed mesh still gives a picture.
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
    let u = board.size() as f64;
    let view = Aabb {
        min: [0.0; 2],
        max: [u; 2],
    };
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
            if seen.insert((a.min(b), a.max(b)), ()).is_none() {
                if let (Some(p), Some(q)) = (point(a), point(b)) {
                    edges.push([p, q]);
                }
            }
        }
    }
    // Line widths shrink with the grid on big boards, so unit cells stay visible.
    let unit_px = DEFAULT_WIDTH_PX / u.max(1.0);
    let edge_px = (unit_px * 0.25).clamp(0.15, 0.5);
    let outline_px = (unit_px * 0.6).clamp(0.8, 2.2);
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
    svg.finish()
}
