//! The mesher's triangle budget on hostile boards: each class (huge U with a small maximum size,
//! huge components in the chapter's unit, long diagonals, a size function forcing unit cells)
//! is refused with the typed error quickly and without building the mesh, and boards within
//! the budget mesh exactly as they do with no limit.

use orthtree::mesh::{
    generate_mesh, random_board, sample_board, Board, BoardError, Component, MeshOptions, Mode,
    OptionsError, DEFAULT_MAX_TRIANGLES,
};
use std::time::{Duration, Instant};

/// Meshes with `options`, asserts the budget error, that it came within `within`, and returns
/// the triangles it says the board needs at least.
fn refused(board: &Board, options: MeshOptions, within: Duration) -> u64 {
    let limit = options.current_max_triangles();
    let start = Instant::now();
    let err = options.generate(board).expect_err("must be refused");
    let took = start.elapsed();
    let OptionsError::TooManyTriangles(e) = err else {
        panic!("wrong error: {err}");
    };
    assert_eq!(e.limit, limit);
    assert!(e.at_least > limit, "{e}");
    assert!(took < within, "refused after {took:?}: {e}");
    assert!(e.to_string().contains("triangles"), "{e}");
    e.at_least
}

fn square(x: i64, y: i64, side: i64) -> Component {
    Component::new(vec![
        [x, y],
        [x + side, y],
        [x + side, y + side],
        [x, y + side],
    ])
}

#[test]
fn huge_boards_with_small_maximum_sizes_fail_at_once() {
    for (levels, max) in [(30, 1), (30, 1000), (25, 2), (20, 64), (16, 1)] {
        let board = Board::new(1 << levels, vec![]).unwrap();
        let options = MeshOptions::new().grid_unit(1).max_size(max);
        let needs = refused(&board, options, Duration::from_millis(50));
        let side = (1u64 << levels) / (max as u64).next_power_of_two().min(max as u64 * 2);
        assert!(
            needs >= 2 * side * side / 4,
            "U = 2^{levels}, max {max}: {needs}"
        );
    }
    // the 12-byte text board of the report: `size 1073741824`, unit 1, max 1
    let board = Board::new(1 << 30, vec![]).unwrap();
    let e = refused(
        &board,
        MeshOptions::new().grid_unit(1).max_size(1),
        Duration::from_millis(50),
    );
    assert_eq!(e, 1 << 61);
}

#[test]
fn huge_components_in_unit_cells_fail_at_once() {
    let boards = [
        Board::new(1 << 30, vec![square(1, 1, (1 << 30) - 2)]).unwrap(),
        Board::new(
            1 << 30,
            vec![square(7, 9, 1 << 28), square(1 << 29, 1 << 29, 1 << 27)],
        )
        .unwrap(),
        Board::new(1 << 26, vec![square(3, 3, (1 << 26) - 8)]).unwrap(),
    ];
    for board in &boards {
        let needs = refused(
            board,
            MeshOptions::new().grid_unit(1),
            Duration::from_millis(50),
        );
        // at least one unit cell per six unit steps of outline
        assert!(needs >= board.perimeter_steps() / 3, "{needs}");
        // the chapter's entry point gives the same refusal as a board error
        let err = generate_mesh(board).unwrap_err();
        assert!(matches!(err, BoardError::TooManyTriangles(e) if e.at_least == needs));
    }
}

#[test]
fn long_diagonals_fail_at_once() {
    for (levels, limit, within) in [
        (30, DEFAULT_MAX_TRIANGLES, 50),
        (24, 10_000_000, 50),
        (20, 1_000_000, 2000),
    ] {
        let u: i64 = 1 << levels;
        // a thin diamond along the board's rising diagonal, and a triangle with a long hypotenuse
        let diamond = Component::new(vec![[1, 2], [u - 2, u - 1], [u - 3, u - 1], [1, 3]]);
        let wedge = Component::new(vec![[2, 1], [u - 1, 1], [u - 1, u - 2]]);
        for c in [diamond, wedge] {
            let board = Board::new(u, vec![c]).unwrap();
            let options = MeshOptions::new().grid_unit(1).max_triangles(limit);
            refused(&board, options, Duration::from_millis(within));
        }
    }
}

#[test]
fn size_functions_forcing_unit_cells_stop_at_the_budget() {
    let limit = 200_000;
    for (levels, hot) in [(30, 0.0), (20, 0.5), (12, 0.25)] {
        let u = (1i64 << levels) as f64;
        let board = Board::new(1 << levels, vec![]).unwrap();
        // unit cells in a disc of radius 0.8 U around (hot * U, hot * U), which the board alone cannot show
        let f = move |p: [f64; 2]| {
            let d = (p[0] - hot * u).hypot(p[1] - hot * u);
            if d < 0.8 * u {
                0.5
            } else {
                f64::INFINITY
            }
        };
        for mode in [Mode::Book, Mode::Coarsest] {
            let options = MeshOptions::new()
                .mode(mode)
                .grid_unit(1)
                .size_fn(f)
                .max_triangles(limit);
            let needs = refused(&board, options, Duration::from_secs(2));
            // refinement stopped as soon as the leaves made passed the limit
            assert!(needs <= limit + 6, "{needs}");
        }
    }
}

#[test]
fn boards_within_the_budget_mesh_as_without_it() {
    let boards = [
        sample_board(),
        random_board(3, 1 << 12, 40),
        random_board(9, 1 << 13, 30),
        Board::new(16, vec![square(1, 1, 1)]).unwrap(),
    ];
    for board in &boards {
        for mode in [Mode::Book, Mode::Coarsest] {
            let free = MeshOptions::new().mode(mode).max_triangles(u64::MAX);
            let mesh = free.generate(board).unwrap().mesh;
            let n = mesh.triangles.len() as u64;
            assert!(n <= DEFAULT_MAX_TRIANGLES);
            let default = MeshOptions::new().mode(mode).generate(board).unwrap().mesh;
            assert_eq!(default, mesh);
            // the limit is exact: n triangles fit a limit of n, not of n - 1
            let tight = MeshOptions::new()
                .mode(mode)
                .max_triangles(n)
                .generate(board);
            assert_eq!(tight.unwrap().mesh, mesh);
            let below = MeshOptions::new().mode(mode).max_triangles(n - 1);
            assert_eq!(refused(board, below, Duration::from_secs(5)), n);
        }
    }
}
