//! `RegionTree::from_nodes` on malformed node lists: each broken invariant is named with the
//! position of its node.

use orthtree::image::{ImageError, ImageTree, Malformation, RegionTree, VoxelTree};

fn error<const D: usize>(extent: [u32; D], nodes: Vec<u8>) -> (usize, Malformation) {
    match RegionTree::<D>::from_nodes(extent, nodes) {
        Err(ImageError::Malformed {
            position,
            invariant,
        }) => (position, invariant),
        other => panic!("{other:?}"),
    }
}

#[test]
fn each_broken_invariant_is_named_with_its_node() {
    let m = Malformation::EndsInsideTree;
    assert_eq!(error([2, 2], vec![]), (0, m.clone()));
    assert_eq!(error([4, 4], vec![2, 2, 1, 0, 0]), (5, m));
    let m = Malformation::InternalAtPixelLevel;
    assert_eq!(error([2, 2], vec![2, 2, 0, 0, 0, 0, 1, 0, 0]), (1, m));
    for (nodes, at, min) in [
        (vec![1], 0, vec![0, 0]),
        (vec![2, 0, 1, 0, 0], 2, vec![2, 0]),
        (vec![2, 0, 0, 0, 1], 4, vec![2, 2]),
    ] {
        let side = if at == 0 { 4 } else { 2 };
        let m = Malformation::BlackOutsideExtent { min, side };
        assert_eq!(error([3, 3], nodes), (at, m));
    }
    for kind in [3, 7, 255] {
        let m = Malformation::UnknownKind { kind };
        assert_eq!(error([2, 2], vec![2, 0, 1, kind, 0]), (3, m));
    }
    let m = Malformation::TrailingNodes { len: 6 };
    assert_eq!(error([2, 2], vec![2, 0, 1, 0, 0, 1]), (5, m));
    assert_eq!(
        error([2, 2], vec![0, 0]).1,
        Malformation::TrailingNodes { len: 2 }
    );
    for colour in [0, 1] {
        // a white (0) or black (1) node with four children of its colour
        let m = Malformation::Collapsible { colour };
        assert_eq!(
            error([2, 2], vec![2, colour, colour, colour, colour]),
            (0, m.clone())
        );
        let mut deep = vec![2, 0, 1, 0, 2];
        deep.extend([colour; 4]);
        assert_eq!(error([4, 4], deep), (4, m));
        let mut voxels = vec![2, 2];
        voxels.extend([colour; 8]);
        voxels.extend([1; 7]);
        assert_eq!(error::<3>([4, 4, 4], voxels).0, 1);
    }
    let e = ImageTree::from_nodes([2, 2], vec![2, 1, 1, 1, 1]).unwrap_err();
    assert!(
        e.to_string().contains("node 0") && e.to_string().contains("black"),
        "{e}"
    );
    assert!(VoxelTree::from_nodes([2, 2, 2], vec![0]).is_ok());
}
