//! The SVG writer through the public API: y up, scaling, one shape per cell, degenerate views drawn.
use orthtree::io::svg::*;
use orthtree::Aabb;
use orthtree::{Connectivity, Quadtree};

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
