//! The picture of a large mesh (more than [`MESH_SVG_DETAIL_TRIANGLES`] triangles), streamed in
//! one pass with a file size bounded by the picture and the board: region fills from the board's
//! outlines, the fine parts shaded by how much of each pixel their edges cover, only the mesh edges of at least
//! [`MIN_EDGE_PX`] pixels drawn (see [`write_mesh_svg`]).
//!
//! [`MESH_SVG_DETAIL_TRIANGLES`]: super::MESH_SVG_DETAIL_TRIANGLES
//! [`write_mesh_svg`]: super::write_mesh_svg

use super::super::format::{clamp_px, escape};
use super::super::{square, Style, Svg, DEFAULT_WIDTH_PX};
use super::{line_widths, region_fill, BOARD_FILL, SEGMENTS_PER_PATH};
use crate::geom::Aabb;
use crate::io::text_out::TextOut;
use crate::mesh::{Board, Mesh};
use std::io::{self, Write};

/// Mesh edges shorter than this many pixels are not drawn; the parts of the picture they fill
/// are shaded instead.
pub const MIN_EDGE_PX: f64 = 4.0;

/// The grey of the mesh edges, also the shade of the fine parts (at half opacity).
const EDGE_GREY: &str = "#6b6b6b";

/// Shades of the fine parts: pixels are drawn at one of this many opacities.
const SHADES: usize = 8;

/// How much of each pixel of the picture (margins included) the short mesh edges cover, as a
/// renderer would stroke them: their length in pixels times the stroke width.
struct Coverage {
    width: usize,
    height: usize,
    cover: Vec<f32>,
}

impl Coverage {
    fn new(width: usize, height: usize) -> Self {
        Coverage {
            width,
            height,
            cover: vec![0.0; width * height],
        }
    }

    /// Adds `amount` at the pixel holding `(x, y)` (pixel coordinates, clipped).
    #[inline]
    fn add(&mut self, x: f64, y: f64, amount: f64) {
        let clip = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
        let k = clip(y, self.height) * self.width + clip(x, self.width);
        self.cover[k] += amount as f32;
    }

    /// The shade of each pixel, row by row: 0 for none, else 1 to [`SHADES`].
    fn shades(&self) -> Vec<u8> {
        let shade = |&cover: &f32| {
            // Overlapping hairlines composite, they do not add up: 1 - e^-sum.
            let c = 1.0 - (-cover).exp();
            (c * SHADES as f32).ceil().min(SHADES as f32) as u8
        };
        self.cover.iter().map(shade).collect()
    }
}

/// Appends a pixel coordinate as [`num`](super::super::format::num) writes it.
#[inline]
fn px<W: Write + ?Sized>(o: &mut TextOut<'_, W>, x: f64) {
    o.f3(clamp_px(x));
}

/// Appends the pixel column and row of the plane point `p`, as `x y`.
fn xy<W: Write + ?Sized>(o: &mut TextOut<'_, W>, svg: &Svg, p: [f64; 2]) {
    px(o, svg.x(p[0]));
    o.sp();
    px(o, svg.y(p[1]));
}

/// Opens a `<g>` with `style`'s attributes.
fn open_group<W: Write + ?Sized>(o: &mut TextOut<'_, W>, style: &Style) -> io::Result<()> {
    o.s("<g").s(&style.attributes()).s(">").nl()
}

/// Writes the picture (see [`write_mesh_svg`](super::write_mesh_svg)).
pub(super) fn write(mesh: &Mesh, board: &Board, out: &mut impl Write) -> io::Result<()> {
    let u = board.size() as f64;
    let view = square(u);
    let mut svg = Svg::new(view, DEFAULT_WIDTH_PX);
    svg.margin(6.0);
    let (w, h) = svg.size_px();
    let mut o = TextOut::new(out);
    o.s(&svg.header());
    o.s("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>")
        .nl()?;

    write_regions(&mut o, &svg, board, &view)?;

    let (edge_px, outline_px) = line_widths(u);
    let mut coverage = Coverage::new(w.ceil() as usize + 1, h.ceil() as usize + 1);
    let long = edge_pass(mesh, &svg, &mut coverage, edge_px);
    write_shades(&mut o, &shade_runs(&coverage.shades(), coverage.width))?;

    write_long_edges(&mut o, &svg, &long, edge_px)?;

    // Component outlines, then the board's.
    open_group(
        &mut o,
        &Style::solid().stroke("#1a1a1a").stroke_width(outline_px),
    )?;
    for c in board.components() {
        write_ring(&mut o, &svg, &c.outline, "")?;
    }
    o.s("</g>").nl()?;
    open_group(&mut o, &Style::solid().stroke("#1a1a1a").stroke_width(1.5))?;
    o.s(&svg.rect_line(&view)).spill()?;
    o.s("</g>").nl()?;
    o.s("</svg>").nl()?;
    o.finish()
}

/// The regions: the board, then each component's outline filled.
fn write_regions<W: Write + ?Sized>(
    o: &mut TextOut<'_, W>,
    svg: &Svg,
    board: &Board,
    view: &Aabb<f64, 2>,
) -> io::Result<()> {
    open_group(o, &Style::solid().stroke("none").fill(BOARD_FILL))?;
    o.s(&svg.rect_line(view)).spill()?;
    o.s("</g>").nl()?;
    for (i, c) in board.components().iter().enumerate() {
        let fill = format!(" fill=\"{}\"", escape(region_fill(i as u32 + 1)));
        write_ring(o, svg, &c.outline, &fill)?;
    }

    Ok(())
}

/// The long edges, one group per level.
fn write_long_edges<W: Write + ?Sized>(
    o: &mut TextOut<'_, W>,
    svg: &Svg,
    long: &Levels,
    edge_px: f64,
) -> io::Result<()> {
    let edge_style = Style::solid().stroke(EDGE_GREY).stroke_width(edge_px);
    for edges in long.iter().filter(|e| !e.is_empty()) {
        open_group(o, &edge_style)?;
        for chunk in edges.chunks(SEGMENTS_PER_PATH) {
            o.s("<path d=\"");
            for [p, q] in chunk {
                o.s("M");
                xy(o, svg, *p);
                o.s("L");
                xy(o, svg, *q);
            }
            o.s("\"/>").nl()?;
        }
        o.s("</g>").nl()?;
    }

    Ok(())
}

/// Long edges of one level: level k holds the edges of 2^k * [`MIN_EDGE_PX`] to
/// 2^(k + 1) * [`MIN_EDGE_PX`] pixels, as pairs of points in plane coordinates.
type Levels = Vec<Vec<[[f64; 2]; 2]>>;

/// One pass over the triangles: short edges added to the coverage, long ones kept by level.
fn edge_pass(mesh: &Mesh, svg: &Svg, coverage: &mut Coverage, edge_px: f64) -> Levels {
    let scale = svg.scale();
    let point = |v: u32| mesh.vertices.get(v as usize).map(|p| p.map(|c| c as f64));
    let mut long: Levels = vec![Vec::new(); 32];
    for tri in &mesh.triangles {
        let (Some(p0), Some(p1), Some(p2)) = (point(tri[0]), point(tri[1]), point(tri[2])) else {
            continue;
        };
        let c = [p0, p1, p2];
        let lengths = [0, 1, 2].map(|i| {
            let (p, q) = (c[i], c[(i + 1) % 3]);
            (p[0] - q[0]).abs().max((p[1] - q[1]).abs()) * scale
        });
        if lengths.iter().all(|&l| l < MIN_EDGE_PX) {
            // A small triangle (most of a large mesh): its three half-edges' ink lands within
            // a few pixels, so it is added once, at the centroid.
            let x = svg.x_at_scale((p0[0] + p1[0] + p2[0]) / 3.0, scale);
            let y = svg.y_at_scale((p0[1] + p1[1] + p2[1]) / 3.0, scale);
            coverage.add(x, y, 0.5 * (lengths[0] + lengths[1] + lengths[2]) * edge_px);
            continue;
        }
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            let (p, q) = (c[i], c[(i + 1) % 3]);
            let length = lengths[i];
            if length < MIN_EDGE_PX {
                // Half from each of the (at most) two triangles holding the edge.
                let x = svg.x_at_scale((p[0] + q[0]) / 2.0, scale);
                let y = svg.y_at_scale((p[1] + q[1]) / 2.0, scale);
                coverage.add(x, y, 0.5 * length * edge_px);
            } else if a < b {
                // Each interior edge is in two triangles, once each way: draw it from one.
                // Board-boundary edges (one way only) are under the board's outline.
                let level = (length / MIN_EDGE_PX).log2().floor().clamp(0.0, 31.0);
                long[level as usize].push([p, q]);
            }
        }
    }
    long
}

/// A run of pixels of one shade: first column, row, length.
type Run = (u32, u32, u32);

/// The runs of pixels of each shade (1 to [`SHADES`], at index shade - 1), row by row, of a
/// picture `width` pixels wide, in one pass.
fn shade_runs(shades: &[u8], width: usize) -> Vec<Vec<Run>> {
    let mut runs = vec![Vec::new(); SHADES];
    for (y, row) in shades.chunks(width.max(1)).enumerate() {
        let mut x = 0;
        while x < row.len() {
            let shade = row[x];
            let start = x;
            while x < row.len() && row[x] == shade {
                x += 1;
            }
            if shade > 0 {
                runs[usize::from(shade) - 1].push((start as u32, y as u32, (x - start) as u32));
            }
        }
    }
    runs
}

/// The fine parts: one group per shade, its runs of pixels as paths of up to
/// [`SEGMENTS_PER_PATH`] rectangles.
fn write_shades<W: Write + ?Sized>(o: &mut TextOut<'_, W>, runs: &[Vec<Run>]) -> io::Result<()> {
    for (k, runs) in runs.iter().enumerate() {
        let opacity = (k + 1) as f64 / SHADES as f64;
        o.s("<g fill=\"").s(EDGE_GREY).s("\" fill-opacity=\"");
        px(o, opacity);
        o.s("\" stroke=\"none\">").nl()?;
        for chunk in runs.chunks(SEGMENTS_PER_PATH) {
            o.s("<path d=\"");
            for &(x, y, len) in chunk {
                let len = u64::from(len);
                o.s("M").u(x.into()).sp().u(y.into()).s("h").u(len);
                o.s("v1h-").u(len).s("z");
            }
            o.s("\"/>").nl()?;
        }
        o.s("</g>").nl()?;
    }
    Ok(())
}

/// A closed polygon as a `<path>` with the attributes `attributes` (each after a space) and its
/// data `M x y L x y ... Z`, in pixels.
fn write_ring<W: Write + ?Sized>(
    o: &mut TextOut<'_, W>,
    svg: &Svg,
    ring: &[[i64; 2]],
    attributes: &str,
) -> io::Result<()> {
    o.s("<path").s(attributes).s(" d=\"");
    for (k, p) in ring.iter().enumerate() {
        o.s(if k == 0 { "M" } else { "L" });
        xy(o, svg, p.map(|c| c as f64));
        o.spill()?;
    }
    o.s("Z\"/>").nl()
}
