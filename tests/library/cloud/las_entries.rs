//! `io::las::read_entries` and its stream `LasEntries`, the coordinates-only LAS readers behind
//! indexing a file (in memory and out of core): the same
//! world coordinates as the full reader (`las::read` then `Cloud::world_points`), paired with
//! their record numbers, for legacy and extended formats with extra bytes and for block
//! boundaries; the tree built from them equals the tree of the full read; truncated files,
//! lying headers and compressed files are refused.

use crate::common::rng;
use orthtree::cloud::{Cloud, Frame};
use orthtree::io::las::{self, LasError};
use orthtree::iter::LasEntries;
use orthtree::points::PointTreeBuilder;
use orthtree::PointSet;
use rand::Rng;
use std::path::PathBuf;

/// A file in the system's temporary folder, removed when dropped.
struct TempFile(PathBuf);

impl TempFile {
    fn new(name: &str, bytes: &[u8]) -> TempFile {
        let path = std::env::temp_dir().join(format!("orthtree-{}-{name}", std::process::id()));
        std::fs::write(&path, bytes).unwrap();
        TempFile(path)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// A cloud of `n` points with a frame, and (when `extended`) the columns that need format 6-8.
fn cloud(seed: u64, n: usize, extended: bool) -> Cloud<i32> {
    let mut r = rng(seed);
    let mut c = Cloud::from_points(
        (0..n)
            .map(|i| match i % 5 {
                // extremes and copies beside random points
                0 => [i32::MIN, i32::MAX, 0],
                1 => [7, 7, 7],
                _ => [r.r#gen(), r.r#gen(), r.gen_range(-100..100)],
            })
            .collect(),
    );
    c.frame = Frame {
        scale: [0.01, 0.01, 0.001],
        offset: [600_000.0, 5_000_000.0, 100.0],
    };
    if extended {
        c.attributes.gps_time = Some((0..n).map(|i| i as f64).collect());
        c.attributes.extra.push(orthtree::cloud::Column {
            name: "scan_angle".into(),
            values: vec![3.0; n],
        });
    }
    c
}

fn bytes(cloud: &Cloud<i32>, compressed: bool) -> Vec<u8> {
    las::write_to(cloud, std::io::Cursor::new(Vec::new()), compressed)
        .unwrap()
        .into_inner()
}

#[test]
fn entries_are_the_full_reads_world_points_in_file_order() {
    // 4 MiB blocks hold 209 715 records of 20 bytes: sizes around one block
    for (n, extended) in [
        (0, false),
        (1, true),
        (500, true),
        (209_715, false),
        (209_716, false),
    ] {
        let c = cloud(n as u64, n, extended);
        let file = TempFile::new(&format!("entries-{n}.las"), &bytes(&c, false));
        let entries = las::read_entries(&file.0).unwrap();
        let world = las::read(&file.0).unwrap().world_points();
        assert_eq!(entries.len(), n);
        for (i, ((p, item), w)) in entries.iter().zip(&world).enumerate() {
            assert_eq!((p, *item as usize), (w, i), "n {n}, record {i}");
        }
        let stream = LasEntries::open(&file.0).unwrap();
        assert_eq!(stream.point_count(), n);
        let streamed: Vec<([f64; 3], u32)> = stream.map(Result::unwrap).collect();
        assert_eq!(
            streamed, entries,
            "n {n}: the stream reads what the whole read does"
        );
    }
}

#[test]
fn the_tree_of_the_entries_is_the_tree_of_the_full_read() {
    let c = cloud(9, 3000, false);
    let file = TempFile::new("tree.las", &bytes(&c, false));
    let entries = las::read_entries(&file.0).unwrap();
    let full: Vec<([f64; 3], u32)> = las::read(&file.0)
        .unwrap()
        .world_points()
        .into_iter()
        .zip(0..)
        .collect();
    let (a, b) = (
        PointTreeBuilder::new().par_build(&entries).unwrap(),
        PointTreeBuilder::new().build(&full).unwrap(),
    );
    a.validate().unwrap();
    assert_eq!(a.items(), b.items());
    assert_eq!(a.points(), b.points());
    assert_eq!(a.leaf_count(), b.leaf_count());
}

#[test]
fn a_truncated_file_names_the_first_missing_point() {
    let b = bytes(&cloud(6, 100, false), false);
    let cut = b.len() - 20 * 40 - 7; // 59 whole records of 20 bytes and part of the 60th
    let file = TempFile::new("cut.las", &b[..cut]);
    match las::read_entries(&file.0).unwrap_err() {
        LasError::Truncated {
            point,
            count,
            length,
        } => assert_eq!((point, count, length), (59, 100, cut as u64)),
        other => panic!("{other}"),
    }
    match LasEntries::open(&file.0).map(|_| ()).unwrap_err() {
        LasError::Truncated { point, .. } => assert_eq!(point, 59),
        other => panic!("{other}"),
    }
}

#[test]
fn a_header_claiming_billions_of_points_is_refused_before_allocating() {
    let mut b = bytes(&cloud(7, 10, false), false);
    // LAS 1.4: the legacy count (u32 at 107) and the 64-bit count (u64 at 247)
    b[107..111].copy_from_slice(&0u32.to_le_bytes());
    b[247..255].copy_from_slice(&(3_000_000_000u64).to_le_bytes());
    let file = TempFile::new("claims.las", &b);
    match las::read_entries(&file.0).unwrap_err() {
        LasError::Truncated {
            point: 10, count, ..
        } => assert_eq!(count, 3_000_000_000),
        other => panic!("{other}"),
    }
    b[247..255].copy_from_slice(&(u64::MAX / 2).to_le_bytes());
    let file = TempFile::new("claims-more.las", &b);
    let message = las::read_entries(&file.0).unwrap_err().to_string();
    assert!(message.contains("at most 4294967294"), "{message}");
    let message = LasEntries::open(&file.0).map(|_| ()).unwrap_err();
    assert!(
        message.to_string().contains("at most 4294967294"),
        "{message}"
    );
}

#[cfg(feature = "laz")]
#[test]
fn compressed_files_are_refused_for_the_full_reader() {
    let file = TempFile::new("compressed.laz", &bytes(&cloud(8, 50, false), true));
    assert!(matches!(
        las::read_entries(&file.0).unwrap_err(),
        LasError::UnsupportedFormat(_)
    ));
}

/// A scale factor of 0 read by the coordinates-only readers: refused with the field, as the
/// full reader refuses it, not turned into points that all share one coordinate.
#[test]
fn a_zero_scale_is_refused_by_the_coordinates_readers_too() {
    let mut b = bytes(&cloud(15, 6, false), false);
    b[139..147].copy_from_slice(&0.0f64.to_le_bytes());
    let file = TempFile::new("zero-scale.las", &b);
    for err in [
        las::read(&file.0).map(|_| ()).unwrap_err(),
        las::read_entries(&file.0).map(|_| ()).unwrap_err(),
        LasEntries::open(&file.0).map(|_| ()).unwrap_err(),
    ] {
        match err {
            LasError::Field {
                field: "y scale factor",
                offset: 139,
                ..
            } => {}
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn a_header_the_full_reader_refuses_is_refused_here_too() {
    let good = bytes(&cloud(14, 6, false), false);
    // the point data said to start inside the header (its bytes would be taken for points),
    // and a version without point format 0
    let mut inside = good.clone();
    inside[96..100].copy_from_slice(&16u32.to_le_bytes());
    let mut version = good.clone();
    version[25] = 15;
    for (name, b) in [("inside", inside), ("version", version)] {
        let file = TempFile::new(&format!("refused-{name}.las"), &b);
        assert!(las::read(&file.0).is_err(), "{name}");
        match las::read_entries(&file.0) {
            Err(LasError::Las { point: None, .. }) => {}
            other => panic!("{name}: {other:?}"),
        }
        assert!(LasEntries::open(&file.0).is_err(), "{name}");
    }
}
