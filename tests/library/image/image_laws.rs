//! Set-algebra laws on random region trees (D = 2 and 3, padded sizes included): commutativity,
//! associativity, distributivity, De Morgan, a - b = a & !b, !!a = a, and a ^ b = (a | b) - (a & b).

use orthtree::image::RegionTree;
use proptest::prelude::*;

/// Three random images of one random extent, as unions of a few random boxes and balls.
fn trees<const D: usize>(max_side: u32) -> impl Strategy<Value = [RegionTree<D>; 3]> {
    proptest::array::uniform::<_, D>(1..=max_side).prop_flat_map(move |extent| {
        let one = (
            proptest::collection::vec(
                (
                    proptest::array::uniform::<_, D>(0..=max_side),
                    proptest::array::uniform::<_, D>(0..=max_side),
                ),
                0..5,
            ),
            proptest::array::uniform::<_, D>(0.0..max_side as f64),
            0.0..max_side as f64 / 2.0,
        )
            .prop_map(move |(boxes, centre, r)| {
                let boxes: Vec<_> = boxes
                    .into_iter()
                    .map(|(p, q)| {
                        (
                            core::array::from_fn(|a| p[a].min(q[a])),
                            core::array::from_fn(|a| p[a].max(q[a])),
                        )
                    })
                    .collect();
                let b = RegionTree::<D>::from_boxes(extent, &boxes).unwrap();
                b ^ RegionTree::<D>::from_ball(extent, centre, r).unwrap()
            });
        [one.clone(), one.clone(), one]
    })
}

fn laws<const D: usize>([a, b, c]: &[RegionTree<D>; 3]) -> Result<(), TestCaseError> {
    for t in [a, b, c] {
        prop_assert!(t.is_canonical());
    }
    prop_assert_eq!(a & b, b & a);
    prop_assert_eq!(a | b, b | a);
    prop_assert_eq!(a ^ b, b ^ a);
    prop_assert_eq!(&(a & b) & c, a & &(b & c));
    prop_assert_eq!(&(a | b) | c, a | &(b | c));
    prop_assert_eq!(&(a ^ b) ^ c, a ^ &(b ^ c));
    prop_assert_eq!(a & &(b | c), &(a & b) | &(a & c));
    prop_assert_eq!(!(a | b), &!a & &!b);
    prop_assert_eq!(!(a & b), &!a | &!b);
    prop_assert_eq!(a - b, a & &!b);
    prop_assert_eq!(!!a.clone(), a.clone());
    prop_assert_eq!(a ^ b, &(a | b) - &(a & b));
    prop_assert!((a - &a.clone()).is_empty());
    prop_assert_eq!(a | &!a, RegionTree::<D>::full(a.extent()).unwrap());
    prop_assert_eq!(a.union_len(b) + a.intersection_len(b), a.len() + b.len());
    for r in [a & b, a | b, a ^ b, a - b, !a] {
        prop_assert!(r.is_canonical(), "{:?}", r.validate());
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn laws_2d(t in trees::<2>(70)) {
        laws(&t)?;
    }

    #[test]
    fn laws_3d(t in trees::<3>(20)) {
        laws(&t)?;
    }
}
