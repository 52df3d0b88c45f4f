//! Serde (feature `serde`) through JSON: point trees (plain, balanced, with freed blocks, over
//! points whose root cube reaches beyond `f64::MAX`; D = 1, 2, 3; f64 and i32), the arena, region
//! trees, boxes and cells round-trip and answer as before;
//! corrupted documents (a point moved out of its leaf, a broken link, a wrong dimension, an
//! inverted box, a cell off its level, a collapsible region node) are refused with an error that
//! names what is broken.

use super::saved::check_against_brute;
use crate::common::points::{
    assert_numbers, beyond_f64_max, beyond_f64_max_queries, check_domain_beyond_f64_max,
};
use orthtree::image::ImageTree;
use orthtree::prelude::*;
use orthtree::tree::NodeId;
use orthtree::{points::PointTreeBuilder, Aabb, Cell, Connectivity, PointTree, Tree};
use serde_json::{json, Value};

fn grid<const D: usize>(n: usize, side: u64) -> Vec<([f64; D], u32)> {
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    (0..n)
        .map(|i| {
            let p = core::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x % side) as f64 * 0.5
            });
            (p, i as u32)
        })
        .collect()
}

fn round_trip<const D: usize>(t: &PointTree<f64, u32, D>, qs: &[[f64; D]]) {
    let json = serde_json::to_string(t).unwrap();
    let back: PointTree<f64, u32, D> = serde_json::from_str(&json).unwrap();
    back.validate().unwrap();
    assert_eq!(back.points(), t.points());
    assert_eq!(back.items(), t.items());
    assert_eq!(back.tree(), t.tree());
    assert_eq!(back.geometry(), t.geometry());
    for q in qs {
        assert_eq!(back.k_nearest(q, 4).unwrap(), t.k_nearest(q, 4).unwrap());
    }
    check_against_brute(&back, qs);
}

#[test]
fn point_trees_round_trip_through_json() {
    let pts = grid::<2>(300, 40);
    let qs: Vec<[f64; 2]> = pts.iter().step_by(17).map(|p| p.0).collect();
    let mut t = PointTreeBuilder::new().bucket_size(3).build(&pts).unwrap();
    round_trip(&t, &qs);
    t.balance(Connectivity::Edge);
    round_trip(&t, &qs);
    let mut t = PointTreeBuilder::new().bucket_size(2).build(&pts).unwrap();
    for (p, i) in &pts[20..200] {
        assert!(t.remove(p, i));
    }
    round_trip(&t, &qs);
    let empty = PointTree::<f64, u32, 3>::new(&[]).unwrap();
    round_trip(&empty, &[[0.5; 3]]);
    let one = grid::<1>(50, 9);
    round_trip(&PointTree::new(&one).unwrap(), &[[1.0], [7.5]]);
    let ints: Vec<([i32; 3], u8)> = (0..100).map(|i| ([i % 5, i % 7, -i], i as u8)).collect();
    let t = PointTree::new(&ints).unwrap();
    let back: PointTree<i32, u8, 3> =
        serde_json::from_str(&serde_json::to_string(&t).unwrap()).unwrap();
    assert_eq!((back.points(), back.items()), (t.points(), t.items()));
}

/// Point trees over points whose root cube's far side rounds beyond `f64::MAX`: the domain
/// stops at `f64::MAX`, so the document holds no infinity (JSON has none: it would write `null`)
/// and reads back the same tree; a domain maximum of `null`, beyond `f64::MAX` or beyond the
/// root cube is refused.
#[test]
fn point_trees_over_points_beyond_f64_max_round_trip_through_json() {
    for pts in beyond_f64_max(32) {
        let qs = beyond_f64_max_queries(&pts);
        for bucket in [1, 64] {
            let t = PointTreeBuilder::new()
                .bucket_size(bucket)
                .build(&pts)
                .unwrap();
            check_domain_beyond_f64_max(&t, &pts);
            assert_numbers(
                &serde_json::to_value(&t).unwrap(),
                &["half_lo", "half_side", "domain_min", "domain_max"],
            );
            let json = serde_json::to_string(&t).unwrap();
            let back: PointTree<f64, u32, 3> = serde_json::from_str(&json).unwrap();
            assert_eq!(back.domain(), t.domain());
            round_trip(&t, &qs);
        }
    }
    let t = PointTree::new(&beyond_f64_max(32)[0]).unwrap();
    let root_max_0 = t.geometry().root_box().max[0];
    let refused = |edit: &dyn Fn(&mut Value)| -> String {
        let mut v = serde_json::to_value(&t).unwrap();
        edit(&mut v);
        match serde_json::from_value::<PointTree<f64, u32, 3>>(v) {
            Ok(_) => panic!("a corrupted document was accepted"),
            Err(e) => e.to_string(),
        }
    };
    let e = refused(&|v| v["domain_max"][1] = Value::Null);
    assert!(e.contains("null"), "{e}");
    let e = refused(&|v| v["domain_max"][0] = json!(root_max_0.next_up()));
    assert!(e.contains("axis 0") && e.contains("root cube"), "{e}");
    let json = serde_json::to_string(&t).unwrap();
    let at = json.find("\"domain_max\":[").unwrap() + "\"domain_max\":[".len();
    let beyond = format!(
        "{}1e309{}",
        &json[..at],
        &json[json[at..].find(',').unwrap() + at..]
    );
    assert!(serde_json::from_str::<PointTree<f64, u32, 3>>(&beyond).is_err());
}

/// `t` as a JSON value, changed by `edit`, read back: the error's message.
fn corrupted(t: &PointTree<f64, u32, 2>, edit: impl FnOnce(&mut Value)) -> String {
    let mut v = serde_json::to_value(t).unwrap();
    edit(&mut v);
    match serde_json::from_value::<PointTree<f64, u32, 2>>(v) {
        Ok(_) => panic!("a corrupted document was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn corrupted_point_trees_are_refused_by_invariant() {
    let pts = grid::<2>(200, 40);
    let t = PointTreeBuilder::new().bucket_size(3).build(&pts).unwrap();
    // The first point moved to the far corner: out of its leaf (or of Morton order).
    let e = corrupted(&t, |v| v["points"][0] = json!(19.5));
    assert!(e.contains("out of place"), "{e}");
    let e = corrupted(&t, |v| v["points"][1] = json!(1e300));
    assert!(e.contains("outside the domain"), "{e}");
    let e = corrupted(&t, |v| v["tree"]["first_child"][0] = json!(2));
    assert!(e.contains("node arena"), "{e}");
    let e = corrupted(&t, |v| v["tree"]["dimension"] = json!(3));
    assert!(e.contains("dimension 3, expected 2"), "{e}");
    let e = corrupted(&t, |v| {
        v["points"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("not whole points"), "{e}");
    let e = corrupted(&t, |v| {
        v["items"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("differ in length"), "{e}");
    let e = corrupted(&t, |v| v["run_ends"][0] = json!(7));
    assert!(e.contains("run"), "{e}");
    let e = corrupted(&t, |v| v["bucket_size"] = json!(0));
    assert!(e.contains("bucket size is 0"), "{e}");
    let e = corrupted(&t, |v| v["half_side"] = json!(-1.0));
    assert!(e.contains("root cube"), "{e}");
    let e = corrupted(&t, |v| v["domain_max"][1] = json!(1e9));
    assert!(e.contains("axis 1"), "{e}");
}

#[test]
fn arenas_region_trees_boxes_and_cells_round_trip_and_are_checked() {
    let mut tree = Tree::<3>::new();
    let first = tree.split(NodeId::ROOT);
    tree.split(first);
    let json = serde_json::to_string(&tree).unwrap();
    assert_eq!(serde_json::from_str::<Tree<3>>(&json).unwrap(), tree);
    let mut v: Value = serde_json::from_str(&json).unwrap();
    v["level"][3] = json!(5);
    let e = serde_json::from_value::<Tree<3>>(v)
        .unwrap_err()
        .to_string();
    assert!(e.contains("node 3 is at level 5, expected level 1"), "{e}");

    let image = ImageTree::from_boxes([8, 6], &[([1, 1], [5, 4]), ([6, 0], [8, 2])]).unwrap();
    let json = serde_json::to_string(&image).unwrap();
    assert_eq!(serde_json::from_str::<ImageTree>(&json).unwrap(), image);
    let e = serde_json::from_str::<ImageTree>(r#"{"extent":[2,2],"nodes":[2,1,1,1,1]}"#);
    assert!(e.is_err());

    let b = Aabb::new([0.5, -1.0, 2.0], [1.0, 1.0, 2.0]).unwrap();
    let json = serde_json::to_string(&b).unwrap();
    assert_eq!(serde_json::from_str::<Aabb<f64, 3>>(&json).unwrap(), b);
    let e = serde_json::from_str::<Aabb<f64, 3>>(r#"{"min":[0,0],"max":[1,1]}"#).unwrap_err();
    assert!(e.to_string().contains("2 values for 3 dimensions"), "{e}");

    let c = Cell::<2>::new(3, [5, 2]).unwrap();
    let json = serde_json::to_string(&c).unwrap();
    assert_eq!(serde_json::from_str::<Cell<2>>(&json).unwrap(), c);
    let e = serde_json::from_str::<Cell<2>>(r#"{"level":2,"coords":[4,0]}"#).unwrap_err();
    assert!(e.to_string().contains("below 2^level"), "{e}");
}
