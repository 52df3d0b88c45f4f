//! LAS (and LAZ) round trips of clouds made in code: LAS -> cloud -> LAS, LAS -> PLY -> LAS
//! and LAS -> tree -> cloud keep every point, its integer coordinates, the frame and every
//! field; the LAZ read equals the LAS read; truncated files and lying headers are refused.

use crate::common::rng;
use orthtree::cloud::{Cloud, Column, Frame};
use orthtree::io::las::{self, LasError};
use orthtree::io::ply::{self, Encoding};
use orthtree::{PointSet, PointTree};
use rand::Rng;
use std::io::Cursor;

fn column(name: &str, values: Vec<f64>) -> Column {
    Column {
        name: name.into(),
        values,
    }
}

/// A cloud with every field of a legacy (0-3) or an extended (6-8) point format.
fn las_cloud(seed: u64, n: usize, extended: bool) -> Cloud<i32> {
    let mut r = rng(seed);
    let mut c = Cloud::from_points(
        (0..n)
            .map(|_| [r.r#gen(), r.r#gen(), r.gen_range(-100..100)])
            .collect(),
    );
    c.frame = Frame {
        scale: [0.01, 0.01, 0.001],
        offset: [600_000.0, 5_000_000.0, 100.0],
    };
    let a = &mut c.attributes;
    a.intensity = Some((0..n).map(|_| r.r#gen()).collect());
    let max_class = if extended { 255 } else { 31 };
    a.classification = Some((0..n).map(|_| r.gen_range(0..=max_class)).collect());
    a.gps_time = Some((0..n).map(|_| r.gen_range(0.0..1e6)).collect());
    a.color = Some((0..n).map(|_| [r.r#gen(), r.r#gen(), r.r#gen()]).collect());
    let returns = if extended { 15.0 } else { 7.0 };
    let mut int = |max: f64| {
        (0..n)
            .map(|_| r.gen_range(0.0..=max).floor())
            .collect::<Vec<f64>>()
    };
    let mut extra = vec![
        column("return_number", int(returns)),
        column("number_of_returns", int(returns)),
        column("scan_direction", int(1.0)),
        column("edge_of_flight_line", int(1.0)),
        column("synthetic", int(1.0)),
        column("key_point", int(1.0)),
        column("withheld", int(1.0)),
    ];
    if extended {
        extra.push(column("overlap", int(1.0)));
        extra.push(column("scanner_channel", int(3.0)));
        extra.push(column(
            "scan_angle",
            int(60000.0).iter().map(|v| v - 30000.0).collect(),
        ));
    } else {
        extra.push(column(
            "scan_angle_rank",
            int(180.0).iter().map(|v| v - 90.0).collect(),
        ));
    }
    extra.push(column("user_data", int(255.0)));
    extra.push(column("point_source_id", int(65535.0)));
    if extended {
        extra.push(column("nir", int(65535.0)));
    }
    extra.push(column("extra_byte_0", int(255.0)));
    extra.push(column("extra_byte_1", int(255.0)));
    a.extra = extra;
    c
}

fn to_las(cloud: &Cloud<i32>, compressed: bool) -> Vec<u8> {
    las::write_to(cloud, Cursor::new(Vec::new()), compressed)
        .unwrap()
        .into_inner()
}

fn from_las(bytes: Vec<u8>) -> Result<Cloud<i32>, LasError> {
    las::read_from(Cursor::new(bytes))
}

#[test]
fn las_keeps_every_point_and_field() {
    for extended in [false, true] {
        for n in [0, 1, 700] {
            let cloud = las_cloud(n as u64, n, extended);
            let back = from_las(to_las(&cloud, false)).unwrap();
            if n == 0 {
                assert!(back.is_empty());
                continue;
            }
            assert_eq!(back, cloud, "extended {extended}, n = {n}");
        }
    }
}

#[test]
fn las_through_ply_and_back_is_the_same_file_content() {
    for extended in [false, true] {
        let cloud = las_cloud(3, 300, extended);
        let first = from_las(to_las(&cloud, false)).unwrap();
        let mut bytes = Vec::new();
        ply::write(&first, Encoding::BinaryLittleEndian, &mut bytes).unwrap();
        let via_ply: Cloud<i32> = ply::read(&bytes[..]).unwrap();
        assert_eq!(via_ply, first);
        assert_eq!(from_las(to_las(&via_ply, false)).unwrap(), first);
    }
}

#[test]
fn las_through_a_tree_keeps_every_point_with_its_fields() {
    let cloud = from_las(to_las(&las_cloud(4, 500, true), false)).unwrap();
    let tree = PointTree::new(&cloud.entries().unwrap()).unwrap();
    tree.validate().unwrap();
    // the cloud in the tree's order, then back in the input order by the items
    let order: Vec<usize> = tree.items().iter().map(|&i| i as usize).collect();
    let in_tree = cloud.select(&order);
    for (s, p) in in_tree.points.iter().enumerate() {
        assert_eq!(tree.point(s), p);
    }
    let mut back_order = vec![0; order.len()];
    for (s, &i) in order.iter().enumerate() {
        back_order[i] = s;
    }
    assert_eq!(in_tree.select(&back_order), cloud);
}

#[cfg(feature = "laz")]
#[test]
fn the_laz_read_equals_the_las_read() {
    for extended in [false, true] {
        let cloud = las_cloud(5, 2000, extended);
        let las = from_las(to_las(&cloud, false)).unwrap();
        let laz_bytes = to_las(&cloud, true);
        assert!(laz_bytes.len() < to_las(&cloud, false).len());
        assert_eq!(from_las(laz_bytes).unwrap(), las);
    }
}

#[test]
fn a_truncated_file_names_the_first_missing_point() {
    let cloud = las_cloud(6, 100, false);
    let bytes = to_las(&cloud, false);
    let record = 34 + 2; // format 3 and two extra bytes
    let cut = bytes.len() - record * 40 - 7; // 59 whole points and a part of the 60th
    match from_las(bytes[..cut].to_vec()).unwrap_err() {
        LasError::Truncated {
            point,
            count,
            length,
        } => {
            assert_eq!((point, count, length), (59, 100, cut as u64))
        }
        other => panic!("{other}"),
    }
}

#[test]
fn a_header_claiming_billions_of_points_allocates_by_the_data() {
    let cloud = las_cloud(7, 10, false);
    let mut bytes = to_las(&cloud, false);
    // LAS 1.4: the legacy count (u32 at 107) and the 64-bit count (u64 at 247)
    bytes[107..111].copy_from_slice(&u32::MAX.to_le_bytes());
    bytes[247..255].copy_from_slice(&(u64::MAX / 2).to_le_bytes());
    match from_las(bytes) {
        Err(LasError::Truncated { point: 10, .. }) | Err(LasError::Las { .. }) => {}
        other => panic!("{other:?}"),
    }
}

#[test]
fn columns_las_cannot_hold_are_refused_by_name() {
    let mut cloud = las_cloud(8, 5, false);
    cloud
        .attributes
        .extra
        .push(column("confidence", vec![0.5; 5]));
    let err = las::write_to(&cloud, Cursor::new(Vec::new()), false).unwrap_err();
    assert_eq!(
        err.to_string(),
        "LAS: column confidence has no field in a LAS point record"
    );
    let mut cloud = las_cloud(8, 5, false);
    cloud.attributes.extra[0].values[3] = 9.0; // return number above 7
    let err = las::write_to(&cloud, Cursor::new(Vec::new()), false).unwrap_err();
    assert_eq!(
        err.to_string(),
        "LAS point 3: return_number = 9 does not fit its field"
    );
}
