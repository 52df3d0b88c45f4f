//! SVG pictures of 2D trees, written as plain strings (no dependencies).
//!
//! [`Svg`] is a small builder: a view (the part of the plane shown) and a width in pixels, then
//! layers drawn in the order they are added: leaf cells ([`Svg::cells`]), the subdivision drawn
//! line by line ([`Svg::subdivision`], for dashed or dotted styles), the lines a refinement adds
//! ([`Svg::refinement`]), boxes and points, each with a [`Style`]. The y axis points up (north
//! up, as in the chapter's figures): the view's `max[1]` is the top edge of the picture.
//! [`point_tree_svg`] draws a [`PointTree`] the way the chapter's Figure 14.5 does: the lines
//! balance adds dotted, the tree itself solid, the points as dots. [`mesh_svg`] draws a mesh
//! on its board with the layers [`Svg::triangles`] and [`Svg::segments`].
//!
//! Nothing here panics on odd input: a view of zero or non-finite size, a non-positive width, or
//! NaN coordinates are all mapped to something drawable (see [`Svg::new`]), and colours are
//! escaped.

mod format;
mod image;
mod mesh;
mod style;
#[cfg(test)]
mod tests;

use format::{clamp_px, escape, length, num, repair_view, MAX_PX};
pub use image::{image_tree_svg, write_image_tree_svg};
pub use mesh::{mesh_svg, write_mesh_svg, write_mesh_svg_to, MESH_SVG_DETAIL_TRIANGLES};
pub use style::Style;

use crate::geom::RootGeometry;
use crate::geom::{Aabb, Cell, Scalar};
use crate::points::PointTree;
use crate::tree::Tree;
use core::fmt::Write as _;
use std::borrow::Borrow;

/// The width in pixels used by [`point_tree_svg`] and when [`Svg::new`] gets an unusable width.
pub const DEFAULT_WIDTH_PX: f64 = 800.0;

/// The margin in pixels around the view unless [`Svg::margin`] sets another.
pub const DEFAULT_MARGIN_PX: f64 = 4.0;

/// A picture under construction: a view of the plane mapped to pixels (y up), and the layers
/// drawn so far. Layers are drawn in the order they are added, later ones on top.
///
/// ```
/// use orthtree::io::svg::{Style, Svg};
/// use orthtree::Quadtree;
/// let pts = [([0.1, 0.1], ()), ([0.2, 0.15], ()), ([0.8, 0.9], ())];
/// let t = Quadtree::builder().bucket_size(1).build(&pts).unwrap();
/// let svg = Svg::new(t.geometry().root_box(), 400.0)
///     .cells(t.tree(), t.geometry(), &Style::solid())
///     .points(t.points(), &Style::points())
///     .finish();
/// assert!(svg.starts_with("<svg"));
/// assert_eq!(svg.matches("<rect").count(), t.leaf_count()); // one per leaf
/// assert_eq!(svg.matches("<circle").count(), 3);
/// assert!(svg.trim_end().ends_with("</svg>"));
/// ```
#[derive(Clone, Debug)]
pub struct Svg {
    view: Aabb<f64, 2>,
    width: f64,
    margin: f64,
    body: String,
}

impl Svg {
    /// A picture of `view`, `width_px` pixels wide (plus the margin on each side) and as high
    /// as the view's aspect ratio asks.
    ///
    /// Odd input is repaired, never refused: a view with a non-finite coordinate becomes the unit
    /// square; `min > max` on an axis is swapped; an axis of zero extent gets the other axis's
    /// extent (a unit extent when both are zero), centred on the given coordinate; a width that
    /// is not a positive finite number becomes [`DEFAULT_WIDTH_PX`].
    ///
    /// ```
    /// use orthtree::io::svg::Svg;
    /// use orthtree::Aabb;
    /// let flat = Aabb { min: [0.0, 2.0], max: [4.0, 2.0] };
    /// let svg = Svg::new(flat, 100.0).finish();
    /// assert!(svg.contains("width=\"108\" height=\"108\"")); // a square, with the margin
    /// ```
    pub fn new(view: Aabb<f64, 2>, width_px: f64) -> Self {
        Svg {
            view: repair_view(view),
            // Checked as the other lengths are: the default unless finite and positive.
            width: Some(width_px)
                .filter(|&w| length(w) > 0.0)
                .unwrap_or(DEFAULT_WIDTH_PX),
            margin: DEFAULT_MARGIN_PX,
            body: String::new(),
        }
    }

    /// Sets the margin in pixels left around the view on every side (so that strokes and dots on
    /// its edge are not clipped); negative or non-finite values count as 0.
    pub fn margin(&mut self, margin_px: f64) -> &mut Self {
        self.margin = length(margin_px);
        self
    }

    /// The view shown, after the repairs of [`Svg::new`].
    pub fn view(&self) -> Aabb<f64, 2> {
        self.view
    }

    /// The size of the whole picture in pixels, margins included: (width, height).
    pub fn size_px(&self) -> (f64, f64) {
        let height = (self.view.max[1] * 0.5 - self.view.min[1] * 0.5) * self.scale() * 2.0;
        (
            self.width + 2.0 * self.margin,
            height.min(MAX_PX) + 2.0 * self.margin,
        )
    }

    /// Fills the whole picture (margins included) with `colour`, under everything added later.
    pub fn background(&mut self, colour: &str) -> &mut Self {
        let _ = writeln!(
            self.body,
            "<rect width=\"100%\" height=\"100%\" fill=\"{}\"/>",
            escape(colour)
        );
        self
    }

    /// Draws the outline (and fill) of every leaf cell of `tree` as one `<rect>` each. Edges
    /// shared by two leaves are stroked twice, which is invisible for solid lines; for dashed
    /// or dotted styles [`Svg::subdivision`] is cleaner.
    pub fn cells(
        &mut self,
        tree: &Tree<2>,
        geometry: &RootGeometry<2>,
        style: &Style,
    ) -> &mut Self {
        self.boxes(tree.leaves().map(|(_, c)| geometry.cell_box(&c)), style)
    }

    /// Draws the lines of the subdivision of `tree`, each segment once: the root cell's outline
    /// and, for every internal node, the two lines that split its cell. The same lines as
    /// [`Svg::cells`] (without fill), but a dash pattern runs evenly along each line.
    pub fn subdivision(
        &mut self,
        tree: &Tree<2>,
        geometry: &RootGeometry<2>,
        style: &Style,
    ) -> &mut Self {
        self.group(style, |svg| {
            svg.body.push_str(&svg.rect_line(&geometry.root_box()));
            for (_, cell) in tree.pre_order().filter(|(id, _)| !tree.is_leaf(*id)) {
                svg.cross(geometry, &cell);
            }
        })
    }

    /// Draws only the lines that `refined` adds to `base` (both over `geometry`): for every
    /// internal node of `refined` whose cell is not split in `base`, the two lines that split
    /// it. With `refined` a balanced clone of `base`, this is the dotted part of the chapter's
    /// Figure 14.5, and nothing is stroked twice.
    pub fn refinement(
        &mut self,
        base: &Tree<2>,
        refined: &Tree<2>,
        geometry: &RootGeometry<2>,
        style: &Style,
    ) -> &mut Self {
        self.group(style, |svg| {
            for (_, cell) in refined.pre_order().filter(|(id, _)| !refined.is_leaf(*id)) {
                let there = base.locate_cell(&cell);
                if base.level(there) != cell.level() || base.is_leaf(there) {
                    svg.cross(geometry, &cell);
                }
            }
        })
    }

    /// Draws one `<rect>` per box; boxes with a non-finite coordinate are skipped.
    pub fn boxes<B: Borrow<Aabb<f64, 2>>>(
        &mut self,
        boxes: impl IntoIterator<Item = B>,
        style: &Style,
    ) -> &mut Self {
        self.group(style, |svg| {
            for b in boxes {
                let b = b.borrow();
                if b.min.iter().chain(&b.max).all(|v| v.is_finite()) {
                    svg.body.push_str(&svg.rect_line(b));
                }
            }
        })
    }

    /// Draws a dot of radius `style.point_radius` at every point (owned or borrowed, any
    /// [`Scalar`]); points with a non-finite coordinate are skipped.
    pub fn points<S: Scalar, P: Borrow<[S; 2]>>(
        &mut self,
        points: impl IntoIterator<Item = P>,
        style: &Style,
    ) -> &mut Self {
        let r = num(length(style.point_radius));
        self.group(style, |svg| {
            for p in points {
                let [x, y] = p.borrow().map(Scalar::to_f64);
                if x.is_finite() && y.is_finite() {
                    let _ = writeln!(
                        svg.body,
                        "<circle cx=\"{}\" cy=\"{}\" r=\"{r}\"/>",
                        num(svg.x(x)),
                        num(svg.y(y))
                    );
                }
            }
        })
    }

    /// The SVG document.
    pub fn finish(&self) -> String {
        format!("{}{}</svg>\n", self.header(), self.body)
    }

    /// Writes [`Svg::finish`] to `out`, without building the document in one string.
    ///
    /// # Errors
    /// The writer's (or the file's) I/O error.
    pub fn write(&self, out: &mut impl std::io::Write) -> std::io::Result<()> {
        out.write_all(self.header().as_bytes())?;
        out.write_all(self.body.as_bytes())?;
        out.write_all(b"</svg>\n")
    }

    /// Writes [`Svg::finish`] to a file, through a buffer.
    ///
    /// # Errors
    /// The writer's (or the file's) I/O error.
    pub fn write_to(&self, path: impl AsRef<std::path::Path>) -> std::io::Result<()> {
        crate::io::write_file(path, |out| self.write(out))
    }

    /// The opening `<svg>` tag, with its line break.
    fn header(&self) -> String {
        let (w, h) = self.size_px();
        let (w, h) = (num(w), num(h));
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\">\n"
        )
    }

    /// Pixels per unit of the plane. Halved differences keep the extent finite for any finite
    /// view.
    #[inline]
    fn scale(&self) -> f64 {
        let half_extent = self.view.max[0] * 0.5 - self.view.min[0] * 0.5;
        self.width * 0.5 / half_extent
    }

    /// The pixel column of `x`.
    #[inline]
    fn x(&self, x: f64) -> f64 {
        self.x_at_scale(x, self.scale())
    }

    /// [`Svg::x`] given [`Svg::scale`] (hoisted out of a loop).
    #[inline]
    fn x_at_scale(&self, x: f64, scale: f64) -> f64 {
        let px = (x * 0.5 - self.view.min[0] * 0.5) * 2.0 * scale + self.margin;
        clamp_px(px)
    }

    /// The pixel row of `y`: y up, so the view's top edge `max[1]` is row `margin`.
    #[inline]
    fn y(&self, y: f64) -> f64 {
        self.y_at_scale(y, self.scale())
    }

    /// [`Svg::y`] given [`Svg::scale`] (hoisted out of a loop).
    #[inline]
    fn y_at_scale(&self, y: f64, scale: f64) -> f64 {
        let px = (self.view.max[1] * 0.5 - y * 0.5) * 2.0 * scale + self.margin;
        clamp_px(px)
    }

    /// The two lines splitting `cell` (which is above the deepest level), as one `<path>`.
    fn cross(&mut self, geometry: &RootGeometry<2>, cell: &Cell<2>) {
        let b = geometry.cell_box(cell);
        // The lower-left child's upper corner is the split point of the cell.
        let mid = geometry.cell_box(&cell.child(0)).max;
        let (x0, x1, xm) = (self.x(b.min[0]), self.x(b.max[0]), self.x(mid[0]));
        let (y0, y1, ym) = (self.y(b.min[1]), self.y(b.max[1]), self.y(mid[1]));
        let _ = writeln!(
            self.body,
            "<path d=\"M{} {}H{}M{} {}V{}\"/>",
            num(x0),
            num(ym),
            num(x1),
            num(xm),
            num(y0),
            num(y1)
        );
    }

    /// A box as one `<rect>` line, with its line break.
    fn rect_line(&self, b: &Aabb<f64, 2>) -> String {
        let (x0, x1) = (self.x(b.min[0]), self.x(b.max[0]));
        let (top, bottom) = (self.y(b.max[1]), self.y(b.min[1]));
        format!(
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>\n",
            num(x0),
            num(top),
            num((x1 - x0).max(0.0)),
            num((bottom - top).max(0.0))
        )
    }

    /// Draws a layer: what `draw` adds, in one `<g>` with `style`'s attributes.
    fn group(&mut self, style: &Style, draw: impl FnOnce(&mut Self)) -> &mut Self {
        let _ = writeln!(self.body, "<g{}>", style.attributes());
        draw(self);
        self.body.push_str("</g>\n");
        self
    }
}

/// The square `[0, side]^2`: the view of a board, or of an image tree's cube.
fn square(side: f64) -> Aabb<f64, 2> {
    Aabb::around(&[[0.0; 2], [side; 2]])
}

/// Draws a 2D point tree like the chapter's Figure 14.5: the lines `refinement` (typically a
/// balanced clone of `tree`, see [`PointTree::balance`]) adds to `tree` dotted, the cells of
/// `tree` solid, and the points of `tree` as dots; the view is `tree`'s root cube, the width
/// [`DEFAULT_WIDTH_PX`], on a white background. The builder calls it makes:
/// [`Svg::refinement`], [`Svg::subdivision`], [`Svg::points`].
///
/// ```
/// use orthtree::io::svg::point_tree_svg;
/// use orthtree::{Aabb, Connectivity, Quadtree};
/// // two points near the centre of the unit square: deep leaves next to big ones
/// let pts = [([0.48, 0.49], ()), ([0.49, 0.49], ()), ([0.9, 0.8], ())];
/// let unit = Aabb::new([0.0, 0.0], [1.0, 1.0]).unwrap();
/// let t = Quadtree::builder().root_box(unit).bucket_size(1).build(&pts).unwrap();
/// let mut balanced = t.clone();
/// assert!(!balanced.balance(Connectivity::Face).is_empty());
/// let svg = point_tree_svg(&t, Some(&balanced));
/// assert!(svg.starts_with("<svg"));
/// assert_eq!(svg.matches("stroke-dasharray").count(), 1); // the dotted refinement
/// assert_eq!(svg.matches("<circle").count(), 3);
/// // without a refinement: no dotted layer
/// assert!(!point_tree_svg(&t, None).contains("stroke-dasharray"));
/// ```
pub fn point_tree_svg<S: Scalar, T>(
    tree: &PointTree<S, T, 2>,
    refinement: Option<&PointTree<S, T, 2>>,
) -> String {
    let mut svg = Svg::new(tree.geometry().root_box(), DEFAULT_WIDTH_PX);
    svg.background("white");
    if let Some(r) = refinement {
        svg.refinement(tree.tree(), r.tree(), r.geometry(), &Style::dotted());
    }
    svg.subdivision(tree.tree(), tree.geometry(), &Style::solid())
        .points(tree.points(), &Style::points())
        .finish()
}
