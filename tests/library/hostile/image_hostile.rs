//! Hostile input to the image readers, writers and region-tree constructors, one test per class:
//! headers that claim more than the data holds, limits, the exact PBM grammar, shapes with
//! non-finite or negative parameters, operands of different extents, and unwritable images.
//! Every input is made here by code.

use orthtree::image::{BoolOp, ImageError, ImageTree, RowBuilder};
use orthtree::io::pbm::{self, PbmError, PbmFormat};
use orthtree::io::{LimitError, Limits};

fn err(bytes: &[u8]) -> PbmError {
    pbm::from_bytes(bytes).unwrap_err()
}

#[test]
fn headers_that_claim_more_than_the_data_are_refused_before_allocating() {
    // sizes up to 2^62 pixels: refused by the data length (no limit) or the pixel limit
    for (w, h) in [
        (2_000_000_000u32, 2_000_000_000u32),
        (65536, 65536),
        (u32::MAX, 1),
        (1, u32::MAX),
        (100_000, 3),
    ] {
        for magic in ["P1", "P4"] {
            let file = format!("{magic}\n{w} {h}\n01");
            let got = pbm::from_bytes_with_limits(file.as_bytes(), Limits::NONE).unwrap_err();
            match got {
                PbmError::Truncated {
                    expected, found, ..
                } => assert!(expected > found, "{file:?}: {expected} <= {found}"),
                PbmError::Image(ImageError::TooLarge { .. }) => assert!(w.max(h) > 1 << 31),
                other => panic!("{file:?}: {other}"),
            }
            let limited = pbm::from_bytes(file.as_bytes()).unwrap_err();
            let pixels = u64::from(w) * u64::from(h);
            if pixels > Limits::DEFAULT_MAX_PIXELS {
                assert!(
                    matches!(limited, PbmError::Limit(LimitError::Pixels { width, height, .. })
                        if (width, height) == (w, h)),
                    "{file:?}: {limited}"
                );
                assert!(limited.to_string().contains(&pixels.to_string()));
            }
        }
    }
}

#[test]
fn limits_name_the_size_and_the_limit() {
    let t = ImageTree::from_ball([300, 200], [150.0, 100.0], 80.0).unwrap();
    for format in [PbmFormat::Plain, PbmFormat::Raw] {
        let bytes = pbm::to_bytes(&t, format).unwrap();
        let few_pixels = Limits {
            max_pixels: 59_999,
            ..Limits::default()
        };
        let e = pbm::from_bytes_with_limits(&bytes, few_pixels).unwrap_err();
        assert_eq!(
            e.to_string(),
            "PBM: the image has 60000 pixels (300 x 200); the limit is 59999 pixels"
        );
        let small_file = Limits {
            max_bytes: bytes.len() as u64 - 1,
            ..Limits::default()
        };
        let e = pbm::from_bytes_with_limits(&bytes, small_file).unwrap_err();
        assert!(matches!(
            e,
            PbmError::Limit(LimitError::Bytes {
                what: "the file",
                ..
            })
        ));
        let exact = Limits {
            max_pixels: 60_000,
            ..Limits::default()
        };
        assert_eq!(pbm::from_bytes_with_limits(&bytes, exact).unwrap(), t);
    }
    // a checkerboard needs a node per pixel: the byte limit stops the tree, not the machine
    let mut board = b"P4\n1024 1024\n".to_vec();
    for y in 0..1024 {
        board.extend(std::iter::repeat_n(
            if y % 2 == 0 { 0xaa } else { 0x55 },
            128,
        ));
    }
    let tight = Limits {
        max_bytes: 300_000,
        ..Limits::default()
    };
    let e = pbm::from_bytes_with_limits(&board, tight).unwrap_err();
    assert!(
        matches!(e, PbmError::Image(ImageError::MemoryLimit { needed, limit }) if needed > limit),
        "{e}"
    );
    assert_eq!(pbm::from_bytes(&board).unwrap().len(), 512 * 1024);
}

#[test]
fn the_p4_header_ends_with_exactly_one_whitespace_byte() {
    // 8 x 1, the pixel byte 0x81: black at both ends
    let expected = ImageTree::from_fn([8, 1], |[x, _]| x == 0 || x == 7).unwrap();
    for good in [
        &b"P4\n8 1\n\x81"[..],
        b"P4 8 1 \x81",
        b"P4\t8\t1\r\x81",
        b"P4\n8 1#comment\n\x81",
        b"P4\n8 1#comment\r\x81",
        b"P4#c\n8#c\n1\n\x81",
    ] {
        assert_eq!(pbm::from_bytes(good).unwrap(), expected, "{good:?}");
    }
    // CR LF after the height: the LF is raster, the real byte is trailing data
    let e = err(b"P4\n8 1\r\n\x81");
    assert!(
        matches!(
            e,
            PbmError::TrailingData {
                offset: 8,
                bytes: 1,
                ..
            }
        ),
        "{e}"
    );
    // a comment after the delimiting whitespace is raster too
    let e = err(b"P4\n8 1\n# c\n\x81");
    assert!(
        matches!(
            e,
            PbmError::TrailingData {
                offset: 8,
                bytes: 4,
                ..
            }
        ),
        "{e}"
    );
    // no whitespace at all after the height
    let e = err(b"P4\n8 1\x81");
    assert!(
        matches!(
            e,
            PbmError::MissingWhitespace {
                after: "height",
                offset: 6,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("\\x81"), "{e}");
    // a second image after the first
    let e = err(b"P4\n8 1\n\x81P4\n8 1\n\x81");
    assert!(
        matches!(
            e,
            PbmError::TrailingData {
                offset: 8,
                bytes: 8,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn the_header_grammar_is_followed_exactly() {
    // no whitespace after the magic number: not a 4-wide P1
    let e = err(b"P14 4\n0000\n0000\n0000\n0000\n");
    assert!(
        matches!(
            e,
            PbmError::MissingWhitespace {
                after: "magic number",
                offset: 2,
                ..
            }
        ),
        "{e}"
    );
    let e = err(b"P1 4x4\n");
    assert!(
        matches!(
            e,
            PbmError::MissingWhitespace {
                after: "width",
                offset: 4,
                ..
            }
        ),
        "{e}"
    );
    let e = err(b"P1 4 4x\n");
    assert!(
        matches!(
            e,
            PbmError::MissingWhitespace {
                after: "height",
                offset: 6,
                ..
            }
        ),
        "{e}"
    );
    let e = err(b"P1 4294967296 1\n0");
    assert!(
        matches!(
            e,
            PbmError::BadHeader {
                field: "width",
                offset: 3,
                ..
            }
        ),
        "{e}"
    );
    let e = err(b"P1 -3 1\n0");
    assert!(
        matches!(
            e,
            PbmError::BadHeader {
                field: "width",
                offset: 3,
                ..
            }
        ),
        "{e}"
    );
    let e = err(b"P1 3 0\n");
    assert!(
        matches!(
            e,
            PbmError::BadHeader {
                field: "height",
                offset: 5,
                ..
            }
        ),
        "{e}"
    );
    // CR-only line ends count as lines
    let e = err(b"P1\r2\r2\r01\r0x\r");
    assert!(
        matches!(
            e,
            PbmError::BadPixel {
                line: 5,
                offset: 11,
                found: b'x'
            }
        ),
        "{e}"
    );
    // P1: trailing whitespace and comments are fine, anything else is not
    assert_eq!(pbm::from_bytes(b"P1 2 1\n01\n# end\n\n").unwrap().len(), 1);
    let e = err(b"P1 2 1\n01\n1");
    assert!(
        matches!(
            e,
            PbmError::TrailingData {
                offset: 10,
                bytes: 1,
                ..
            }
        ),
        "{e}"
    );
    let e = err(b"P1 2 1\n01\nP1 2 1\n01\n");
    assert!(
        matches!(e, PbmError::TrailingData { offset: 10, .. }),
        "{e}"
    );
}

#[test]
fn messages_escape_invisible_bytes_and_cut_long_fields() {
    let e = err(b"\0\x07rest");
    assert_eq!(
        e.to_string(),
        "PBM byte 0: starts with \"\\x00\\x07\", expected \"P1\" or \"P4\""
    );
    let e = err(b"P1 2 2\n0\x001\n");
    assert_eq!(
        e.to_string(),
        "PBM line 2, byte 8: pixel is \"\\x00\", expected 0 or 1"
    );
    let mut long = b"P1 ".to_vec();
    long.extend(std::iter::repeat_n(b'z', 100_000));
    let message = err(&long).to_string();
    assert!(
        message.len() < 200 && message.contains("zzz..."),
        "{message}"
    );
    let mut huge_number = b"P1 ".to_vec();
    huge_number.extend(std::iter::repeat_n(b'9', 100_000));
    let message = err(&huge_number).to_string();
    assert!(message.len() < 200, "{message}");
}

#[test]
fn ball_parameters_are_refused_as_ball_new_refuses_them() {
    let extent = [64, 64];
    for radius in [f64::NAN, -1.0, -1e-300, f64::NEG_INFINITY] {
        let e = ImageTree::from_ball(extent, [32.0, 32.0], radius).unwrap_err();
        assert!(
            matches!(e, ImageError::InvalidRadius { .. }),
            "{radius}: {e}"
        );
        assert!(orthtree::query::Ball::new([32.0, 32.0], radius).is_err());
    }
    for (axis, value) in [(0, f64::NAN), (1, f64::INFINITY), (0, f64::NEG_INFINITY)] {
        let mut centre = [32.0, 32.0];
        centre[axis] = value;
        let e = ImageTree::from_ball(extent, centre, 5.0).unwrap_err();
        assert!(
            matches!(e, ImageError::InvalidCentre { axis: a, .. } if a == axis),
            "{e}"
        );
    }
    // accepted: zero (and negative zero) radius, infinite radius, huge values without overflow
    let origin = ImageTree::from_ball(extent, [0.5, 0.5], -0.0).unwrap();
    assert_eq!(origin.len(), 1);
    assert_eq!(
        ImageTree::from_ball(extent, [1e300, -1e300], f64::INFINITY)
            .unwrap()
            .len(),
        64 * 64
    );
    assert!(ImageTree::from_ball(extent, [1e300, 0.0], 1e299)
        .unwrap()
        .is_empty());
    assert_eq!(
        ImageTree::from_ball(extent, [1e300, 0.0], 2e300)
            .unwrap()
            .len(),
        64 * 64
    );
    assert!(ImageTree::from_ball(extent, [-1e200, 0.0], 1e199)
        .unwrap()
        .is_empty());
    // far but finite: the pixel-exact answer at the scale of the image
    let far = ImageTree::from_ball(extent, [1e6, 32.0], 1e6 - 10.0).unwrap();
    let dense = ImageTree::from_fn(extent, |[x, y]| {
        let (dx, dy) = (x as f64 + 0.5 - 1e6, y as f64 + 0.5 - 32.0);
        dx * dx + dy * dy <= (1e6 - 10.0) * (1e6 - 10.0)
    })
    .unwrap();
    assert_eq!(far, dense);
}

#[test]
fn inverted_boxes_are_refused_naming_box_and_axis() {
    let extent = [16, 16, 16];
    let boxes = [([0, 0, 0], [4, 4, 4]), ([2, 9, 0], [3, 8, 1])];
    let e = orthtree::image::VoxelTree::from_boxes(extent, &boxes).unwrap_err();
    assert_eq!(
        e,
        ImageError::InvertedBox {
            index: 1,
            axis: 1,
            lo: 9,
            hi: 8
        }
    );
    assert!(e.to_string().contains("box 1") && e.to_string().contains("axis 1"));
    // empty (lo == hi) and beyond-the-extent boxes are fine: nothing, and cut off
    let t =
        ImageTree::from_boxes([8, 8], &[([3, 3], [3, 7]), ([6, 6], [u32::MAX, u32::MAX])]).unwrap();
    assert_eq!(t.len(), 4);
}

#[test]
fn every_operation_on_different_extents_has_a_try_form() {
    for (ea, eb) in [([8, 8], [8, 9]), ([5, 3], [3, 5]), ([1, 1], [2, 1])] {
        let a = ImageTree::full(ea).unwrap();
        let b = ImageTree::full(eb).unwrap();
        let mismatch = ImageError::SizeMismatch {
            left: ea.to_vec(),
            right: eb.to_vec(),
        };
        for op in [BoolOp::And, BoolOp::Or, BoolOp::Xor, BoolOp::Sub] {
            assert_eq!(a.try_combine(&b, op).unwrap_err(), mismatch);
            assert_eq!(a.try_combine_len(&b, op).unwrap_err(), mismatch);
            let mut c = a.clone();
            assert_eq!(c.try_combine_assign(&b, op).unwrap_err(), mismatch);
            assert_eq!(c, a);
        }
        assert_eq!(a.try_intersection_len(&b).unwrap_err(), mismatch);
        assert_eq!(a.try_union_len(&b).unwrap_err(), mismatch);
        assert_eq!(a.try_difference_len(&b).unwrap_err(), mismatch);
        assert_eq!(a.try_symmetric_difference_len(&b).unwrap_err(), mismatch);
        assert_eq!(a.try_is_disjoint(&b).unwrap_err(), mismatch);
        assert!(mismatch.to_string().contains(&format!("{ea:?}")));
        assert_eq!(a.try_union_len(&a), Ok(a.len()));
    }
}

#[test]
fn images_no_pbm_can_hold_are_not_written() {
    let dir = std::env::temp_dir().join(format!("orthtree-unwritable-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for extent in [[0, 5], [5, 0], [0, 0]] {
        let t = ImageTree::empty(extent).unwrap();
        for format in [PbmFormat::Plain, PbmFormat::Raw] {
            let e = pbm::to_bytes(&t, format).unwrap_err();
            assert!(
                matches!(e, PbmError::EmptyImage { width, height } if [width, height] == extent)
            );
            let path = dir.join("empty.pbm");
            assert!(pbm::write(&t, &path, format).is_err());
            assert!(!path.exists(), "no file is left behind");
        }
    }
    // and every image that is written reads back
    for extent in [[1, 1], [1, 77], [77, 1], [64, 65]] {
        let t = ImageTree::from_fn(extent, |[x, y]| (x ^ y) % 3 == 0).unwrap();
        for format in [PbmFormat::Plain, PbmFormat::Raw] {
            assert_eq!(
                pbm::from_bytes(&pbm::to_bytes(&t, format).unwrap()).unwrap(),
                t
            );
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn rows_streamed_in_build_the_same_tree_as_the_dense_bitmap() {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    for extent in [[1u32, 1u32], [3, 200], [200, 3], [129, 130], [64, 64]] {
        let pixels: Vec<bool> = (0..extent[0] * extent[1])
            .map(|i| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                // runs of a few pixels, so the tree has leaves of every size
                (i / 5 + seed.is_multiple_of(7) as u32).is_multiple_of(2)
            })
            .collect();
        let dense = ImageTree::from_bools(extent, &pixels).unwrap();
        let mut b = RowBuilder::new(extent).unwrap();
        for row in pixels.chunks(extent[0] as usize) {
            let mut words = vec![0u64; b.row_words()];
            for (x, &p) in row.iter().enumerate() {
                words[x / 64] |= u64::from(p) << (x % 64);
            }
            b.push_row(&words).unwrap();
        }
        assert_eq!(b.finish().unwrap(), dense, "{extent:?}");
    }
}
