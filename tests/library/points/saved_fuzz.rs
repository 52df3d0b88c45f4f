//! The saved-tree loader under corrupt input: every truncation of small files, and random byte
//! mutations (single bytes, runs of bytes, counts and words set to extremes) give an error or a
//! tree that validates and answers box and nearest queries as brute force over its own points
//! does; never a panic, never a wrong answer. The same for the borrowed view
//! (`PointTreeView`), which must open whenever the owned loader accepts (it checks a subset of
//! the owned tree's invariants: what the queries rely on). Headers claiming huge counts are
//! refused before anything is allocated.

use super::saved::check_against_brute;
use crate::common::points::config;
use orthtree::io::saved::{
    read_point_tree, read_point_tree_file, write_point_tree, PointTreeView, SavedError,
};
use orthtree::prelude::*;
use orthtree::{points::PointTreeBuilder, Connectivity, PointTree};
use proptest::prelude::*;

/// A small 2D tree with duplicates, points on split lines and a freed block, saved.
fn small_file(balanced: bool) -> (Vec<u8>, Vec<[f64; 2]>) {
    let mut pts: Vec<([f64; 2], u16)> = (0..60u16)
        .map(|i| ([(i % 8) as f64 / 4.0, (i / 8) as f64 / 4.0], i))
        .collect();
    pts.extend((60..66).map(|i| ([0.5, 0.5], i)));
    let mut t = PointTreeBuilder::new().bucket_size(3).build(&pts).unwrap();
    if balanced {
        t.balance(Connectivity::Face);
    } else {
        for (p, i) in &pts[40..52] {
            assert!(t.remove(p, i));
        }
    }
    let mut bytes = Vec::new();
    write_point_tree(&t, &mut bytes).unwrap();
    let qs = pts.iter().step_by(5).map(|p| p.0).collect();
    (bytes, qs)
}

/// Opens `bytes` as a view; a view that opens must validate and agree with brute force over its
/// own points.
fn view_and_check(bytes: &[u8], qs: &[[f64; 2]]) -> Result<(), SavedError> {
    let v = PointTreeView::<f64, u16, 2>::open(bytes)?;
    v.validate().unwrap();
    check_against_brute(&v, qs);
    let serial = PointTreeView::<f64, u16, 2>::open_serial(bytes).map(|s| s.len());
    assert_eq!(serial.ok(), Some(v.len()));
    Ok(())
}

/// Loads `bytes`; a tree that loads must validate and agree with brute force, and so must the
/// view, which opens whenever the tree loads. Returns the owned load's outcome.
fn load_and_check(bytes: &[u8], qs: &[[f64; 2]]) -> Result<(), SavedError> {
    let view = view_and_check(bytes, qs);
    let t: PointTree<f64, u16, 2> = read_point_tree(bytes)?;
    t.validate().unwrap();
    check_against_brute(&t, qs);
    assert!(view.is_ok(), "the tree loads, the view refuses: {view:?}");
    Ok(())
}

#[test]
fn every_truncation_is_refused() {
    for balanced in [false, true] {
        let (bytes, _) = small_file(balanced);
        for len in 0..bytes.len() {
            match read_point_tree::<f64, u16, 2>(&bytes[..len]) {
                Err(SavedError::Truncated { available, .. }) => {
                    assert_eq!(available, len as u64)
                }
                other => panic!("length {len}: {other:?}"),
            }
            match PointTreeView::<f64, u16, 2>::open(&bytes[..len]) {
                Err(SavedError::Truncated { available, .. }) => {
                    assert_eq!(available, len as u64)
                }
                other => panic!("view, length {len}: {other:?}"),
            }
        }
    }
    // A file cut short is refused the same way.
    let (bytes, _) = small_file(false);
    let path = std::env::temp_dir().join(format!("orthtree-cut-{}.bin", std::process::id()));
    std::fs::write(&path, &bytes[..bytes.len() - 16]).unwrap();
    let r = read_point_tree_file::<f64, u16, 2>(&path);
    std::fs::remove_file(&path).unwrap();
    assert!(matches!(r, Err(SavedError::Truncated { .. })));
}

#[test]
fn every_single_bit_flip_is_refused_or_harmless() {
    let (bytes, qs) = small_file(false);
    let mut loaded = 0;
    for at in 0..bytes.len() {
        for bit in 0..8 {
            let mut b = bytes.clone();
            b[at] ^= 1 << bit;
            if load_and_check(&b, &qs).is_ok() {
                loaded += 1;
            }
        }
    }
    // Item bits are unchecked (any u16 is an item); most other flips are caught.
    assert!(loaded < bytes.len() * 8 / 2, "{loaded} flips loaded");
}

#[test]
fn huge_counts_are_refused_before_allocation() {
    let (bytes, _) = small_file(false);
    for (offset, field) in [(32, "points"), (40, "node slots"), (48, "free blocks")] {
        for value in [u32::MAX as u64, (u32::MAX - 15) as u64, 1 + (1 << 20) * 4] {
            let mut b = bytes.clone();
            b[offset..offset + 8].copy_from_slice(&value.to_le_bytes());
            match read_point_tree::<f64, u16, 2>(&b) {
                Err(SavedError::Truncated { .. } | SavedError::Field { .. }) => {}
                other => panic!("{field} = {value}: {other:?}"),
            }
            match PointTreeView::<f64, u16, 2>::open(&b) {
                Err(SavedError::Truncated { .. } | SavedError::Field { .. }) => {}
                other => panic!("view, {field} = {value}: {other:?}"),
            }
        }
    }
}

/// A mutation: at a byte offset (taken modulo the length), one of several kinds.
fn mutation() -> impl Strategy<Value = (usize, u8, u64)> {
    (any::<usize>(), 0u8..5, any::<u64>())
}

fn apply(b: &mut [u8], (at, kind, value): (usize, u8, u64)) {
    let at = at % b.len();
    let end = (at + 8).min(b.len());
    match kind {
        0 => b[at] = value as u8,
        1 => b[at] ^= 1 << (value % 8),
        // a little-endian word set to an extreme or a random value
        2 => b[at..end].copy_from_slice(&u64::MAX.to_le_bytes()[..end - at]),
        3 => b[at..end].copy_from_slice(&value.to_le_bytes()[..end - at]),
        _ => b[at..end].fill(0),
    }
}

proptest! {
    #![proptest_config(config(2000, 0xf022_5a7e))]

    #[test]
    fn random_mutations_are_refused_or_harmless(
        mutations in proptest::collection::vec(mutation(), 1..5),
        balanced in any::<bool>(),
    ) {
        let (mut bytes, qs) = small_file(balanced);
        for m in mutations {
            apply(&mut bytes, m);
        }
        let _ = load_and_check(&bytes, &qs);
    }
}
