//! Serde (feature `serde`) of the compressed trees through JSON: `CompressedTree` and
//! `SkipQuadtree` fresh from a build and after updates (duplicates listed out of slot order,
//! points closer than the finest `Cell`, points on split lines, points whose root cube reaches
//! beyond `f64::MAX`), empty, for D = 1, 2, 3 and 5,
//! read back valid and answering as before (against brute force, slots and ties included);
//! `Subdivision` and `PointLocator` read back locating as before; corrupted documents refused
//! with an error naming what is broken; mutated documents refused or valid.

use crate::common::mutate::mutate;
use crate::common::points::{
    assert_numbers, beyond_f64_max, beyond_f64_max_queries, check_domain_beyond_f64_max, config,
    same_answers,
};
use orthtree::compressed::{PointLocator, SkipQuadtree, Subdivision};
use orthtree::prelude::*;
use orthtree::{Aabb, CompressedTree};
use proptest::prelude::*;
use serde_json::{json, Value};

type Comp<const D: usize> = CompressedTree<f64, u32, D>;
type Skip<const D: usize> = SkipQuadtree<f64, u32, D>;

/// `n` points on a grid of step 0.5 in `[0, side / 2)^D` (many on split lines, many repeated),
/// numbered, and a few 2^-50 apart (one finest `Cell`, distinct deep cells).
fn points<const D: usize>(n: usize, side: u64, seed: u64) -> Vec<([f64; D], u32)> {
    let mut x = seed | 1;
    let mut pts: Vec<([f64; D], u32)> = (0..n)
        .map(|i| {
            let p = core::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x % side) as f64 * 0.5
            });
            (p, i as u32)
        })
        .collect();
    let close = (-50f64).exp2();
    for j in 0..3u32 {
        let mut p = [0.75; D];
        p[0] += f64::from(j) * close;
        pts.push((p, n as u32 + j));
    }
    pts
}

/// A compressed tree over `[0, side / 2]^D` built from the first `built` pairs, the rest
/// inserted, then every third removed: slots moved, duplicates listed out of slot order.
fn churned<const D: usize>(pts: &[([f64; D], u32)], built: usize, side: u64) -> Comp<D> {
    let root = Aabb::new([0.0; D], [side as f64 * 0.5; D]).unwrap();
    let mut t = CompressedTree::builder()
        .root_box(root)
        .build(&pts[..built])
        .unwrap();
    for &(p, i) in &pts[built..] {
        t.insert(p, i).unwrap();
    }
    for (p, i) in pts.iter().step_by(3) {
        assert!(t.remove(p, i));
    }
    t.validate().unwrap();
    t
}

fn queries<const D: usize>(pts: &[([f64; D], u32)]) -> Vec<[f64; D]> {
    let mut qs: Vec<[f64; D]> = pts.iter().step_by(7).map(|p| p.0).collect();
    qs.extend([[0.75; D], [0.3; D], [-5.0; D]]);
    qs
}

fn round_trip<const D: usize>(t: &Comp<D>, qs: &[[f64; D]]) {
    let json = serde_json::to_string(t).unwrap();
    let back: Comp<D> = serde_json::from_str(&json).unwrap();
    same_answers(t, &back, qs);
    assert!(back.cells().eq(t.cells()), "the same nodes");
    assert_eq!(back.geometry(), t.geometry());
    assert_eq!(
        serde_json::to_string(&back).unwrap(),
        json,
        "written again the same"
    );
}

fn skip_round_trip<const D: usize>(t: &Skip<D>, qs: &[[f64; D]]) {
    let json = serde_json::to_string(t).unwrap();
    let back: Skip<D> = serde_json::from_str(&json).unwrap();
    same_answers(t, &back, qs);
    assert_eq!(
        (back.seed(), back.level_count()),
        (t.seed(), t.level_count())
    );
    for i in 0..t.level_count() {
        assert!(back.level_cells(i).eq(t.level_cells(i)), "level {i}");
    }
    for q in qs {
        let (a, b) = (t.locate(q).unwrap(), back.locate(q).unwrap());
        assert_eq!(a.map(|l| (l.cell, l.leaf)), b.map(|l| (l.cell, l.leaf)));
        let near = |s: &Skip<D>| s.approx_nearest(q, 0.5).unwrap().0.map(|n| n.index);
        assert_eq!(near(t), near(&back));
    }
}

#[test]
fn compressed_trees_round_trip_in_every_dimension() {
    let pts = points::<2>(300, 20, 0x9e37_79b9_7f4a_7c15);
    round_trip(&CompressedTree::new(&pts).unwrap(), &queries(&pts));
    let t = churned(&pts, 100, 20);
    round_trip(&t, &queries(&pts));
    skip_round_trip(&SkipQuadtree::with_seed(t, 12345), &queries(&pts));
    let pts = points::<1>(200, 15, 3);
    round_trip(&churned(&pts, 0, 15), &queries(&pts));
    let pts = points::<3>(300, 7, 5);
    let t = churned(&pts, 150, 7);
    round_trip(&t, &queries(&pts));
    skip_round_trip(&SkipQuadtree::with_seed(t, 7), &queries(&pts));
    let pts = points::<5>(150, 4, 9);
    round_trip(&churned(&pts, 50, 4), &queries(&pts));
    // Every point equal: one leaf.
    let same: Vec<([f64; 2], u32)> = (0..30).map(|i| ([0.5, 0.5], i)).collect();
    round_trip(
        &CompressedTree::new(&same).unwrap(),
        &[[0.5, 0.5], [0.0, 0.0]],
    );
    // Empty, and emptied.
    round_trip(&Comp::<3>::new(&[]).unwrap(), &[[0.0; 3]]);
    skip_round_trip(&Skip::<2>::new(&[]).unwrap(), &[[0.0; 2]]);
    let mut t = churned(&pts[..20], 10, 4);
    for (p, i) in &pts[..20] {
        t.remove(p, i);
    }
    assert!(t.is_empty());
    round_trip(&t, &[[0.5; 5]]);
}

/// Compressed and skip quadtrees over points whose root cube's far side rounds beyond
/// `f64::MAX`, fresh and after updates at the domain's corners: the domain stops at
/// `f64::MAX`, so the document holds no infinity and reads back the same tree.
#[test]
fn compressed_trees_over_points_beyond_f64_max_round_trip() {
    for pts in beyond_f64_max(34) {
        let qs = beyond_f64_max_queries(&pts);
        let mut t = CompressedTree::new(&pts).unwrap();
        check_domain_beyond_f64_max(&t, &pts);
        assert_numbers(
            &serde_json::to_value(&t).unwrap(),
            &["half_lo", "half_side", "domain_min", "domain_max"],
        );
        let back: Comp<3> = serde_json::from_str(&serde_json::to_string(&t).unwrap()).unwrap();
        assert_eq!(back.domain(), t.domain());
        round_trip(&t, &qs);
        let domain = *t.domain();
        t.insert(domain.max, 1000).unwrap();
        t.insert(domain.min, 1001).unwrap();
        assert!(t.remove(&pts[0].0, &pts[0].1));
        assert_eq!(*t.domain(), domain);
        round_trip(&t, &qs);
        let skip = SkipQuadtree::with_seed(t, 99);
        assert_numbers(
            &serde_json::to_value(&skip).unwrap()["base"],
            &["half_lo", "half_side", "domain_min", "domain_max"],
        );
        let back: Skip<3> = serde_json::from_str(&serde_json::to_string(&skip).unwrap()).unwrap();
        assert_eq!(back.domain(), skip.domain());
        skip_round_trip(&skip, &qs);
    }
}

#[test]
fn subdivisions_and_locators_round_trip() {
    let v = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0], [2.0, 2.0]];
    let e = vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 4], [4, 2]];
    let s = Subdivision::new(v, e).unwrap();
    let json = serde_json::to_string(&s).unwrap();
    let back: Subdivision = serde_json::from_str(&json).unwrap();
    assert_eq!((back.vertices(), back.edges()), (s.vertices(), s.edges()));
    assert_eq!(back.face_count(), s.face_count());
    let locator = PointLocator::new(s).unwrap();
    let back: PointLocator =
        serde_json::from_str(&serde_json::to_string(&locator).unwrap()).unwrap();
    assert_eq!(back.node_count(), locator.node_count());
    for x in 0..=8 {
        for y in 0..=8 {
            let q = [x as f64 * 0.55 - 0.2, y as f64 * 0.55 - 0.2];
            assert_eq!(back.locate(&q), locator.locate(&q), "{q:?}");
        }
    }
    let bad = |doc: &str| {
        serde_json::from_str::<Subdivision>(doc)
            .unwrap_err()
            .to_string()
    };
    let e = bad(r#"{"vertices":[[0,0],[1,0]],"edges":[[0,2]]}"#);
    assert!(e.contains("subdivision") && e.contains('2'), "{e}");
    let e = bad(r#"{"vertices":[[0,0],[1,0]],"edges":[[0,0]]}"#);
    assert!(e.contains("subdivision"), "{e}");
    let e = bad(r#"{"vertices":[[0,0],[0,0]],"edges":[[0,1]]}"#);
    assert!(e.contains("subdivision"), "{e}");
    let e = serde_json::from_str::<PointLocator>(
        r#"{"subdivision":{"vertices":[[0,0],[2,2],[0,2],[2,0]],"edges":[[0,1],[2,3],[0,2]]}}"#,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("subdivision") || e.contains("point locator"),
        "{e}"
    );
}

/// A churned 2D compressed tree as a JSON value, changed by `edit`, read back: the error.
fn corrupted(edit: impl FnOnce(&mut Value)) -> String {
    let pts = points::<2>(120, 20, 17);
    let mut v = serde_json::to_value(churned(&pts, 60, 20)).unwrap();
    edit(&mut v);
    match serde_json::from_value::<Comp<2>>(v) {
        Ok(_) => panic!("a corrupted document was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn corrupted_compressed_trees_are_refused_by_invariant() {
    let e = corrupted(|v| v["points"][3] = json!(1e300));
    assert!(e.contains("point 1") && e.contains("axis 1"), "{e}");
    let e = corrupted(|v| v["points"][0] = json!(-0.5));
    assert!(e.contains("point 0") && e.contains("axis 0"), "{e}");
    let e = corrupted(|v| {
        v["points"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("not whole points"), "{e}");
    let e = corrupted(|v| {
        v["items"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("items"), "{e}");
    let e = corrupted(|v| {
        v["order"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("slots in order"), "{e}");
    let e = corrupted(|v| v["order"][0] = json!(100_000));
    assert!(e.contains("holds slot 100000, out of range"), "{e}");
    let e = corrupted(|v| {
        let other = v["order"][1].clone();
        v["order"][0] = other;
    });
    assert!(e.contains("repeated") || e.contains("Morton order"), "{e}");
    let e = corrupted(|v| {
        v["order"].as_array_mut().unwrap().reverse();
    });
    assert!(e.contains("Morton order"), "{e}");
    let e = corrupted(|v| v["half_side"] = json!(-2.0));
    assert!(e.contains("root cube"), "{e}");
    let e = corrupted(|v| v["domain_min"][0] = json!(-1e9));
    assert!(e.contains("axis 0"), "{e}");
    let e = corrupted(|v| v["domain_max"] = json!([1.0]));
    assert!(e.contains("1 values for 2 dimensions"), "{e}");
    // A skip quadtree: its base is checked the same way.
    let pts = points::<2>(50, 20, 1);
    let mut v = serde_json::to_value(SkipQuadtree::with_seed(churned(&pts, 20, 20), 3)).unwrap();
    v["base"]["points"][1] = json!(f64::MAX);
    let e = serde_json::from_value::<Skip<2>>(v)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("compressed tree") && e.contains("point 0"),
        "{e}"
    );
}

proptest! {
    #![proptest_config(config(300, 0x5e7d_e002))]

    /// A mutated compressed tree or skip quadtree document is refused, or read back as a valid
    /// structure that answers queries and takes updates without a panic.
    #[test]
    fn mutated_compressed_documents_are_refused_or_valid(
        steps in prop::collection::vec((any::<u64>(), any::<u8>()), 1..4),
        skip in any::<bool>(),
    ) {
        let pts = points::<2>(40, 8, 23);
        let t = churned(&pts, 20, 8);
        let mut v = if skip {
            serde_json::to_value(SkipQuadtree::with_seed(t, 5)).unwrap()
        } else {
            serde_json::to_value(t).unwrap()
        };
        let done: Vec<String> = steps.iter().map(|&(at, kind)| mutate(&mut v, at, kind)).collect();
        let check = |t: &mut dyn FnMut([f64; 2], u32) -> bool| {
            pts.iter().all(|&(p, i)| t(p, i))
        };
        if skip {
            if let Ok(mut t) = serde_json::from_value::<Skip<2>>(v) {
                prop_assert!(t.validate().is_ok(), "{done:?}");
                prop_assert_eq!(t.k_nearest(&[1.0, 2.0], 3).unwrap().len(), t.len().min(3));
                prop_assert!(check(&mut |p, i| t.insert(p, i).is_err() || t.remove(&p, &i)));
                prop_assert!(t.validate().is_ok(), "{done:?}");
            }
        } else { if let Ok(mut t) = serde_json::from_value::<Comp<2>>(v) {
            prop_assert!(t.validate().is_ok(), "{done:?}");
            prop_assert_eq!(t.k_nearest(&[1.0, 2.0], 3).unwrap().len(), t.len().min(3));
            prop_assert!(check(&mut |p, i| t.insert(p, i).is_err() || t.remove(&p, &i)));
            prop_assert!(t.validate().is_ok(), "{done:?}");
        }}
    }
}
