//! Fuzzing the PBM reader (P1 and P4) and the region-tree node decoder
//! ([`RegionTree::from_nodes`]) with random bytes and with structure-aware mutations of valid
//! input: no input panics, and every input accepted round-trips. Bounded case counts keep each
//! property to about a second in `--release`.

use orthtree::image::{ImageTree, RegionTree, VoxelTree};
use orthtree::io::pbm::{self, PbmFormat};
use orthtree::io::Limits;
use proptest::prelude::*;

/// A small limit, so that no accepted header can make a case slow.
const SMALL: Limits = Limits {
    max_pixels: 1 << 16,
    max_bytes: 1 << 22,
};

/// One mutation of a byte string: flip, set, insert, delete, duplicate a slice, or truncate.
#[derive(Clone, Debug)]
enum Mutation {
    Flip(usize, u8),
    Set(usize, u8),
    Insert(usize, Vec<u8>),
    Delete(usize, usize),
    Repeat(usize, usize),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    // bytes that mean something to the grammar, and any byte
    let interesting = prop_oneof![
        Just(b' '),
        Just(b'\n'),
        Just(b'\r'),
        Just(b'#'),
        Just(b'0'),
        Just(b'1'),
        Just(b'9'),
        Just(b'P'),
        Just(0u8),
        any::<u8>(),
    ];
    prop_oneof![
        (any::<usize>(), 1u8..=255).prop_map(|(i, m)| Mutation::Flip(i, m)),
        (any::<usize>(), interesting.clone()).prop_map(|(i, b)| Mutation::Set(i, b)),
        (any::<usize>(), proptest::collection::vec(interesting, 1..6))
            .prop_map(|(i, b)| Mutation::Insert(i, b)),
        (any::<usize>(), 1usize..8).prop_map(|(i, n)| Mutation::Delete(i, n)),
        (any::<usize>(), 1usize..16).prop_map(|(i, n)| Mutation::Repeat(i, n)),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let len = bytes.len();
    let at = |i: usize| if len == 0 { 0 } else { i % len };
    match m {
        Mutation::Flip(i, mask) if len > 0 => bytes[at(*i)] ^= mask,
        Mutation::Set(i, b) if len > 0 => bytes[at(*i)] = *b,
        Mutation::Insert(i, b) => {
            let i = if len == 0 { 0 } else { i % (len + 1) };
            bytes.splice(i..i, b.iter().copied());
        }
        Mutation::Delete(i, n) if len > 0 => {
            let i = at(*i);
            bytes.drain(i..(i + n).min(len));
        }
        Mutation::Repeat(i, n) if len > 0 => {
            let i = at(*i);
            let slice = bytes[i..(i + n).min(len)].to_vec();
            bytes.splice(i..i, slice);
        }
        Mutation::Truncate(i) => bytes.truncate(if len == 0 { 0 } else { i % len }),
        _ => {}
    }
}

/// Reads with the small limits; an accepted image must come back the same through both formats.
fn check_pbm(bytes: &[u8]) -> Result<(), TestCaseError> {
    if let Ok(t) = pbm::from_bytes_with_limits(bytes, SMALL) {
        prop_assert!(t.is_canonical());
        for format in [PbmFormat::Plain, PbmFormat::Raw] {
            let again = pbm::to_bytes(&t, format).expect("an image read is writable");
            prop_assert_eq!(&pbm::from_bytes(&again).unwrap(), &t);
        }
    }
    Ok(())
}

fn image(w: u32, h: u32, seed: u64) -> ImageTree {
    ImageTree::from_fn([w, h], |[x, y]| {
        (u64::from(x / 3 * 7 + y / 2 * 13) ^ seed).wrapping_mul(0x9e37_79b9) % 5 < 2
    })
    .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn pbm_random_bytes(tail in proptest::collection::vec(any::<u8>(), 0..64), magic in 0usize..3) {
        let mut bytes = [&b"P1"[..], b"P4", b""][magic].to_vec();
        bytes.extend(tail);
        check_pbm(&bytes)?;
    }

    #[test]
    fn pbm_mutated_valid_files(
        w in 1u32..20,
        h in 1u32..20,
        seed in any::<u64>(),
        raw in any::<bool>(),
        mutations in proptest::collection::vec(mutation(), 1..5),
    ) {
        let format = if raw { PbmFormat::Raw } else { PbmFormat::Plain };
        let mut bytes = pbm::to_bytes(&image(w, h, seed), format).unwrap();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        check_pbm(&bytes)?;
    }

    #[test]
    fn node_decoder_random_lists(
        nodes in proptest::collection::vec(0u8..4, 0..80),
        w in 0u32..20,
        h in 0u32..20,
    ) {
        if let Ok(t) = ImageTree::from_nodes([w, h], nodes.clone()) {
            prop_assert_eq!(t.nodes(), &nodes[..]);
            prop_assert!(t.is_canonical());
            prop_assert_eq!(&ImageTree::from_nodes([w, h], t.nodes().to_vec()).unwrap(), &t);
            prop_assert_eq!(&ImageTree::from_bools([w, h], &t.to_bools()).unwrap(), &t);
        }
        let _ = VoxelTree::from_nodes([w, h, 3], nodes);
    }

    #[test]
    fn node_decoder_mutated_trees(
        w in 1u32..33,
        h in 1u32..33,
        seed in any::<u64>(),
        mutations in proptest::collection::vec(mutation(), 1..4),
    ) {
        let mut nodes = image(w, h, seed).nodes().to_vec();
        for m in &mutations {
            apply(&mut nodes, m);
        }
        // keep most bytes node kinds, so that mutations stay near the grammar
        for b in nodes.iter_mut() {
            if *b > 2 && *b % 8 != 3 {
                *b %= 3;
            }
        }
        if let Ok(t) = RegionTree::<2>::from_nodes([w, h], nodes.clone()) {
            prop_assert!(t.is_canonical());
            prop_assert_eq!(&ImageTree::from_bools([w, h], &t.to_bools()).unwrap(), &t);
            let bytes = pbm::to_bytes(&t, PbmFormat::Raw).unwrap();
            prop_assert_eq!(&pbm::from_bytes(&bytes).unwrap(), &t);
        }
    }
}
