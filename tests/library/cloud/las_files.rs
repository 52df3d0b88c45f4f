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

/// `bytes[at..at + N]` set to `value`'s little-endian bytes.
fn put<const N: usize>(bytes: &mut [u8], at: usize, value: [u8; N]) {
    bytes[at..at + N].copy_from_slice(&value);
}

/// The error of reading `bytes`, which must name header field `field` at byte `offset`.
fn assert_field(bytes: Vec<u8>, field: &str, offset: usize) {
    match from_las(bytes) {
        Err(LasError::Field {
            field: f,
            offset: o,
            ..
        }) if f == field && o == offset as u64 => {}
        other => panic!("expected {field} at {offset}: {other:?}"),
    }
}

#[test]
fn a_point_count_whose_records_end_beyond_64_bits_is_refused_by_field() {
    // 2^64 - 1 records of 36 bytes: the end of the records overflows (the las crate's own
    // arithmetic would)
    let mut bytes = to_las(&las_cloud(9, 3, false), false);
    put(&mut bytes, 107, 0u32.to_le_bytes());
    put(&mut bytes, 247, u64::MAX.to_le_bytes());
    assert_field(bytes.clone(), "number of point records", 247);
    let err = from_las(bytes).unwrap_err().to_string();
    assert!(err.contains("byte offset 247"), "{err}");
}

/// A frame that gives no world coordinates: a scale factor of 0, NaN or infinity, or an
/// offset that is not finite, on each axis (scales from byte 131, offsets from byte 155).
#[test]
fn a_scale_of_zero_or_a_non_finite_frame_is_refused_by_field() {
    let good = to_las(&las_cloud(12, 3, false), false);
    for (a, axis) in ["x", "y", "z"].into_iter().enumerate() {
        for bad in [0.0, -0.0, f64::NAN, f64::INFINITY] {
            let mut bytes = good.clone();
            put(&mut bytes, 131 + 8 * a, bad.to_le_bytes());
            assert_field(bytes, &format!("{axis} scale factor"), 131 + 8 * a);
        }
        for bad in [f64::NAN, f64::NEG_INFINITY] {
            let mut bytes = good.clone();
            put(&mut bytes, 155 + 8 * a, bad.to_le_bytes());
            assert_field(bytes, &format!("{axis} offset"), 155 + 8 * a);
        }
    }
    // a negative scale is a frame like any other
    let mut bytes = good;
    put(&mut bytes, 131, (-0.01f64).to_le_bytes());
    assert!(from_las(bytes).is_ok());
}

/// The writer refuses the frames the readers refuse, naming the header field, so that it never
/// writes a file it cannot read back.
#[test]
fn a_frame_the_readers_refuse_is_not_written() {
    let zero_z_scale = Frame {
        scale: [0.01, 0.01, 0.0],
        offset: [0.0; 3],
    };
    let nan_x_offset = Frame {
        scale: [0.01; 3],
        offset: [f64::NAN, 0.0, 0.0],
    };
    for (frame, field, offset) in [
        (zero_z_scale, "z scale factor", 147),
        (nan_x_offset, "x offset", 155),
    ] {
        let mut cloud = las_cloud(13, 3, false);
        cloud.frame = frame;
        match las::write_to(&cloud, Cursor::new(Vec::new()), false) {
            Err(LasError::Field {
                field: f,
                offset: o,
                ..
            }) if f == field && o == offset => {}
            other => panic!("expected {field} at {offset}: {:?}", other.map(|_| ())),
        }
    }
}

#[test]
fn an_evlr_longer_than_the_file_is_refused_before_it_is_allocated() {
    let mut bytes = to_las(&las_cloud(10, 3, false), false);
    let start = bytes.len();
    // one EVLR header (60 bytes) claiming 2^40 bytes of data, none of which follow
    let mut evlr = vec![0u8; 60];
    evlr[20..28].copy_from_slice(&(1u64 << 40).to_le_bytes());
    bytes.extend_from_slice(&evlr);
    put(&mut bytes, 235, (start as u64).to_le_bytes());
    put(&mut bytes, 243, 1u32.to_le_bytes());
    assert_field(bytes.clone(), "EVLR record length", start + 20);
    // and one starting past the end of the file
    put(&mut bytes, 235, (1u64 << 50).to_le_bytes());
    assert_field(bytes, "start of first EVLR", 235);
}

/// The byte offset of the data of the LASzip VLR of `bytes` (a LAZ file by `to_las`).
fn laszip_data(bytes: &[u8]) -> usize {
    let id = bytes
        .windows(14)
        .position(|w| w == b"laszip encoded")
        .expect("a LAZ file has the LASzip VLR");
    id - 2 + 54
}

#[test]
fn a_laz_chunk_table_claiming_more_chunks_than_bytes_is_refused() {
    let mut bytes = to_las(&las_cloud(11, 50, false), true);
    let data = u32::from_le_bytes(bytes[96..100].try_into().unwrap()) as usize;
    let table = i64::from_le_bytes(bytes[data..data + 8].try_into().unwrap()) as usize;
    // 2^32 - 1 chunks: the laz crate would reserve 64 GiB for their entries
    put(&mut bytes, table + 4, u32::MAX.to_le_bytes());
    assert_field(bytes, "LAZ chunk count", table + 4);
}

#[test]
fn laszip_items_other_than_the_point_formats_are_refused() {
    for extended in [false, true] {
        let mut bytes = to_las(&las_cloud(12, 5, extended), true);
        let vlr = laszip_data(&bytes);
        // no items at all (the laz crate's decoder panics on those), then a wrong size
        let mut none = bytes.clone();
        put(&mut none, vlr + 32, 0u16.to_le_bytes());
        assert_field(none, "LASzip items", vlr + 32);
        put(&mut bytes, vlr + 34 + 2, 7u16.to_le_bytes());
        assert_field(bytes, "LASzip items", vlr + 32);
    }
}

#[test]
fn a_laz_layer_longer_than_the_file_is_refused_before_it_is_allocated() {
    // formats 6-8 compress in layers whose byte counts follow each chunk's first record and
    // point count; the laz crate allocates a layer's count before reading it
    let bytes = to_las(&las_cloud(13, 40, true), true);
    let data = u32::from_le_bytes(bytes[96..100].try_into().unwrap()) as usize;
    let record = u16::from_le_bytes(bytes[105..107].try_into().unwrap()) as usize;
    let sizes = data + 8 + record + 4;
    for layer in [0, 3] {
        let mut b = bytes.clone();
        put(&mut b, sizes + 4 * layer, u32::MAX.to_le_bytes());
        assert_field(b, "LAZ layer size", sizes + 4 * layer);
    }
    // the unchanged file still reads
    assert_eq!(from_las(bytes).unwrap().len(), 40);
}

#[test]
fn a_point_wise_laz_file_with_layered_items_has_its_layers_checked_too() {
    // the laz crate picks the layered decoder by the items' version, whatever the compressor
    // says: a point-wise file (compressor 1: one chunk from the first byte of the point data,
    // no chunk table) of format 6-8 items is read in layers as well
    let mut bytes = to_las(&las_cloud(17, 40, true), true);
    let vlr = laszip_data(&bytes);
    put(&mut bytes, vlr, 1u16.to_le_bytes());
    let data = u32::from_le_bytes(bytes[96..100].try_into().unwrap()) as usize;
    let record = u16::from_le_bytes(bytes[105..107].try_into().unwrap()) as usize;
    let sizes = data + record + 4;
    put(&mut bytes, sizes, u32::MAX.to_le_bytes());
    assert_field(bytes, "LAZ layer size", sizes);
}

#[test]
fn a_laz_chunk_table_outside_the_file_is_refused() {
    // where the laz crate reads points after failing to read its table depends on how far its
    // seeks moved the input (past the end of a file, a seek to 2^63 fails and leaves the input
    // 8 bytes further on, so every layer count is read from the wrong place)
    let mut bytes = to_las(&las_cloud(18, 40, true), true);
    let data = u32::from_le_bytes(bytes[96..100].try_into().unwrap()) as usize;
    let end = bytes.len();
    put(&mut bytes, data, i64::MAX.to_le_bytes());
    put(&mut bytes, end - 8, 0i64.to_le_bytes());
    assert_field(bytes.clone(), "offset to the LAZ chunk table", data);
    let file = std::env::temp_dir().join(format!("orthtree-laz-table-{}.laz", std::process::id()));
    std::fs::write(&file, &bytes).unwrap();
    let err = las::read(&file).unwrap_err();
    std::fs::remove_file(&file).unwrap();
    assert!(matches!(err, LasError::Field { .. }), "{err:?}");
}
