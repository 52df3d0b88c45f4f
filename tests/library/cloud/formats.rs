//! Round trips of clouds made in code through PLY (every encoding) and XYZ/CSV: every point
//! and every attribute comes back, integer coordinates and their frame included.

use crate::common::rng;
use orthtree::cloud::{Attributes, Cloud, Column, Frame};
use orthtree::io::ply::{self, Encoding};
use orthtree::io::xyz;
use rand::Rng;

/// A cloud of `n` random points with every kind of attribute.
pub fn full_cloud(seed: u64, n: usize) -> Cloud<f64> {
    let mut r = rng(seed);
    let points: Vec<[f64; 3]> = (0..n)
        .map(|_| {
            [
                r.gen_range(-5.0..5.0),
                r.gen_range(0.0..1.0),
                r.r#gen::<f64>() * 1e6,
            ]
        })
        .collect();
    let attributes = Attributes {
        intensity: Some((0..n).map(|_| r.r#gen()).collect()),
        classification: Some((0..n).map(|_| r.r#gen()).collect()),
        color: Some((0..n).map(|_| [r.r#gen(), r.r#gen(), r.r#gen()]).collect()),
        gps_time: Some((0..n).map(|_| r.gen_range(0.0..1e9)).collect()),
        normal: Some(
            (0..n)
                .map(|_| [r.r#gen(), r.r#gen(), -r.r#gen::<f32>()])
                .collect(),
        ),
        extra: vec![Column {
            name: "confidence".into(),
            values: (0..n).map(|_| r.gen_range(-1.0..1.0)).collect(),
        }],
    };
    Cloud {
        points,
        attributes,
        frame: Frame::IDENTITY,
    }
}

/// An integer cloud in a LAS-like frame.
pub fn integer_cloud(seed: u64, n: usize) -> Cloud<i32> {
    let mut r = rng(seed);
    let mut cloud = Cloud::from_points(
        (0..n)
            .map(|_| [r.r#gen(), r.gen_range(-1000..1000), r.gen_range(0..3)])
            .collect(),
    );
    cloud.frame = Frame {
        scale: [0.001, 0.01, 0.25],
        offset: [431_000.5, 5_112_000.0, -12.0],
    };
    cloud.attributes.intensity = Some((0..n).map(|i| i as u16).collect());
    cloud
}

fn ply_round_trip<S: orthtree::Scalar>(cloud: &Cloud<S>, encoding: Encoding) -> Cloud<S> {
    let mut bytes = Vec::new();
    ply::write(cloud, encoding, &mut bytes).unwrap();
    ply::read(&bytes[..]).unwrap()
}

#[test]
fn ply_keeps_every_point_and_attribute() {
    for (seed, n) in [(1, 0), (2, 1), (3, 500)] {
        let cloud = full_cloud(seed, n);
        for encoding in [
            Encoding::Ascii,
            Encoding::BinaryLittleEndian,
            Encoding::BinaryBigEndian,
        ] {
            assert_eq!(
                ply_round_trip(&cloud, encoding),
                cloud,
                "{encoding:?}, n = {n}"
            );
        }
    }
}

#[test]
fn ply_keeps_integer_coordinates_and_their_frame() {
    let cloud = integer_cloud(4, 300);
    for encoding in [Encoding::Ascii, Encoding::BinaryLittleEndian] {
        let back = ply_round_trip(&cloud, encoding);
        assert_eq!(back, cloud);
    }
    let mut text = Vec::new();
    ply::write(&cloud, Encoding::Ascii, &mut text).unwrap();
    let text = String::from_utf8(text).unwrap();
    assert!(text.contains("property int x"), "{text:.200}");
    assert!(text.contains("comment orthtree frame 0.001 0.01 0.25 431000.5 5112000 -12"));
}

#[test]
fn ply_coordinates_that_do_not_fit_the_type_are_refused() {
    let cloud = Cloud::from_points(vec![[0.0, 1.5, 2.0]]);
    let mut bytes = Vec::new();
    ply::write(&cloud, Encoding::Ascii, &mut bytes).unwrap();
    let err = ply::read::<i32>(&bytes[..]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "PLY vertex 0: y = 1.5 is not a finite value that i32 holds exactly"
    );
}

#[test]
fn ply_of_other_programs_reads_with_its_8_bit_colours_and_extra_properties() {
    let text = "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nelement vertex 2\r\n\
                property float x\r\nproperty float y\r\nproperty float z\r\n\
                property uchar red\r\nproperty uchar green\r\nproperty uchar blue\r\n\
                property uchar alpha\r\nelement face 0\r\nproperty list uchar int vertex_indices\r\n\
                end_header\r\n0 0 0 255 0 0 255\r\n1.5 -2 3e2 0 128 7 9\r\n";
    let cloud: Cloud<f32> = ply::read(text.as_bytes()).unwrap();
    assert_eq!(cloud.points, [[0.0, 0.0, 0.0], [1.5, -2.0, 300.0]]);
    assert_eq!(cloud.attributes.color, Some(vec![[255, 0, 0], [0, 128, 7]]));
    assert_eq!(
        cloud.attributes.extra_column("alpha"),
        Some(&[255.0, 9.0][..])
    );
    assert_eq!(ply_round_trip(&cloud, Encoding::BinaryLittleEndian), cloud);
}

#[test]
fn xyz_keeps_every_point_and_attribute() {
    for (seed, n) in [(5, 0), (6, 1), (7, 400)] {
        let cloud = full_cloud(seed, n);
        let mut text = Vec::new();
        xyz::write(&cloud, &mut text).unwrap();
        let back: Cloud<f64> = xyz::read(&text[..]).unwrap();
        if n == 0 {
            assert!(back.is_empty());
        } else {
            assert_eq!(back, cloud);
        }
    }
}

#[test]
fn xyz_without_names_reads_three_coordinates_and_extra_columns() {
    let text = "# x y z and two more\n1 2 3 4 5\n\n6,7,8,9,10 # trailing comment\n";
    let cloud: Cloud<i64> = xyz::read(text.as_bytes()).unwrap();
    assert_eq!(cloud.points, [[1, 2, 3], [6, 7, 8]]);
    assert_eq!(cloud.attributes.names(), ["column4", "column5"]);
    assert_eq!(
        cloud.attributes.extra_column("column5"),
        Some(&[5.0, 10.0][..])
    );
}

#[test]
fn xyz_lines_end_in_lf_crlf_or_cr_alike() {
    let lines = ["x,y,z,intensity", "1,2,3,7", "# a comment", "", "4,5,6,8"];
    let want: Cloud<f64> = xyz::read(lines.join("\n").as_bytes()).unwrap();
    assert_eq!(want.points, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
    for end in ["\r\n", "\r", "\n\r"] {
        for last in ["", end] {
            let text = lines.join(end) + last;
            let got: Cloud<f64> = xyz::read(text.as_bytes()).unwrap();
            assert_eq!(got, want, "{text:?}");
        }
    }
    // Without names, CR alone: three points of three coordinates, no extra column.
    let cloud: Cloud<f64> = xyz::read("1 2 3\r4 5 6\r7 8 9\r".as_bytes()).unwrap();
    assert_eq!(cloud.points.len(), 3);
    assert!(cloud.attributes.names().is_empty());
    // A CR counts as a line end in the line numbers of errors.
    let err = xyz::read::<f64>("1 2 3\r4 five 6\r".as_bytes()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "XYZ line 2, field 2: \"five\" is not a number"
    );
}

#[test]
fn a_cloud_read_from_ply_builds_a_tree_that_finds_every_point() {
    use orthtree::prelude::*;
    let cloud = ply_round_trip(&integer_cloud(8, 200), Encoding::BinaryLittleEndian);
    let tree = orthtree::PointTree::new(&cloud.entries().unwrap()).unwrap();
    tree.validate().unwrap();
    for (i, p) in cloud.points.iter().enumerate() {
        let found: Vec<u32> = tree
            .in_box(&orthtree::Aabb { min: *p, max: *p })
            .unwrap()
            .map(|(_, item)| *item)
            .collect();
        assert!(found.contains(&(i as u32)), "point {i} at {p:?}");
    }
}
