//! `RowBuilder` and `for_each_row`: images rebuilt row by row equal their dense forms.

use orthtree::image::*;

fn rebuild(t: &ImageTree) -> ImageTree {
    let mut b = RowBuilder::new(t.extent()).unwrap();
    t.for_each_row(|_, w| b.push_row(w)).unwrap();
    b.finish().unwrap()
}

#[test]
fn rows_round_trip_against_the_dense_forms() {
    let mut seed = 7u64;
    for (w, h) in [
        (1, 1),
        (1, 9),
        (9, 1),
        (64, 64),
        (65, 3),
        (130, 77),
        (200, 129),
    ] {
        for density in [0u64, 3, 50, 97, 100] {
            let t = ImageTree::from_fn([w, h], |[x, y]| {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                // blocks of 4 x 4 so that the tree has big leaves too
                let _ = (x, y);
                (seed >> 33) % 100 < density
            })
            .unwrap();
            let again = rebuild(&t);
            assert_eq!(again, t, "{w} x {h}, density {density}");
            assert!(again.is_canonical());
            let disc =
                ImageTree::from_ball([w, h], [w as f64 / 2.0, 0.3 * h as f64], 0.4 * w as f64)
                    .unwrap();
            assert_eq!(rebuild(&disc), disc);
            let mut dense = Vec::new();
            disc.for_each_row(|_, words| -> Result<(), ()> {
                dense.extend((0..w as usize).map(|x| (words[x / 64] >> (x % 64)) & 1 == 1));
                Ok(())
            })
            .unwrap();
            assert_eq!(dense, disc.to_bools());
        }
    }
}

#[test]
fn row_counts_and_lengths_are_checked() {
    let mut b = RowBuilder::new([10, 2]).unwrap();
    assert!(matches!(
        b.push_row(&[0, 0]),
        Err(ImageError::BitmapLength {
            expected: 1,
            found: 2
        })
    ));
    b.push_row(&[1]).unwrap();
    let early = RowBuilder::new([10, 2]).unwrap().finish();
    assert!(matches!(
        early,
        Err(ImageError::MissingRows {
            height: 2,
            found: 0
        })
    ));
    b.push_row(&[1]).unwrap();
    assert!(matches!(
        b.push_row(&[1]),
        Err(ImageError::TooManyRows { height: 2 })
    ));
    assert_eq!(b.finish().unwrap().len(), 2);
}

#[test]
fn the_memory_budget_is_enforced() {
    // a checkerboard: every pixel its own leaf
    let mut b = RowBuilder::new([256, 256]).unwrap().max_bytes(4096);
    let mut outcome = Ok(());
    for y in 0..256u32 {
        let pattern = if y % 2 == 0 {
            0x5555_5555_5555_5555
        } else {
            0xaaaa_aaaa_aaaa_aaaa
        };
        outcome = b.push_row(&[pattern; 4]);
        if outcome.is_err() {
            break;
        }
    }
    let Err(ImageError::MemoryLimit { needed, limit }) = outcome else {
        panic!("expected the limit, got {outcome:?}");
    };
    assert!(needed > limit && limit == 4096);
}
