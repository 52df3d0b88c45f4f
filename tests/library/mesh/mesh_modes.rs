//! The mesher's options: the coarsest mode, the grid unit, the near and maximum sizes
//! and a user size function. Every setting must keep the guarantees (conforming, respects the
//! input, every angle in [45, 90], regions right): each mesh here is checked by the oracle of
//! `mesh_oracle` and by the crate's own `Mesh::validate`, on random boards for every mode.
//!
//! Run with `--nocapture` to see the measured counts.

use crate::mesh_oracle;

use mesh_oracle::{assert_valid_board, assert_valid_mesh, board, figure_14_2};
use orthtree::mesh::{
    generate_mesh, random_board, random_board_capacity, sample_board, Board, Component, Mesh,
    MeshOptions, MeshOutcome, Mode, OptionsError,
};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

/// Meshes `board` with `options`, checks the mesh with the oracle and `Mesh::validate`.
fn mesh_and_check(board: &Board, options: &MeshOptions) -> MeshOutcome {
    assert_valid_board(board);
    let out = options.generate(board).expect("valid options");
    let report = out.mesh.validate(board);
    assert!(report.is_ok(), "{options:?}: {report}");
    let stats = assert_valid_mesh(board, &out.mesh);
    assert_eq!(stats.outline_length as u64, board.perimeter_steps());
    out
}

fn coarsest() -> MeshOptions {
    MeshOptions::new().mode(Mode::Coarsest)
}

/// `board` with every coordinate (and U) multiplied by 2^k.
fn scaled(board: &Board, k: u32) -> Board {
    let comps = (board.components().iter())
        .map(|c| Component::new(c.outline.iter().map(|p| p.map(|x| x << k)).collect()))
        .collect();
    Board::new(board.size() << k, comps).expect("a scaled board is valid")
}

/// The triangles of a mesh as sorted corner coordinates with regions, in a canonical order, so
/// that two meshes can be compared whatever their numbering.
fn canonical(mesh: &Mesh, scale: i64) -> Vec<([[i64; 2]; 3], u32)> {
    let mut t: Vec<_> = (mesh.triangles.iter().zip(&mesh.regions))
        .map(|(tri, &r)| {
            let mut p = tri.map(|v| mesh.vertices[v as usize].map(|x| x * scale));
            p.sort_unstable();
            (p, r)
        })
        .collect();
    t.sort_unstable();
    t
}

#[test]
fn figure_14_2_coarsest() {
    let b = figure_14_2(4);
    let book = mesh_and_check(&b, &MeshOptions::new());
    assert_eq!(book.mesh.triangles.len(), 94);
    let coarse = mesh_and_check(&b, &coarsest());
    eprintln!(
        "Figure 14.2: book {} triangles, coarsest {} (the book's figure: 52)",
        book.mesh.triangles.len(),
        coarse.mesh.triangles.len()
    );
    assert_eq!(coarse.mesh.triangles.len(), 44);
    assert_eq!(coarse.tree.leaf_count(), 13);
    assert!(coarse.mesh.triangles.len() <= 52);
    assert_eq!(coarse.mesh.regions.iter().filter(|&&r| r == 1).count(), 2);
    // Larger boards of the family: coarsest never has more triangles than book.
    for j in 3..=12 {
        let b = figure_14_2(j);
        let book = generate_mesh(&b).unwrap().mesh.triangles.len();
        let coarse = mesh_and_check(&b, &coarsest()).mesh.triangles.len();
        eprintln!("Figure 14.2 at U = 2^{j}: book {book}, coarsest {coarse}");
        assert!(coarse <= book, "j = {j}");
        // the unit square's corner pattern, then 12 triangles per level (5 + 5 + 2)
        assert_eq!(coarse as u32, 12 * j - 4, "j = {j}");
    }
}

/// Book mode through the options with unit 1 is `generate_mesh`, triangle for triangle; with the
/// detected unit it is the same on boards whose detected unit is 1.
#[test]
fn book_mode_is_the_chapters() {
    for seed in 0..6 {
        let b = random_board(seed, 256, 30);
        let old = generate_mesh(&b).unwrap().mesh;
        let new = MeshOptions::new().grid_unit(1).generate(&b).unwrap().mesh;
        assert_eq!(old, new);
        if b.grid_unit() == 1 {
            assert_eq!(MeshOptions::new().generate(&b).unwrap().mesh, old);
        }
    }
    let b = sample_board();
    assert_eq!(b.grid_unit(), 1);
    assert_eq!(
        MeshOptions::new().generate(&b).unwrap().mesh,
        generate_mesh(&b).unwrap().mesh
    );
}

/// A board scaled by 2^k meshes to the same triangles, scaled, in every mode (sizes, being in
/// board coordinates, scaled too).
#[test]
fn scaling_by_powers_of_two() {
    let options: [fn(u32) -> MeshOptions; 3] = [
        |_| MeshOptions::new(),
        |_| coarsest(),
        |k| coarsest().max_size(16 << k),
    ];
    for seed in 0..4 {
        let b = random_board(seed, 64, 12);
        for o in options {
            let base = mesh_and_check(&b, &o(0));
            for k in [1, 3, 7] {
                let big = scaled(&b, k);
                let out = mesh_and_check(&big, &o(k));
                assert_eq!(out.grid_unit, base.grid_unit << k);
                assert_eq!(
                    canonical(&out.mesh, 1),
                    canonical(&base.mesh, 1 << k),
                    "seed {seed}, k {k}, {:?}",
                    o(k)
                );
            }
        }
    }
}

#[test]
fn coarsest_on_the_sample_board() {
    let b = sample_board();
    let book = generate_mesh(&b).unwrap().mesh.triangles.len();
    let coarse = mesh_and_check(&b, &coarsest()).mesh.triangles.len();
    eprintln!("sample_board: book {book} triangles, coarsest {coarse}");
    assert!(coarse * 2 < book);
}

/// The size limits: no leaf larger than the maximum size; cells meeting the outlines no larger
/// than the near size; a size function refines where it asks to.
#[test]
fn size_limits() {
    let b = random_board(3, 256, 20);
    let plain = mesh_and_check(&b, &coarsest()).mesh.triangles.len();
    for max in [16, 64] {
        let out = mesh_and_check(&b, &coarsest().max_size(max));
        let longest = longest_leg(&out.mesh);
        assert!(longest <= max, "max {max}: a leg of {longest}");
        assert!(out.mesh.triangles.len() >= plain);
    }
    for near in [1, 2, 8] {
        let out = mesh_and_check(&b, &coarsest().near_size(near));
        let book_like = mesh_and_check(&b, &MeshOptions::new().near_size(near));
        // coarsest with a near size splits no more than book with the same near size
        assert!(out.mesh.triangles.len() <= book_like.mesh.triangles.len());
    }
    // near size 1 in coarsest mode is the chapter's mesh
    assert_eq!(
        mesh_and_check(&b, &coarsest().near_size(1)).mesh,
        generate_mesh(&b).unwrap().mesh
    );
    // a size function asking for cells of side 4 in the left half only
    let out = mesh_and_check(
        &b,
        &coarsest().size_fn(|p| if p[0] < 128.0 { 4.0 } else { f64::INFINITY }),
    );
    let left_max = (out.mesh.triangles.iter())
        .filter(|t| t.iter().all(|&v| out.mesh.vertices[v as usize][0] <= 128))
        .map(|t| leg(&out.mesh, t))
        .max()
        .unwrap();
    assert!(left_max <= 4, "{left_max}");
}

/// The longer of the two legs of a right isosceles triangle (the cell's side, or half of it).
fn leg(mesh: &Mesh, t: &[u32; 3]) -> i64 {
    let p = t.map(|v| mesh.vertices[v as usize]);
    (0..3)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 3]);
            (a[0] - b[0]).abs().max((a[1] - b[1]).abs())
        })
        .min()
        .unwrap()
}

fn longest_leg(mesh: &Mesh) -> i64 {
    mesh.triangles
        .iter()
        .map(|t| leg(mesh, t))
        .max()
        .unwrap_or(0)
}

#[test]
fn bad_options_are_errors() {
    let b = board(64, &[&[[8, 8], [24, 8], [24, 16], [8, 16]]]);
    assert_eq!(b.grid_unit(), 8);
    let err = |o: MeshOptions| o.generate(&b).unwrap_err();
    assert_eq!(
        err(MeshOptions::new().near_size(4)),
        OptionsError::SizeBelowUnit {
            option: "near size",
            size: 4,
            unit: 8
        }
    );
    assert_eq!(
        err(coarsest().max_size(0)).to_string(),
        "maximum size 0 is not positive"
    );
    assert_eq!(
        err(coarsest().near_size(-8)).to_string(),
        "near size -8 is not positive"
    );
    assert_eq!(
        err(MeshOptions::new().grid_unit(3)).to_string(),
        "grid unit 3 is not a positive power of two"
    );
    assert_eq!(
        err(MeshOptions::new().grid_unit(0)).to_string(),
        "grid unit 0 is not a positive power of two"
    );
    assert_eq!(
        err(MeshOptions::new().grid_unit(16)).to_string(),
        "grid unit 16 does not divide coordinate 8 of component 1's vertex (8, 8)"
    );
    assert_eq!(
        err(MeshOptions::new().grid_unit(128)).to_string(),
        "grid unit 128 does not divide the board's side 64"
    );
    assert_eq!(
        err(coarsest().size_fn(|p| if p[0] > 40.0 { f64::NAN } else { 1e9 })).to_string(),
        "the size function returned NaN at (48, 16)"
    );
    assert_eq!(
        err(coarsest().size_fn(|_| -1.0)).to_string(),
        "the size function returned -1 at (32, 32); sizes must be positive"
    );
    // a smaller unit than detected is fine, and so is a size function below one unit
    let out = mesh_and_check(&b, &coarsest().grid_unit(2));
    assert_eq!(out.grid_unit, 2);
    let fine = mesh_and_check(&b, &coarsest().size_fn(|_| 0.5));
    assert_eq!(longest_leg(&fine.mesh), 8);
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        rng_seed: RngSeed::Fixed(0x0b0a_4d09),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Every mode on random boards: valid, and coarsest never above book.
    #[test]
    fn every_mode_on_random_boards(seed in any::<u64>(), level in 3u32..=9, count in 0usize..50,
                                   max in 1u32..=9, near in 0u32..=4) {
        let count = count.min(random_board_capacity(1 << level) as usize);
        let b = random_board(seed, 1 << level, count);
        let (g, max, near) = (b.grid_unit(), 1i64 << max.min(level), 1i64 << near);
        let (max, near) = (max.max(g), near.max(g));
        let book = mesh_and_check(&b, &MeshOptions::new());
        let coarse = mesh_and_check(&b, &coarsest());
        prop_assert!(coarse.mesh.triangles.len() <= book.mesh.triangles.len());
        mesh_and_check(&b, &coarsest().max_size(max));
        mesh_and_check(&b, &coarsest().near_size(near));
        mesh_and_check(&b, &MeshOptions::new().near_size(near).max_size(max));
        let k = (seed % 3) as u32;
        let big = scaled(&b, k);
        let out = mesh_and_check(&big, &coarsest());
        prop_assert_eq!(canonical(&out.mesh, 1), canonical(&coarse.mesh, 1 << k));
    }
}
