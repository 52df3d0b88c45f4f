//! Bad and truncated point files: each refused with a typed error naming the line, field or byte
//! offset; a header's vertex count is never trusted for memory; random bytes never panic.

use orthtree::cloud::Cloud;
use orthtree::io::ply::{self, Encoding, PlyError};
use orthtree::io::xyz::{self, XyzError};
use proptest::prelude::*;

fn header(format: &str, count: &str) -> String {
    format!(
        "ply\nformat {format} 1.0\nelement vertex {count}\nproperty float x\nproperty float y\n\
         property float z\nend_header\n"
    )
}

#[test]
fn a_truncated_binary_body_names_the_vertex_and_byte_offset() {
    let mut bytes = header("binary_little_endian", "3").into_bytes();
    let start = bytes.len() as u64;
    bytes.extend_from_slice(&[0u8; 12 + 5]); // one vertex and 5 bytes of the next
    match ply::read::<f32>(&bytes[..]).unwrap_err() {
        PlyError::Truncated {
            vertex,
            count,
            offset,
        } => assert_eq!((vertex, count, offset), (1, 3, start + 17)),
        other => panic!("{other}"),
    }
}

#[test]
fn a_huge_vertex_count_allocates_nothing_before_the_data() {
    // 18446744073709551615 vertices claimed, none given: refused at once, nothing reserved
    let bytes = header("binary_little_endian", &u64::MAX.to_string()).into_bytes();
    let err = ply::read::<f64>(&bytes[..]).unwrap_err();
    assert!(
        matches!(err, PlyError::Truncated { vertex: 0, .. }),
        "{err}"
    );
}

#[test]
fn ascii_errors_name_line_and_field() {
    let text = header("ascii", "2") + "1 2 3\n4 x 6\n";
    let err = ply::read::<f64>(text.as_bytes()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "PLY line 9, field 2 (y): \"x\" is not a valid value"
    );
    let text = header("ascii", "1") + "1 2\n";
    let err = ply::read::<f64>(text.as_bytes()).unwrap_err();
    assert!(matches!(
        err,
        PlyError::FieldCount {
            line: 8,
            found: 2,
            expected: 3
        }
    ));
    let text = header("ascii", "1") + "1 2 3\n4 5 6\n";
    let err = ply::read::<f64>(text.as_bytes()).unwrap_err();
    assert!(matches!(err, PlyError::TrailingData { .. }), "{err}");
}

#[test]
fn header_errors_name_the_line() {
    let cases = [
        ("plx\n", 1),
        ("ply\nformat ascii 2.0\nend_header\n", 2),
        (
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
            4,
        ),
        ("ply\nformat ascii 1.0\nelement face 3\nend_header\n", 3),
        (
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar int x\nend_header\n",
            4,
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n",
            5,
        ),
        ("ply\nformat ascii 1.0\n", 3),
    ];
    for (text, line) in cases {
        match ply::read::<f64>(text.as_bytes()).unwrap_err() {
            PlyError::Header { line: l, message } => assert_eq!(l, line, "{text:?}: {message}"),
            other => panic!("{text:?}: {other}"),
        }
    }
    let no_z =
        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nend_header\n";
    assert!(matches!(
        ply::read::<f64>(no_z.as_bytes()).unwrap_err(),
        PlyError::MissingProperty { name: "z" }
    ));
    let endless = "ply\n".to_string() + &"comment\n".repeat(10_000);
    assert!(matches!(
        ply::read::<f64>(endless.as_bytes()).unwrap_err(),
        PlyError::HeaderTooLong { .. }
    ));
}

#[test]
fn out_of_range_attributes_are_refused_not_clamped() {
    let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
                property float z\nproperty int intensity\nend_header\n0 0 0 70000\n";
    let err = ply::read::<f64>(text.as_bytes()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "PLY vertex 0: intensity = 70000 is not an integer from 0 to 65535"
    );
}

#[test]
fn xyz_errors_name_line_and_field() {
    let err = xyz::read::<f64>("x y z\n1 2 3\n4 5\n".as_bytes()).unwrap_err();
    assert!(matches!(
        err,
        XyzError::FieldCount {
            line: 3,
            found: 2,
            expected: 3
        }
    ));
    let err = xyz::read::<f64>("a b c\n".as_bytes()).unwrap_err();
    assert!(matches!(err, XyzError::MissingColumn { name: "x" }));
    let err = xyz::read::<i32>("1 2 3.5\n".as_bytes()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "XYZ line 1, field 3 (z): \"3.5\" is not a finite value that i32 holds exactly"
    );
    // the field's own text, not what it parsed to; attributes name their range
    let err = xyz::read::<f64>("1e400 2 3\n".as_bytes()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "XYZ line 1, field 1 (x): \"1e400\" is not a finite value that f64 holds exactly"
    );
    let err =
        xyz::read::<f64>("x,y,z,classification\n1,2,3,7\n1,2,3,256\n".as_bytes()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "XYZ line 3, field 4 (classification): \"256\" is not an integer from 0 to 255"
    );
    let err = xyz::read::<f64>(&b"1 2 3\n1 2 \xff\n"[..]).unwrap_err();
    assert!(matches!(err, XyzError::BadLine { line: 2 }));
}

#[test]
fn xyz_refuses_a_first_line_of_separators_alone() {
    // a line of commas is no blank line, but it has no field: the first column was read from
    // an empty list
    for text in [",", ",,\n1,2,3\n", "# names\n , \t,\n"] {
        let err = xyz::read::<f64>(text.as_bytes()).unwrap_err();
        assert!(
            matches!(err, XyzError::MissingColumn { name: "x" }),
            "{err:?}"
        );
    }
    // after the first line, such a line is a line with no fields
    let err = xyz::read::<f64>("1,2,3\n,,\n".as_bytes()).unwrap_err();
    assert!(matches!(
        err,
        XyzError::FieldCount {
            line: 2,
            found: 0,
            expected: 3
        }
    ));
}

#[test]
fn xyz_refuses_a_line_longer_than_the_limit_without_holding_the_file() {
    // A line of exactly the limit (its end not counted) is read, one byte more is refused.
    let line = |len: usize| format!("1 2 3{}", " ".repeat(len - 5));
    let cloud = xyz::read::<f64>(format!("4 5 6\r{}\r", line(xyz::MAX_LINE_BYTES)).as_bytes());
    assert_eq!(cloud.unwrap().points.len(), 2);
    let err = xyz::read::<f64>(format!("4 5 6\r{}\r", line(xyz::MAX_LINE_BYTES + 1)).as_bytes());
    assert!(matches!(err, Err(XyzError::BadLine { line: 2 })), "{err:?}");
    // 16 MiB without a line end: refused at the first line.
    let err = xyz::read::<f64>("9".repeat(1 << 24).as_bytes());
    assert!(matches!(err, Err(XyzError::BadLine { line: 1 })), "{err:?}");
}

#[test]
fn xyz_refuses_a_column_named_twice() {
    // the second x would have replaced the first without a word: x = 4 for the point
    let err = xyz::read::<f64>("x,y,z,x\n1,2,3,4\n".as_bytes()).unwrap_err();
    assert!(
        matches!(&err, XyzError::DuplicateColumn { line: 1, field: 4, name } if name == "x"),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        "XYZ line 1, field 4: column \"x\" is named twice"
    );
    // after comment lines, and for attribute and extra columns alike
    for (text, line, field) in [
        ("# scan\nx y z intensity intensity\n1 2 3 4 5\n", 2, 5),
        ("x y z w w\n1 2 3 4 5\n", 1, 5),
    ] {
        match xyz::read::<f64>(text.as_bytes()).unwrap_err() {
            XyzError::DuplicateColumn {
                line: l, field: f, ..
            } => assert_eq!((l, f), (line, field)),
            other => panic!("{other}"),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Any cut or corruption of a valid file: an error or a cloud, never a panic; a cut
    /// binary body is always an error.
    #[test]
    fn cut_or_corrupted_files_never_panic(
        n in 0usize..20,
        cut in 0usize..2000,
        flips in proptest::collection::vec((0usize..2000, any::<u8>()), 0..4),
        binary in any::<bool>(),
    ) {
        let cloud = super::formats::full_cloud(n as u64, n);
        let encoding = if binary { Encoding::BinaryLittleEndian } else { Encoding::Ascii };
        let mut bytes = Vec::new();
        ply::write(&cloud, encoding, &mut bytes).unwrap();
        let whole = bytes.len();
        for (at, v) in flips {
            if at < bytes.len() {
                bytes[at] = v;
            }
        }
        bytes.truncate(cut.min(whole));
        let read = ply::read::<f64>(&bytes[..]);
        if binary && cut < whole {
            prop_assert!(read.is_err());
        }
        let _ = xyz::read::<f64>(&bytes[..]);
        if let Ok(c) = read {
            prop_assert!(c.attributes.check(c.len()).is_ok());
        }
    }
}

#[test]
fn a_cloud_with_columns_of_other_lengths_is_not_written() {
    let mut cloud = Cloud::from_points(vec![[0.0f64; 3]; 2]);
    cloud.attributes.intensity = Some(vec![1]);
    let err = ply::write(&cloud, Encoding::Ascii, Vec::new()).unwrap_err();
    assert!(
        err.to_string()
            .contains("intensity has 1 values for 2 points"),
        "{err}"
    );
}
