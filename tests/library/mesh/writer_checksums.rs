//! Every mesh file pinned by its length and FNV-1a hash: the built-in board's mesh and two random
//! boards' (one small enough for the triangle-by-triangle SVG, one drawn merged), so that any
//! change in the bytes the writers put out, whatever its cause, shows here. A change that is
//! meant (a fix) updates the figures.

use orthtree::io::{gmsh, svg, triangle, vtk};
use orthtree::mesh::{random_board, sample_board, Board, Mesh};

/// FNV-1a, 64 bits: the same figure on every platform and Rust version.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The length and hash of each file, in the order node, ele, edge, msh, vtk, svg.
fn figures(mesh: &Mesh, board: &Board) -> Vec<(usize, u64)> {
    type Writer<'a> = Box<dyn Fn(&mut Vec<u8>) -> std::io::Result<()> + 'a>;
    let writers: [Writer<'_>; 6] = [
        Box::new(|o| triangle::write_node(mesh, o)),
        Box::new(|o| triangle::write_ele(mesh, o)),
        Box::new(|o| triangle::write_edge(mesh, o)),
        Box::new(|o| gmsh::write_msh(mesh, o)),
        Box::new(|o| vtk::write_vtk(mesh, o)),
        Box::new(|o| svg::write_mesh_svg(mesh, board, o)),
    ];
    writers
        .iter()
        .map(|write| {
            let mut out = Vec::new();
            write(&mut out).unwrap();
            (out.len(), fnv1a(&out))
        })
        .collect()
}

fn check(board: &Board, expected: [(usize, u64); 6]) {
    let out = orthtree::mesh::generate_mesh(board).unwrap();
    let got = figures(&out.mesh, board);
    let got_all = &got;
    let names = ["node", "ele", "edge", "msh", "vtk", "svg"];
    for ((name, got), want) in names.iter().zip(&got).zip(&expected) {
        assert_eq!(
            got, want,
            ".{name}: (length, hash) changed; all: {got_all:?}"
        );
    }
}

#[test]
fn the_built_in_boards_files_are_unchanged() {
    check(
        &sample_board(),
        [
            (2979174, 4912914379793329645),
            (10417828, 8733182248575868285),
            (11951181, 5691829403183646411),
            (13068549, 9168810715721149933),
            (11227248, 1938425814447043708),
            (2398505, 15886247001825030228),
        ],
    );
}

#[test]
fn a_small_random_boards_files_are_unchanged() {
    let board = random_board(11, 1 << 8, 30);
    check(
        &board,
        [
            (179565, 17202978137651255579),
            (575095, 15826879902225795966),
            (672329, 2921286990099509389),
            (732605, 5962888734619245132),
            (652017, 9175845469422171184),
            (2452179, 14916843550739861910),
        ],
    );
}

#[test]
fn a_merged_pictures_files_are_unchanged() {
    let board = random_board(12, 1 << 11, 300);
    check(
        &board,
        [
            (4469991, 10293886090064797054),
            (14760694, 5942815355861259241),
            (16871404, 8822787729505799277),
            (18604240, 765961885366871976),
            (16135466, 7938145317119190563),
            (2219232, 920987668217054706),
        ],
    );
}
