//! Boolean operations on region trees against pixel-by-pixel reference operations on random
//! images (D = 2 and 3, sizes that are and are not powers of two), the count-only variants, and
//! the canonical form of every result.

use orthtree::image::{BoolOp, ImageError, RegionTree};
use proptest::prelude::*;

const OPS: [BoolOp; 4] = [BoolOp::And, BoolOp::Or, BoolOp::Xor, BoolOp::Sub];

/// Random images with blobs (so that trees have large leaves as well as single pixels): each
/// pixel is the XOR of a few random boxes and a sprinkle of noise.
fn image<const D: usize>(max_side: u32) -> impl Strategy<Value = ([u32; D], Vec<bool>, Vec<bool>)> {
    proptest::array::uniform::<_, D>(1..=max_side).prop_flat_map(move |extent| {
        let n: usize = extent.iter().map(|&e| e as usize).product();
        let bits = move || {
            (
                proptest::collection::vec(
                    (
                        proptest::array::uniform::<_, D>(0..=max_side),
                        proptest::array::uniform::<_, D>(0..=max_side),
                    ),
                    0..4,
                ),
                proptest::collection::vec(prop::bool::weighted(0.05), n),
            )
                .prop_map(move |(boxes, noise)| {
                    (0..n)
                        .map(|i| {
                            let mut p = [0u32; D];
                            let mut r = i;
                            for a in 0..D {
                                p[a] = (r % extent[a] as usize) as u32;
                                r /= extent[a] as usize;
                            }
                            let inside = boxes
                                .iter()
                                .filter(|(lo, hi)| {
                                    (0..D).all(|a| {
                                        lo[a].min(hi[a]) <= p[a] && p[a] < lo[a].max(hi[a])
                                    })
                                })
                                .count();
                            (inside % 2 == 1) ^ noise[i]
                        })
                        .collect::<Vec<bool>>()
                })
        };
        (Just(extent), bits(), bits())
    })
}

fn check<const D: usize>(extent: [u32; D], a: &[bool], b: &[bool]) -> Result<(), TestCaseError> {
    let ta = RegionTree::<D>::from_bools(extent, a).unwrap();
    let tb = RegionTree::<D>::from_bools(extent, b).unwrap();
    prop_assert!(ta.validate().is_ok() && tb.validate().is_ok());
    prop_assert_eq!(ta.to_bools(), a);
    prop_assert_eq!(ta.len(), a.iter().filter(|&&x| x).count() as u64);
    for op in OPS {
        let r = ta.try_combine(&tb, op).unwrap();
        prop_assert!(r.validate().is_ok(), "{:?}: {:?}", op, r.validate());
        let want: Vec<bool> = a.iter().zip(b).map(|(&x, &y)| op.apply(x, y)).collect();
        prop_assert_eq!(&r.to_bools(), &want, "{:?}", op);
        prop_assert_eq!(r.len(), want.iter().filter(|&&x| x).count() as u64);
        prop_assert_eq!(ta.combine_len(&tb, op), r.len());
        // canonical form is unique: building from the reference gives the same tree
        prop_assert_eq!(&r, &RegionTree::<D>::from_bools(extent, &want).unwrap());
    }
    let not = !&ta;
    prop_assert!(not.validate().is_ok());
    prop_assert_eq!(not.to_bools(), a.iter().map(|&x| !x).collect::<Vec<_>>());
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn ops_match_reference_2d((extent, a, b) in image::<2>(40)) {
        check(extent, &a, &b)?;
    }

    #[test]
    fn ops_match_reference_3d((extent, a, b) in image::<3>(12)) {
        check(extent, &a, &b)?;
    }

    #[test]
    fn ops_match_reference_1d((extent, a, b) in image::<1>(200)) {
        check(extent, &a, &b)?;
    }
}

#[test]
fn operators_owned_and_borrowed_agree() {
    let a = RegionTree::<2>::from_ball([30, 20], [10.0, 10.0], 8.0).unwrap();
    let b = RegionTree::<2>::from_boxes([30, 20], &[([5, 0], [25, 12])]).unwrap();
    let and = a.intersection(&b);
    assert_eq!(&a & &b, and);
    assert_eq!(a.clone() & &b, and);
    assert_eq!(&a & b.clone(), and);
    assert_eq!(a.clone() & b.clone(), and);
    let mut c = a.clone();
    c &= &b;
    assert_eq!(c, and);
    let mut c = a.clone();
    c |= b.clone();
    assert_eq!(c, a.union(&b));
    let mut c = a.clone();
    c ^= &b;
    assert_eq!(c, a.symmetric_difference(&b));
    let mut c = a.clone();
    c -= &b;
    assert_eq!(c, a.difference(&b));
    assert_eq!(!a.clone(), a.complement());
}

#[test]
fn size_mismatch_is_a_typed_error() {
    let a = RegionTree::<2>::empty([8, 8]).unwrap();
    let b = RegionTree::<2>::empty([8, 7]).unwrap();
    assert_eq!(
        a.try_union(&b),
        Err(ImageError::SizeMismatch {
            left: vec![8, 8],
            right: vec![8, 7]
        })
    );
    assert!(a.try_intersection(&b).is_err());
    assert!(a.try_difference(&b).is_err());
    assert!(a.try_symmetric_difference(&b).is_err());
}

#[test]
#[should_panic(expected = "operands differ in size")]
fn operator_panics_on_size_mismatch() {
    let a = RegionTree::<2>::empty([8, 8]).unwrap();
    let b = RegionTree::<2>::empty([4, 4]).unwrap();
    let _ = &a | &b;
}
