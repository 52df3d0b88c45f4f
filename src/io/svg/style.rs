//! [`Style`]: how a layer of an SVG picture is drawn.

use super::format::{escape, length, num};
use core::fmt::Write as _;

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
    /// The radius of a point's dot in pixels ([`Svg::points`](super::Svg::points)).
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
    /// Draw it with [`Svg::subdivision`](super::Svg::subdivision), which strokes every segment once, so dots from
    /// neighbouring cells do not overlap out of phase.
    pub fn dotted() -> Self {
        Style {
            stroke: "#555".into(),
            dash: vec![1.0, 2.0],
            ..Style::solid()
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
            fill: "black".into(),
            point_radius: 1.6,
            ..Style::solid()
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
    pub(super) fn attributes(&self) -> String {
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
