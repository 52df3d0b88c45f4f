//! PBM (P1 and P4) round trips, padded sizes, comments, and malformed files with the line or
//! byte offset they name.

use orthtree::image::ImageTree;
use orthtree::io::pbm::{self, PbmError, PbmFormat};
use proptest::prelude::*;

proptest! {
    #[test]
    fn round_trips(w in 1u32..40, h in 1u32..40, seed in any::<u64>()) {
        let t = ImageTree::from_fn([w, h], |[x, y]| (u64::from(x * 31 + y * 17) ^ seed) % 3 == 0).unwrap();
        for format in [PbmFormat::Plain, PbmFormat::Raw] {
            let back = pbm::from_bytes(&pbm::to_bytes(&t, format).unwrap()).unwrap();
            prop_assert_eq!(&back, &t);
            prop_assert_eq!(back.extent(), [w, h]);
        }
    }
}

#[test]
fn comments_and_free_layout() {
    let t = pbm::from_bytes(b"P1 # a comment\n# another\n3\n2\n1 0 1\n# mid-body\n011").unwrap();
    assert_eq!(t.to_bools(), [true, false, true, false, true, true]);
    let raw = pbm::from_bytes(b"P4\n# c\n9 1\n\xff\x80").unwrap();
    assert_eq!(raw.len(), 9);
}

#[test]
fn writes_and_reads_files() {
    let dir = std::env::temp_dir().join(format!("orthtree-pbm-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let t = ImageTree::from_ball([50, 30], [25.0, 15.0], 12.0).unwrap();
    let path = dir.join("disc.pbm");
    pbm::write(&t, &path, PbmFormat::Raw).unwrap();
    assert_eq!(pbm::read(&path).unwrap(), t);
    assert!(matches!(
        pbm::read(dir.join("missing.pbm")),
        Err(PbmError::Io(_))
    ));
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn malformed_files_name_what_and_where() {
    let err = |b: &[u8]| pbm::from_bytes(b).unwrap_err();
    assert!(matches!(err(b"P2\n1 1\n0"), PbmError::BadMagic { found } if found == "P2"));
    assert!(matches!(err(b""), PbmError::BadMagic { .. }));
    assert!(matches!(
        err(b"P1\n\nx 1\n0"),
        PbmError::BadHeader {
            field: "width",
            line: 3,
            offset: 4,
            ..
        }
    ));
    assert!(matches!(
        err(b"P1\n3\n"),
        PbmError::BadHeader {
            field: "height",
            line: 3,
            offset: 5,
            ..
        }
    ));
    assert!(matches!(
        err(b"P1 0 1\n"),
        PbmError::BadHeader {
            field: "width",
            line: 1,
            offset: 3,
            ..
        }
    ));
    assert!(matches!(
        err(b"P1 2 2\n01\n0"),
        PbmError::Truncated {
            offset: 11,
            line: 3,
            expected: 4,
            found: 3,
            unit: "pixels"
        }
    ));
    assert!(matches!(
        err(b"P1 2 2\n01\n02"),
        PbmError::BadPixel {
            line: 3,
            offset: 11,
            found: b'2'
        }
    ));
    assert!(matches!(
        err(b"P4 9 2\n\x00\x00\x00"),
        PbmError::Truncated {
            offset: 10,
            expected: 4,
            found: 3,
            ..
        }
    ));
    assert!(matches!(err(b"P1 4294967295 1\n"), PbmError::Image(_)));
    assert!(err(b"P1 2 2\n01\n02").to_string().contains("line 3"));
}
