//! Serde (feature `serde`) of `DynamicPointTree` through JSON: trees fresh from a build, after
//! inserts and removes (chunks with slack, free space in the chunk array), with duplicates and
//! points on split lines, over points whose root cube reaches beyond `f64::MAX`, empty, for D = 1,
//! 2, 3 and 6, read back valid and answering as before
//! (against brute force, slots and ties included), and updating alike afterwards; corrupted
//! documents refused with an error naming what is broken; mutated documents refused or valid.

use crate::common::mutate::mutate;
use crate::common::points::{
    assert_numbers, beyond_f64_max, beyond_f64_max_queries, check_domain_beyond_f64_max, config,
    same_answers,
};
use orthtree::prelude::*;
use orthtree::{points::PointTreeBuilder, Aabb, DynamicPointTree};
use proptest::prelude::*;
use serde_json::{json, Value};

type Dyn<const D: usize> = DynamicPointTree<f64, u32, D>;

/// `n` points on a grid of step 0.5 (many on split lines, many repeated), numbered.
fn grid<const D: usize>(n: usize, side: u64, seed: u64) -> Vec<([f64; D], u32)> {
    let mut x = seed | 1;
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

/// A dynamic tree over the cube `[0, side / 2]^D`, built from the first `built` pairs, the rest
/// inserted, then every third of them removed: chunks with slack and free space.
fn churned<const D: usize>(pts: &[([f64; D], u32)], built: usize, bucket: usize) -> Dyn<D> {
    let hi = pts.iter().flat_map(|p| p.0).fold(1.0, f64::max);
    let root = Aabb::new([0.0; D], [hi; D]).unwrap();
    let b = PointTreeBuilder::new().root_box(root).bucket_size(bucket);
    let mut t = DynamicPointTree::from(b.build(&pts[..built]).unwrap());
    for &(p, i) in &pts[built..] {
        t.insert(p, i).unwrap();
    }
    for (p, i) in pts.iter().step_by(3) {
        assert!(t.remove(p, i));
    }
    t.validate().unwrap();
    t
}

fn round_trip<const D: usize>(t: &Dyn<D>, qs: &[[f64; D]]) -> Dyn<D> {
    let json = serde_json::to_string(t).unwrap();
    let back: Dyn<D> = serde_json::from_str(&json).unwrap();
    same_answers(t, &back, qs);
    assert_eq!(back.tree(), t.tree());
    assert_eq!(back.geometry(), t.geometry());
    assert_eq!(
        (back.bucket_size(), back.max_depth()),
        (t.bucket_size(), t.max_depth())
    );
    // Free space reads back with a filler point and its nodes cleared: the second round trip
    // is exact.
    let again = serde_json::to_string(&back).unwrap();
    let third: Dyn<D> = serde_json::from_str(&again).unwrap();
    assert_eq!(
        serde_json::to_string(&third).unwrap(),
        again,
        "written again the same"
    );
    back
}

fn queries<const D: usize>(pts: &[([f64; D], u32)]) -> Vec<[f64; D]> {
    let mut qs: Vec<[f64; D]> = pts.iter().step_by(11).map(|p| p.0).collect();
    qs.push([0.25; D]);
    qs.push([1e6; D]);
    qs
}

#[test]
fn dynamic_trees_round_trip_in_every_dimension() {
    let pts = grid::<2>(400, 30, 0x9e37_79b9_7f4a_7c15);
    round_trip(&DynamicPointTree::new(&pts).unwrap(), &queries(&pts));
    let mut t = churned(&pts, 100, 3);
    let mut back = round_trip(&t, &queries(&pts));
    // The same updates on both: the same trees (free space is reused alike).
    for &(p, i) in pts.iter().step_by(5) {
        t.insert(p, i + 1000).unwrap();
        back.insert(p, i + 1000).unwrap();
    }
    for (p, i) in pts.iter().step_by(4) {
        assert_eq!(t.remove(p, i), back.remove(p, i));
    }
    // The free lists read back may cut the free space differently, so later chunks may land
    // elsewhere and ties among equal distances may come in another order: the same pairs in
    // the same slots, the same leaves, the same distances.
    back.validate().unwrap();
    assert!(back.iter().eq(t.iter()), "the pairs by slot");
    assert_eq!(back.tree().leaves().count(), t.tree().leaves().count());
    for q in queries(&pts) {
        let d = |x: &Dyn<2>| -> Vec<f64> {
            x.k_nearest(&q, 9)
                .unwrap()
                .iter()
                .map(|n| n.distance)
                .collect()
        };
        assert_eq!(d(&back), d(&t), "9 nearest of {q:?}");
    }

    let pts = grid::<1>(300, 17, 5);
    round_trip(&churned(&pts, 0, 2), &queries(&pts));
    let pts = grid::<3>(500, 9, 77);
    round_trip(&churned(&pts, 250, 4), &queries(&pts));
    let pts = grid::<6>(200, 4, 99);
    round_trip(&churned(&pts, 50, 2), &queries(&pts));
    // All points equal: one leaf at the maximum depth over the bucket size.
    let same: Vec<([f64; 2], u32)> = (0..40).map(|i| ([0.5, 0.5], i)).collect();
    let b = PointTreeBuilder::new().bucket_size(2).max_depth(4);
    round_trip(
        &DynamicPointTree::from(b.build(&same).unwrap()),
        &[[0.5, 0.5]],
    );
    // Empty, and emptied.
    round_trip(&Dyn::<3>::new(&[]).unwrap(), &[[0.0; 3]]);
    let mut t = churned(&pts[..20], 10, 1);
    for (p, i) in &pts[..20] {
        t.remove(p, i);
    }
    assert!(t.is_empty());
    round_trip(&t, &[[1.0; 6]]);
}

/// Dynamic trees over points whose root cube's far side rounds beyond `f64::MAX`, fresh and
/// after updates at the domain's corners: the domain stops at `f64::MAX`, so the document holds
/// no infinity and reads back the same tree.
#[test]
fn dynamic_trees_over_points_beyond_f64_max_round_trip() {
    for pts in beyond_f64_max(33) {
        let qs = beyond_f64_max_queries(&pts);
        let b = PointTreeBuilder::new().bucket_size(2);
        let mut t = DynamicPointTree::from(b.build(&pts).unwrap());
        check_domain_beyond_f64_max(&t, &pts);
        assert_numbers(
            &serde_json::to_value(&t).unwrap(),
            &["half_lo", "half_side", "domain_min", "domain_max"],
        );
        assert_eq!(round_trip(&t, &qs).domain(), t.domain());
        let domain = *t.domain();
        t.insert(domain.max, 1000).unwrap();
        t.insert(domain.min, 1001).unwrap();
        assert!(t.remove(&pts[0].0, &pts[0].1));
        assert_eq!(*t.domain(), domain);
        assert_eq!(round_trip(&t, &qs).domain(), &domain);
    }
}

/// A live leaf of a tree holding at least two points: its node index, count and chunk start.
#[derive(Clone, Copy)]
struct Leaf {
    node: usize,
    count: u64,
    start: usize,
}

/// A churned 2D tree as a JSON value, changed by `edit` (given a live leaf of two points or
/// more), read back: the error's message.
fn corrupted(edit: impl FnOnce(&mut Value, Leaf)) -> String {
    let pts = grid::<2>(200, 30, 3);
    let t = churned(&pts, 100, 3);
    let mut v = serde_json::to_value(&t).unwrap();
    let leaf = t
        .tree()
        .leaves()
        .map(|(id, _)| {
            let rec = &v["nodes"][id.index()];
            Leaf {
                node: id.index(),
                count: rec[0].as_u64().unwrap(),
                start: rec[1].as_u64().unwrap() as usize,
            }
        })
        .find(|l| l.count > 1)
        .unwrap();
    edit(&mut v, leaf);
    match serde_json::from_value::<Dyn<2>>(v) {
        Ok(_) => panic!("a corrupted document was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn corrupted_dynamic_trees_are_refused_by_invariant() {
    let e = corrupted(|v, l| {
        v["points"][2 * l.start] = json!(f64::MAX);
    });
    assert!(
        e.contains("outside the domain") || e.contains("out of place"),
        "{e}"
    );
    let e = corrupted(|v, l| {
        v["points"][2 * l.start + 1] = json!(-3.0);
    });
    assert!(e.contains("outside the domain"), "{e}");
    let e = corrupted(|v, _| {
        v["points"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("not whole points"), "{e}");
    let e = corrupted(|v, _| {
        v["slots"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("slots"), "{e}");
    let e = corrupted(|v, _| v["nodes"][0][0] = json!(7));
    assert!(e.contains("root counts 7 points"), "{e}");
    let e = corrupted(|v, l| {
        v["nodes"][l.node][0] = json!(l.count - 1);
    });
    assert!(e.contains("count"), "{e}");
    let e = corrupted(|v, l| {
        v["nodes"][l.node][1] = json!(u32::MAX);
    });
    assert!(e.contains("in an array of"), "{e}");
    let e = corrupted(|v, l| {
        v["nodes"][l.node][2] = json!(0);
    });
    assert!(e.contains("chunk of 0 entries"), "{e}");
    let e = corrupted(|v, l| {
        v["slots"][l.start] = json!(100_000);
    });
    assert!(e.contains("holds slot 100000"), "{e}");
    let e = corrupted(|v, l| {
        let other = v["slots"][l.start + 1].clone();
        v["slots"][l.start] = other;
    });
    assert!(e.contains("slot disagree"), "{e}");
    let e = corrupted(|v, _| {
        v["items"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("root counts"), "{e}");
    let e = corrupted(|v, _| {
        v["nodes"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("node records"), "{e}");
    let e = corrupted(|v, _| v["bucket_size"] = json!(0));
    assert!(e.contains("bucket size is 0"), "{e}");
    let e = corrupted(|v, _| v["max_depth"] = json!(200));
    assert!(e.contains("maximum depth 200"), "{e}");
    let e = corrupted(|v, _| v["max_depth"] = json!(0));
    assert!(e.contains("maximum depth being 0"), "{e}");
    let e = corrupted(|v, _| v["half_side"] = json!(-1.0));
    assert!(e.contains("root cube"), "{e}");
    let e = corrupted(|v, _| v["domain_max"][1] = json!(1e9));
    assert!(e.contains("axis 1"), "{e}");
    let e = corrupted(|v, _| v["tree"]["dimension"] = json!(3));
    assert!(e.contains("dimension 3, expected 2"), "{e}");
    let e = corrupted(|v, _| v["tree"]["first_child"][0] = json!(4));
    assert!(e.contains("node arena"), "{e}");
}

proptest! {
    #![proptest_config(config(300, 0x5e7d_e001))]

    /// A mutated document is refused, or read back as a valid tree that answers queries and
    /// takes updates without a panic.
    #[test]
    fn mutated_dynamic_documents_are_refused_or_valid(
        steps in prop::collection::vec((any::<u64>(), any::<u8>()), 1..4),
    ) {
        let pts = grid::<2>(60, 12, 11);
        let mut v = serde_json::to_value(churned(&pts, 30, 2)).unwrap();
        let done: Vec<String> = steps.iter().map(|&(at, kind)| mutate(&mut v, at, kind)).collect();
        if let Ok(mut t) = serde_json::from_value::<Dyn<2>>(v) {
            prop_assert!(t.validate().is_ok(), "{done:?}");
            let n = t.len();
            prop_assert_eq!(t.k_nearest(&[1.0, 2.0], 5).unwrap().len(), n.min(5));
            for &(p, i) in &pts {
                if t.insert(p, i).is_ok() {
                    prop_assert!(t.remove(&p, &i));
                }
            }
            prop_assert!(t.validate().is_ok(), "{done:?}");
        }
    }
}
