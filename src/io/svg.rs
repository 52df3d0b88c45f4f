//! SVG pictures of 2D trees, written as plain strings (no dependencies).
//!
//! [`Svg`] is a small builder: a view (the part of the plane shown) and a width in pixels, then
//! layers drawn in the order they are added: leaf cells ([`Svg::cells`]), the subdivision drawn
//! line by line ([`Svg::subdivision`], for dashed or dotted styles), the lines a refinement adds
//! ([`Svg::refinement`]), boxes and points, each with a [`Style`]. The y axis points up (north
//! up, as in the chapter's figures): the view's `max[1]` is the top edge of the picture.
//! [`point_tree_svg`] draws a [`PointTree`] the way the chapter's Figure 14.5 does: the lines
//! balance adds dotted, the tree itself solid, the points as dots.
//!
//! Nothing here panics on odd input: a view of zero or non-finite size, a non-positive width, or
//! NaN coordinates are all mapped to something drawable (see [`Svg::new`]), and colours are
//! escaped.

use crate::geom::{Aabb, Cell, Scalar};
use crate::points::{PointTree, RootGeometry};
use crate::tree::Tree;
use core::fmt::Write as _;
use std::borrow::Borrow;

/// The width in pixels used by [`point_tree_svg`] and when [`Svg::new`] gets an unusable width.
pub const DEFAULT_WIDTH_PX: f64 = 800.0;

/// The margin in pixels around the view unless [`Svg::margin`] sets another.
pub const DEFAULT_MARGIN_PX: f64 = 4.0;

/// Pixel coordinates are clamped to this magnitude, so every number written is finite.
const MAX_PX: f64 = 1e7;

/// How a layer is drawn: stroke, dashes, fill and the radius of point dots. Lengths are in
/// pixels of the output; colours are any SVG colour (`"black"`, `"#8a8a8a"`, `"none"`).
///
/// ```
/// use orthtree::io::svg::Style;
/// let s = Style::dotted().stroke("#06c").stroke_width(1.5);
/// assert_eq!(s.dash, [1.0, 2.0]);
/// assert_eq!(Style::solid().dash, Vec::<f64>::new());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Style {
    /// The stroke colour; `"none"` for no outline.
    pub stroke: String,
    /// The stroke width in pixels.
    pub stroke_width: f64,
    /// The dash pattern in pixels (dash, gap, dash, ...); empty for a solid line.
    pub dash: Vec<f64>,
    /// The fill colour; `"none"` for no fill.
    pub fill: String,
    /// The radius of a point's dot in pixels ([`Svg::points`]).
    pub point_radius: f64,
}

impl Default for Style {
    /// [`Style::solid`].
    fn default() -> Self {
        Style::solid()
    }
}

impl Style {
    /// Thin solid black lines, no fill: the cells of a tree.
    pub fn solid() -> Self {
        Style {
            stroke: "black".into(),
            stroke_width: 1.0,
            dash: Vec::new(),
            fill: "none".into(),
            point_radius: 0.0,
        }
    }

    /// Dotted grey lines, no fill: a refinement drawn under a tree (the chapter's Figure 14.5).
    /// Draw it with [`Svg::subdivision`], which strokes every segment once, so dots from
    /// neighbouring cells do not overlap out of phase.
    pub fn dotted() -> Self {
        Style {
            stroke: "#555".into(),
            stroke_width: 1.0,
            dash: vec![1.0, 2.0],
            fill: "none".into(),
            point_radius: 0.0,
        }
    }

    /// Dashed grey lines, no fill.
    pub fn dashed() -> Self {
        Style {
            dash: vec![4.0, 3.0],
            ..Style::dotted()
        }
    }

    /// Filled black dots of radius 1.6 px, no outline: the points.
    pub fn points() -> Self {
        Style {
            stroke: "none".into(),
            stroke_width: 0.0,
            dash: Vec::new(),
            fill: "black".into(),
            point_radius: 1.6,
        }
    }

    /// The same style with another stroke colour.
    pub fn stroke(mut self, colour: impl Into<String>) -> Self {
        self.stroke = colour.into();
        self
    }

    /// The same style with another stroke width.
    pub fn stroke_width(mut self, width: f64) -> Self {
        self.stroke_width = width;
        self
    }

    /// The same style with another dash pattern (empty: solid).
    pub fn dash(mut self, pattern: &[f64]) -> Self {
        self.dash = pattern.to_vec();
        self
    }

    /// The same style with another fill colour.
    pub fn fill(mut self, colour: impl Into<String>) -> Self {
        self.fill = colour.into();
        self
    }

    /// The same style with another point radius.
    pub fn point_radius(mut self, radius: f64) -> Self {
        self.point_radius = radius;
        self
    }

    /// The presentation attributes of a `<g>` element, with a leading space.
    fn attributes(&self) -> String {
        let mut s = format!(
            " fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\"",
            escape(&self.fill),
            escape(&self.stroke),
            num(length(self.stroke_width))
        );
        let dash: Vec<f64> = self.dash.iter().map(|&d| length(d)).collect();
        // An all-zero pattern would be an error in SVG; treat it as solid.
        if dash.iter().any(|&d| d > 0.0) {
            let parts: Vec<String> = dash.into_iter().map(num).collect();
            let _ = write!(s, " stroke-dasharray=\"{}\"", parts.join(" "));
        }
        s
    }
}

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
        let width = if width_px.is_finite() && width_px > 0.0 {
            width_px
        } else {
            DEFAULT_WIDTH_PX
        };
        Svg {
            view: repair_view(view),
            width,
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
        self.open_group(style);
        let root = geometry.root_box();
        self.rect(&root);
        for (id, cell) in tree.pre_order() {
            if tree.is_leaf(id) {
                continue;
            }
            self.cross(geometry, &cell);
        }
        self.close_group();
        self
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
        self.open_group(style);
        for (id, cell) in refined.pre_order() {
            if refined.is_leaf(id) {
                continue;
            }
            let there = base.locate_cell(&cell);
            if base.level(there) == cell.level() && !base.is_leaf(there) {
                continue;
            }
            self.cross(geometry, &cell);
        }
        self.close_group();
        self
    }

    /// Draws one `<rect>` per box; boxes with a non-finite coordinate are skipped.
    pub fn boxes<B: Borrow<Aabb<f64, 2>>>(
        &mut self,
        boxes: impl IntoIterator<Item = B>,
        style: &Style,
    ) -> &mut Self {
        self.open_group(style);
        for b in boxes {
            let b = b.borrow();
            if b.min.iter().chain(&b.max).all(|v| v.is_finite()) {
                self.rect(b);
            }
        }
        self.close_group();
        self
    }

    /// Draws a dot of radius `style.point_radius` at every point (owned or borrowed, any
    /// [`Scalar`]); points with a non-finite coordinate are skipped.
    pub fn points<S: Scalar, P: Borrow<[S; 2]>>(
        &mut self,
        points: impl IntoIterator<Item = P>,
        style: &Style,
    ) -> &mut Self {
        self.open_group(style);
        let r = num(length(style.point_radius));
        for p in points {
            let [x, y] = p.borrow().map(Scalar::to_f64);
            if x.is_finite() && y.is_finite() {
                let _ = writeln!(
                    self.body,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"{r}\"/>",
                    num(self.x(x)),
                    num(self.y(y))
                );
            }
        }
        self.close_group();
        self
    }

    /// The SVG document.
    pub fn finish(&self) -> String {
        let (w, h) = self.size_px();
        let (w, h) = (num(w), num(h));
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\">\n{}</svg>\n",
            self.body
        )
    }

    /// Writes [`Svg::finish`] to a file.
    pub fn write_to(&self, path: impl AsRef<std::path::Path>) -> std::io::Result<()> {
        std::fs::write(path, self.finish())
    }

    /// Pixels per unit of the plane. Halved differences keep the extent finite for any finite
    /// view.
    fn scale(&self) -> f64 {
        let half_extent = self.view.max[0] * 0.5 - self.view.min[0] * 0.5;
        self.width * 0.5 / half_extent
    }

    /// The pixel column of `x`.
    fn x(&self, x: f64) -> f64 {
        let px = (x * 0.5 - self.view.min[0] * 0.5) * 2.0 * self.scale() + self.margin;
        clamp_px(px)
    }

    /// The pixel row of `y`: y up, so the view's top edge `max[1]` is row `margin`.
    fn y(&self, y: f64) -> f64 {
        let px = (self.view.max[1] * 0.5 - y * 0.5) * 2.0 * self.scale() + self.margin;
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

    fn rect(&mut self, b: &Aabb<f64, 2>) {
        let (x0, x1) = (self.x(b.min[0]), self.x(b.max[0]));
        let (top, bottom) = (self.y(b.max[1]), self.y(b.min[1]));
        let _ = writeln!(
            self.body,
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>",
            num(x0),
            num(top),
            num((x1 - x0).max(0.0)),
            num((bottom - top).max(0.0))
        );
    }

    fn open_group(&mut self, style: &Style) {
        let _ = writeln!(self.body, "<g{}>", style.attributes());
    }

    fn close_group(&mut self) {
        self.body.push_str("</g>\n");
    }
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

/// The view with the repairs documented at [`Svg::new`].
fn repair_view(view: Aabb<f64, 2>) -> Aabb<f64, 2> {
    if !view.min.iter().chain(&view.max).all(|v| v.is_finite()) {
        return Aabb {
            min: [0.0; 2],
            max: [1.0; 2],
        };
    }
    let mut v = view;
    for a in 0..2 {
        if v.min[a] > v.max[a] {
            core::mem::swap(&mut v.min[a], &mut v.max[a]);
        }
    }
    let half = |v: &Aabb<f64, 2>, a: usize| v.max[a] * 0.5 - v.min[a] * 0.5;
    let (h0, h1) = (half(&v, 0), half(&v, 1));
    for (a, mine, other) in [(0, h0, h1), (1, h1, h0)] {
        if mine == 0.0 {
            let h = if other > 0.0 { other } else { 0.5 };
            let c = v.min[a];
            // Centred on c; saturate rather than overflow near the ends of the f64 range.
            v.min[a] = (c - h).max(-f64::MAX);
            v.max[a] = (c + h).min(f64::MAX);
            if half(&v, a) == 0.0 {
                // h vanished next to c's magnitude: widen by an ulp each way.
                v.min[a] = c.next_down().max(-f64::MAX);
                v.max[a] = c.next_up().min(f64::MAX);
            }
        }
    }
    v
}

/// A length: non-negative and finite, else 0.
fn length(x: f64) -> f64 {
    if x.is_finite() && x > 0.0 {
        x
    } else {
        0.0
    }
}

/// A pixel coordinate clamped to a finite range (NaN, which only a degenerate view could
/// produce, becomes 0).
fn clamp_px(x: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(-MAX_PX, MAX_PX)
    }
}

/// A number with at most three decimals and no trailing zeros.
fn num(x: f64) -> String {
    let s = format!("{:.3}", clamp_px(x));
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        &s
    };
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// Escapes a string for an attribute value in double quotes.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(ch),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Connectivity, Quadtree};

    fn unit() -> Aabb<f64, 2> {
        Aabb {
            min: [0.0; 2],
            max: [1.0; 2],
        }
    }

    #[test]
    fn y_points_up() {
        let mut svg = Svg::new(unit(), 100.0);
        svg.margin(0.0);
        svg.points([[0.0, 1.0], [1.0, 0.0]], &Style::points());
        let s = svg.finish();
        // (0, 1) is the top-left corner, (1, 0) the bottom-right
        assert!(s.contains("cx=\"0\" cy=\"0\""), "{s}");
        assert!(s.contains("cx=\"100\" cy=\"100\""), "{s}");
    }

    #[test]
    fn rects_are_flipped_and_scaled() {
        let mut svg = Svg::new(
            Aabb {
                min: [-1.0, -1.0],
                max: [1.0, 3.0],
            },
            200.0,
        );
        svg.margin(0.0);
        let b = Aabb {
            min: [0.0, 0.0],
            max: [1.0, 1.0],
        };
        svg.boxes([b], &Style::solid());
        let s = svg.finish();
        assert!(s.contains("width=\"200\" height=\"400\""), "{s}");
        assert!(
            s.contains("<rect x=\"100\" y=\"200\" width=\"100\" height=\"100\"/>"),
            "{s}"
        );
    }

    #[test]
    fn one_rect_per_leaf_and_one_cross_per_internal_node() {
        let pts: Vec<([f64; 2], usize)> = (0..50)
            .map(|i| {
                (
                    [(i * 37 % 50) as f64 / 50.0, (i * 11 % 50) as f64 / 50.0],
                    i,
                )
            })
            .collect();
        let t = Quadtree::builder().bucket_size(1).build(&pts).unwrap();
        let cells = Svg::new(t.geometry().root_box(), 300.0)
            .cells(t.tree(), t.geometry(), &Style::solid())
            .finish();
        assert_eq!(cells.matches("<rect").count(), t.leaf_count());
        let lines = Svg::new(t.geometry().root_box(), 300.0)
            .subdivision(t.tree(), t.geometry(), &Style::dotted())
            .finish();
        let internal = t.node_count() - t.leaf_count();
        assert_eq!(lines.matches("<path").count(), internal);
        assert_eq!(lines.matches("<rect").count(), 1); // the root outline
        assert!(lines.contains("stroke-dasharray=\"1 2\""));
    }

    #[test]
    fn balanced_figure_has_both_layers() {
        // two points close to the centre: deep leaves next to a level-1 leaf
        let pts = [([0.48, 0.49], 0), ([0.49, 0.49], 1), ([0.9, 0.8], 2)];
        let t = Quadtree::builder()
            .root_box(unit())
            .bucket_size(1)
            .build(&pts)
            .unwrap();
        let mut b = t.clone();
        let splits = b.balance(Connectivity::Face).len();
        assert!(splits > 0);
        let s = point_tree_svg(&t, Some(&b));
        let dotted = s.find("stroke-dasharray").unwrap();
        let solid = s.find("stroke=\"black\"").unwrap();
        assert!(dotted < solid, "the refinement is drawn underneath");
        // one dotted cross per leaf that balance split, nothing else in that layer
        assert_eq!(s[dotted..solid].matches("<path").count(), splits);
        assert_eq!(s[dotted..solid].matches("<rect").count(), 0);
        let internal = t.node_count() - t.leaf_count();
        assert_eq!(s[solid..].matches("<path").count(), internal);
        assert_eq!(s.matches("<circle").count(), 3);
        assert!(s.contains("fill=\"white\""));
    }

    #[test]
    fn degenerate_input_is_drawn_not_refused() {
        // zero-size view, zero and NaN widths, NaN points, odd colours
        let point = Aabb {
            min: [2.0, 2.0],
            max: [2.0, 2.0],
        };
        let mut svg = Svg::new(point, 0.0);
        svg.points(
            [[2.0, 2.0], [f64::NAN, 1.0]],
            &Style::points().fill("\"><x"),
        );
        let s = svg.finish();
        assert!(s.contains(&format!("width=\"{}\"", DEFAULT_WIDTH_PX + 8.0)));
        assert_eq!(s.matches("<circle").count(), 1);
        assert!(s.contains("cx=\"404\" cy=\"404\""), "{s}");
        assert!(s.contains("&quot;&gt;&lt;x"));
        assert!(!s.contains("NaN") && !s.contains("inf"));

        let weird = [
            Aabb {
                min: [f64::NAN, 0.0],
                max: [1.0, 1.0],
            },
            Aabb {
                min: [1.0, 1.0],
                max: [0.0, 0.0],
            },
            Aabb {
                min: [-f64::MAX, 0.0],
                max: [f64::MAX, 0.0],
            },
            Aabb {
                min: [f64::MAX, 1e-300],
                max: [f64::MAX, 2e-300],
            },
        ];
        for v in weird {
            let mut svg = Svg::new(v, f64::NAN);
            svg.margin(f64::INFINITY)
                .boxes([v, unit()], &Style::solid().stroke_width(f64::NAN))
                .points([[f64::MAX, -f64::MAX], [0.0, 0.0]], &Style::points())
                .points([[i64::MIN, 3]], &Style::points().point_radius(-1.0));
            let s = svg.finish();
            assert!(s.starts_with("<svg"), "{v:?}");
            assert!(!s.contains("NaN") && !s.contains("inf"), "{v:?}: {s}");
            let (w, h) = svg.size_px();
            assert!(
                w.is_finite() && h.is_finite() && w > 0.0 && h >= 0.0,
                "{v:?}"
            );
        }
    }

    #[test]
    fn all_zero_dash_is_solid_and_numbers_are_short() {
        assert!(!Style::solid()
            .dash(&[0.0, 0.0])
            .attributes()
            .contains("dasharray"));
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.0001), "0");
        assert_eq!(num(2.5), "2.5");
        assert_eq!(num(f64::INFINITY), "10000000");
    }
}
