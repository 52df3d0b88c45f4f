//! SVG of a 2D region tree: black leaves filled, every leaf cell outlined thinly, the image's
//! extent outlined when it is padded. Pixel `(x, y)` is drawn with row 0 at the top, as image
//! viewers show it (the plane's y axis points up, so row `y` is the strip
//! `side - y - 1 .. side - y`).

use super::{Style, Svg, DEFAULT_WIDTH_PX};
use crate::geom::Aabb;
use crate::image::{Block, ImageTree};

/// The plane box of a block, row 0 at the top of a cube of side `side`.
fn block_box(b: &Block<2>, side: f64) -> Aabb<f64, 2> {
    let [x, y] = b.min.map(f64::from);
    let s = f64::from(b.side);
    Aabb {
        min: [x, side - y - s],
        max: [x + s, side - y],
    }
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
/// dashed red; [`DEFAULT_WIDTH_PX`] wide.
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
    let side = f64::from(tree.side());
    let cube = Aabb {
        min: [0.0, 0.0],
        max: [side, side],
    };
    let mut svg = Svg::new(cube, DEFAULT_WIDTH_PX);
    svg.background("white");
    let width = (0.5f64).min(DEFAULT_WIDTH_PX / side / 4.0);
    svg.image_tree(
        tree,
        &Style::solid().stroke("none").fill("black"),
        &Style::solid().stroke("#888").stroke_width(width),
    );
    if !tree.is_cube() {
        let [w, h] = tree.extent().map(f64::from);
        let extent = Aabb {
            min: [0.0, side - h],
            max: [w, side],
        };
        svg.boxes([extent], &Style::dashed().stroke("red"));
    }
    svg.finish()
}
