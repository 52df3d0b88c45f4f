//! Hostile and fuzzed PNG input (feature `png`): headers that claim more pixels than the data
//! holds, the limits, interlaced (Adam7) files, unwritable images, and random and mutated bytes
//! (no panic; every accepted image round-trips). The files are made here by code, with stored
//! (uncompressed) deflate blocks so that any header can be paired with any data.
#![cfg(feature = "png")]

use orthtree::image::ImageTree;
use orthtree::io::png::{self, PngDepth, PngError};
use orthtree::io::{LimitError, Limits};
use proptest::prelude::*;

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

fn adler32(bytes: &[u8]) -> u32 {
    let (mut a, mut b) = (1u32, 0u32);
    for &x in bytes {
        a = (a + u32::from(x)) % 65521;
        b = (b + a) % 65521;
    }
    (b << 16) | a
}

/// A zlib stream of stored blocks.
fn zlib_stored(data: &[u8]) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    let blocks: Vec<&[u8]> = if data.is_empty() {
        vec![&[]]
    } else {
        data.chunks(65535).collect()
    };
    for (i, block) in blocks.iter().enumerate() {
        out.push(u8::from(i + 1 == blocks.len()));
        let len = block.len() as u16;
        out.extend(len.to_le_bytes());
        out.extend((!len).to_le_bytes());
        out.extend_from_slice(block);
    }
    out.extend(adler32(data).to_be_bytes());
    out
}

fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend((data.len() as u32).to_be_bytes());
    let mut body = kind.to_vec();
    body.extend_from_slice(data);
    out.extend_from_slice(&body);
    out.extend(crc32(&body).to_be_bytes());
}

/// An 8-bit grey PNG of `w x h` (interlaced or not) whose image data is `raw` (filter bytes
/// included).
fn grey_png(w: u32, h: u32, interlaced: bool, raw: &[u8]) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = Vec::new();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([8, 0, 0, 0, u8::from(interlaced)]);
    chunk(&mut out, b"IHDR", &ihdr);
    chunk(&mut out, b"IDAT", &zlib_stored(raw));
    chunk(&mut out, b"IEND", &[]);
    out
}

/// The raw Adam7 data of a grey image given by `pixel`.
fn adam7(w: u32, h: u32, pixel: impl Fn(u32, u32) -> u8) -> Vec<u8> {
    let passes = [
        (0, 0, 8, 8),
        (4, 0, 8, 8),
        (0, 4, 4, 8),
        (2, 0, 4, 4),
        (0, 2, 2, 4),
        (1, 0, 2, 2),
        (0, 1, 1, 2),
    ];
    let mut raw = Vec::new();
    for (x0, y0, dx, dy) in passes {
        if x0 >= w || y0 >= h {
            continue;
        }
        for y in (y0..h).step_by(dy) {
            raw.push(0);
            raw.extend((x0..w).step_by(dx).map(|x| pixel(x, y)));
        }
    }
    raw
}

#[test]
fn headers_that_claim_more_than_the_data_are_refused() {
    // 40000 x 40000 (and more) with a few bytes of data: an error, not gigabytes
    for (w, h) in [
        (40_000, 40_000),
        (65_536, 65_536),
        (1, 1 << 30),
        (1 << 30, 1),
    ] {
        let file = grey_png(w, h, false, &[0, 0, 0, 0]);
        let e = png::from_bytes(&file).unwrap_err();
        assert!(
            matches!(e, PngError::Decode(_) | PngError::Limit(_)),
            "{w} x {h}: {e}"
        );
    }
    let e = png::from_bytes(&grey_png(70_000, 70_000, false, &[0])).unwrap_err();
    assert!(
        matches!(
            e,
            PngError::Limit(LimitError::Pixels {
                width: 70_000,
                height: 70_000,
                ..
            })
        ),
        "{e}"
    );
    assert!(e.to_string().contains("4900000000 pixels"), "{e}");
    // the interlaced buffer is counted against the byte limit before it is allocated
    let small = Limits {
        max_bytes: 1 << 20,
        ..Limits::default()
    };
    let e = png::from_bytes_with_limits(&grey_png(20_000, 20_000, true, &[0]), small).unwrap_err();
    assert!(
        matches!(e, PngError::Limit(LimitError::Bytes { .. })),
        "{e}"
    );
}

#[test]
fn the_tree_under_construction_obeys_the_byte_limit() {
    let (w, h) = (512u32, 512u32);
    let mut raw = Vec::new();
    for y in 0..h {
        raw.push(0);
        raw.extend((0..w).map(|x| if (x + y) % 2 == 0 { 0 } else { 255 }));
    }
    let file = grey_png(w, h, false, &raw);
    let tight = Limits {
        max_bytes: 100_000,
        ..Limits::default()
    };
    let e = png::from_bytes_with_limits(&file, tight).unwrap_err();
    assert!(e.to_string().contains("the limit is"), "{e}");
    assert_eq!(png::from_bytes(&file).unwrap().len(), u64::from(w * h / 2));
}

#[test]
fn interlaced_images_read_as_the_same_image() {
    for (w, h) in [(1, 1), (3, 2), (8, 8), (13, 9), (40, 33)] {
        let pixel = |x: u32, y: u32| if (x * 3 + y * 5) % 7 < 3 { 0 } else { 255 };
        let expected = ImageTree::from_fn([w, h], |[x, y]| pixel(x, y) == 0).unwrap();
        let file = grey_png(w, h, true, &adam7(w, h, pixel));
        assert_eq!(png::from_bytes(&file).unwrap(), expected, "{w} x {h}");
        let mut plain = Vec::new();
        for y in 0..h {
            plain.push(0);
            plain.extend((0..w).map(|x| pixel(x, y)));
        }
        assert_eq!(
            png::from_bytes(&grey_png(w, h, false, &plain)).unwrap(),
            expected
        );
    }
}

#[test]
fn images_no_png_can_hold_are_not_written() {
    let dir = std::env::temp_dir().join(format!("orthtree-png-unwritable-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for extent in [[0, 5], [5, 0], [0, 0]] {
        let t = ImageTree::empty(extent).unwrap();
        for depth in [PngDepth::One, PngDepth::Eight] {
            let e = png::to_bytes(&t, depth).unwrap_err();
            assert!(
                matches!(e, PngError::EmptyImage { width, height } if [width, height] == extent)
            );
            let path = dir.join("empty.png");
            assert!(png::write(&t, &path, depth).is_err());
            assert!(!path.exists());
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

fn check(bytes: &[u8]) -> Result<(), TestCaseError> {
    let small = Limits {
        max_pixels: 1 << 16,
        max_bytes: 1 << 22,
    };
    if let Ok(t) = png::from_bytes_with_limits(bytes, small) {
        prop_assert!(t.is_canonical());
        for depth in [PngDepth::One, PngDepth::Eight] {
            let again = png::to_bytes(&t, depth).expect("an image read is writable");
            prop_assert_eq!(&png::from_bytes(&again).unwrap(), &t);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_after_the_signature(tail in proptest::collection::vec(any::<u8>(), 0..96)) {
        let mut bytes = b"\x89PNG\r\n\x1a\n".to_vec();
        bytes.extend(tail);
        check(&bytes)?;
    }

    #[test]
    fn mutated_data_with_valid_checksums(
        w in 1u32..24,
        h in 1u32..24,
        interlaced in any::<bool>(),
        edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 0..6),
        cut in any::<usize>(),
        claim in proptest::option::of((1u32..300, 1u32..300)),
    ) {
        // structure-aware: the chunks and checksums stay valid, the image data is mutated and
        // the header may claim another size
        let pixel = |x: u32, y: u32| ((x * 7 + y * 11) % 256) as u8;
        let mut raw = if interlaced {
            adam7(w, h, pixel)
        } else {
            (0..h).flat_map(|y| std::iter::once(0).chain((0..w).map(move |x| pixel(x, y)))).collect()
        };
        for (i, b) in &edits {
            let n = raw.len();
            raw[i % n] = *b;
        }
        if edits.len() % 3 == 2 {
            raw.truncate(cut % (raw.len() + 1));
        }
        let (cw, ch) = claim.unwrap_or((w, h));
        check(&grey_png(cw, ch, interlaced, &raw))?;
    }

    #[test]
    fn mutated_written_files(
        w in 1u32..30,
        h in 1u32..30,
        one_bit in any::<bool>(),
        edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..4),
    ) {
        let t = ImageTree::from_fn([w, h], |[x, y]| (x ^ y) % 3 == 0).unwrap();
        let depth = if one_bit { PngDepth::One } else { PngDepth::Eight };
        let mut bytes = png::to_bytes(&t, depth).unwrap();
        for (i, b) in &edits {
            let n = bytes.len();
            bytes[i % n] = *b;
        }
        check(&bytes)?;
    }
}
