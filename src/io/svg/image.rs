//! SVG of a 2D region tree: black leaves filled, every leaf cell outlined thinly, the image's
//! extent outlined when it is padded. Pixel `(x, y)` is drawn with row 0 at the top, as image
//! viewers show it (the plane's y axis points up, so row `y` is the strip
//! `side - y - 1 .. side - y`).

use super::{square, Style, Svg, DEFAULT_WIDTH_PX};
use crate::geom::Aabb;
use crate::image::{Block, ImageTree};
use std::io::{BufWriter, Write};

/// The plane box of a block, row 0 at the top of a cube of side `side`.
fn block_box(b: &Block<2>, side: f64) -> Aabb<f64, 2> {
    let [x, y] = b.min.map(f64::from);
    let s = f64::from(b.side);
    Aabb::around(&[[x, side - y - s], [x + s, side - y]])
}

impl Svg {
    /// Draws the leaves of a 2D region tree whose root cube is the view's `[0, side]^2`: the
    /// black leaves with `black` (typically a fill and no stroke), then the outlines of all
    /// leaves with `outline`. Row 0 of the image is at the top.
    pub fn image_tree(&mut self, tree: &ImageTree, black: &Style, outline: &Style) -> &mut Self {
        let side = f64::from(tree.side());
        self.boxes(
            tree.blocks()
                .filter(|b| b.black)
                .map(|b| block_box(&b, side)),
            black,
        );
        self.boxes(tree.blocks().map(|b| block_box(&b, side)), outline)
    }
}

/// An SVG picture of a 2D region tree: its root cube `[0, 2^k]^2` on a white background, black
/// leaves filled black, every leaf cell outlined in thin grey, and the extent (when padded) in
/// dashed red; [`DEFAULT_WIDTH_PX`] wide. [`write_image_tree_svg`] into a `String`.
///
/// ```
/// use orthtree::image::ImageTree;
/// use orthtree::io::svg::image_tree_svg;
/// let t = ImageTree::from_boxes([6, 8], &[([0, 0], [4, 4])]).unwrap();
/// let svg = image_tree_svg(&t);
/// assert_eq!(svg.matches("<rect").count(), 1 + 1 + t.leaf_count() + 1);
/// assert!(svg.contains("stroke-dasharray")); // the 6 x 8 extent inside the 8 x 8 cube
/// ```
pub fn image_tree_svg(tree: &ImageTree) -> String {
    let mut out = Vec::new();
    write_image_tree_svg(tree, &mut out).expect("writing to a Vec does not fail");
    String::from_utf8(out).expect("the SVG is ASCII")
}

/// Writes the picture of [`image_tree_svg`] to `out` through a buffer, one `<rect>` per leaf as
/// the leaves are visited: memory O(k), whatever the tree's size.
///
/// # Errors
/// The first error of `out`.
///
/// ```
/// use orthtree::image::ImageTree;
/// use orthtree::io::svg::{write_image_tree_svg, Style, Svg, DEFAULT_WIDTH_PX};
/// use orthtree::Aabb;
/// let t = ImageTree::from_ball([40, 30], [20.0, 15.0], 9.0).unwrap();
/// let mut out = Vec::new();
/// write_image_tree_svg(&t, &mut out).unwrap();
/// // the same picture as the builder's layers
/// let side = f64::from(t.side());
/// let mut svg = Svg::new(Aabb { min: [0.0; 2], max: [side; 2] }, DEFAULT_WIDTH_PX);
/// svg.background("white");
/// let outline = Style::solid().stroke("#888").stroke_width(0.5f64.min(800.0 / side / 4.0));
/// svg.image_tree(&t, &Style::solid().stroke("none").fill("black"), &outline);
/// let extent = Aabb { min: [0.0, side - 30.0], max: [40.0, side] };
/// svg.boxes([extent], &Style::dashed().stroke("red"));
/// assert_eq!(String::from_utf8(out).unwrap(), svg.finish());
/// ```
pub fn write_image_tree_svg(tree: &ImageTree, out: impl Write) -> std::io::Result<()> {
    let side = f64::from(tree.side());
    let svg = Svg::new(square(side), DEFAULT_WIDTH_PX);
    let mut out = BufWriter::new(out);
    out.write_all(svg.header().as_bytes())?;
    writeln!(out, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>")?;
    let width = (0.5f64).min(DEFAULT_WIDTH_PX / side / 4.0);
    let layers = [
        (Style::solid().stroke("none").fill("black"), true),
        (Style::solid().stroke("#888").stroke_width(width), false),
    ];
    for (style, only_black) in &layers {
        writeln!(out, "<g{}>", style.attributes())?;
        for b in tree.blocks().filter(|b| b.black || !only_black) {
            out.write_all(svg.rect_line(&block_box(&b, side)).as_bytes())?;
        }
        writeln!(out, "</g>")?;
    }
    if !tree.is_cube() {
        let [w, h] = tree.extent().map(f64::from);
        let extent = Aabb::around(&[[0.0, side - h], [w, side]]);
        writeln!(out, "<g{}>", Style::dashed().stroke("red").attributes())?;
        out.write_all(svg.rect_line(&extent).as_bytes())?;
        writeln!(out, "</g>")?;
    }
    writeln!(out, "</svg>")?;
    out.flush()
}
