//! Serde (feature `serde`) of the mesher's values through JSON: meshes (book and coarsest modes,
//! a sample board, the empty mesh), boards and options read back equal, the meshes still valid
//! against their boards; corrupted documents refused with an error naming the triangle, vertex,
//! segment, component or setting; mutated mesh documents refused or read back as meshes that pass
//! every check a mesh can pass without its board.

use crate::common::mutate::mutate;
use crate::common::points::config;
use orthtree::mesh::{
    generate_mesh, sample_board, Board, Component, HalfEdges, Mesh, MeshOptions, Mode,
};
use proptest::prelude::*;
use serde_json::{json, Value};

/// The chapter's Figure 14.2: a unit square near the top-left corner of a 16 x 16 board.
fn figure() -> Board {
    Board::new(
        16,
        vec![Component::new(vec![[1, 14], [2, 14], [2, 15], [1, 15]])],
    )
    .unwrap()
}

fn round_trip(mesh: &Mesh, board: &Board) {
    let json = serde_json::to_string(mesh).unwrap();
    let back: Mesh = serde_json::from_str(&json).unwrap();
    assert_eq!(&back, mesh);
    let report = back.validate(board);
    assert!(report.is_ok(), "{report}");
    let b: Board = serde_json::from_str(&serde_json::to_string(board).unwrap()).unwrap();
    assert_eq!(&b, board);
}

#[test]
fn meshes_boards_and_options_round_trip() {
    let board = figure();
    round_trip(&generate_mesh(&board).unwrap().mesh, &board);
    let coarse = MeshOptions::new().mode(Mode::Coarsest);
    round_trip(&coarse.generate(&board).unwrap().mesh, &board);
    let sample = sample_board();
    round_trip(&coarse.generate(&sample).unwrap().mesh, &sample);
    let empty: Mesh =
        serde_json::from_str(&serde_json::to_string(&Mesh::default()).unwrap()).unwrap();
    assert_eq!(empty, Mesh::default());
    let plain = Board::new(8, vec![]).unwrap();
    round_trip(&generate_mesh(&plain).unwrap().mesh, &plain);

    let options = MeshOptions::new()
        .mode(Mode::Coarsest)
        .grid_unit(2)
        .near_size(4)
        .max_triangles(1000);
    let json = serde_json::to_string(&options).unwrap();
    let back: MeshOptions = serde_json::from_str(&json).unwrap();
    assert_eq!(format!("{back:?}"), format!("{options:?}"));
    let fine = Board::new(
        64,
        vec![Component::new(vec![[4, 56], [8, 56], [8, 60], [4, 60]])],
    )
    .unwrap();
    assert_eq!(
        back.generate(&fine).unwrap().mesh,
        options.generate(&fine).unwrap().mesh
    );
    let with_fn = MeshOptions::new().size_fn(|_| 4.0);
    let e = serde_json::to_string(&with_fn).unwrap_err().to_string();
    assert!(e.contains("size function"), "{e}");
}

/// The figure's mesh as a JSON value, changed by `edit`, read back: the error's message.
fn corrupted(edit: impl FnOnce(&mut Value)) -> String {
    let mut v = serde_json::to_value(generate_mesh(&figure()).unwrap().mesh).unwrap();
    edit(&mut v);
    match serde_json::from_value::<Mesh>(v) {
        Ok(_) => panic!("a corrupted document was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn corrupted_meshes_boards_and_options_are_refused() {
    let e = corrupted(|v| v["vertices"][2] = json!([-1, 0]));
    assert!(e.contains("vertex 2 at (-1, 0)"), "{e}");
    let e = corrupted(|v| v["vertices"][0] = json!([0, i64::MAX]));
    assert!(e.contains("vertex 0") && e.contains("1073741824"), "{e}");
    let e = corrupted(|v| v["triangles"][4][1] = json!(100_000));
    assert!(e.contains("triangle 4"), "{e}");
    let e = corrupted(|v| {
        v["regions"].as_array_mut().unwrap().pop();
    });
    assert!(e.contains("region"), "{e}");
    let e = corrupted(|v| {
        let t = v["triangles"][3].clone();
        v["triangles"][3] = json!([t[1], t[0], t[2]]);
    });
    assert!(
        e.contains("triangle 3") && e.contains("counter-clockwise"),
        "{e}"
    );
    let e = corrupted(|v| {
        let t = v["triangles"][5].clone();
        v["triangles"][5] = json!([t[0], t[0], t[2]]);
    });
    assert!(e.contains("triangle 5"), "{e}");
    let e = corrupted(|v| {
        let t = v["triangles"][0].clone();
        v["triangles"].as_array_mut().unwrap().push(t);
        v["regions"].as_array_mut().unwrap().push(json!(0));
    });
    assert!(e.contains("twice") || e.contains("both use"), "{e}");
    let e = corrupted(|v| v["segments"][0]["vertices"][1] = json!(100_000));
    assert!(e.contains("segment 0"), "{e}");
    let e = corrupted(|v| {
        let a = v["segments"][1]["vertices"][0].clone();
        v["segments"][1]["vertices"] = json!([a, a]);
    });
    assert!(e.contains("segment 1 joins vertex"), "{e}");
    let e = corrupted(|v| v["segments"][2]["kind"] = json!({"Component": 0}));
    assert!(e.contains("segment 2 lies on component 0"), "{e}");
    let e = corrupted(|v| v["segments"][2]["kind"] = json!("Nowhere"));
    assert!(e.contains("Nowhere"), "{e}");

    let board = |doc: &str| serde_json::from_str::<Board>(doc).unwrap_err().to_string();
    let e = board(r#"{"size":12,"components":[]}"#);
    assert!(e.contains("12"), "{e}");
    let square = |x: i64| {
        format!(
            r#"{{"outline":[[{x},1],[{},1],[{},3],[{x},3]],"lines":[]}}"#,
            x + 2,
            x + 2
        )
    };
    let e = board(&format!(r#"{{"size":8,"components":[{}]}}"#, square(7)));
    assert!(e.contains("component 1"), "{e}");
    let e = board(&format!(
        r#"{{"size":16,"components":[{},{}]}}"#,
        square(1),
        square(2)
    ));
    assert!(e.contains("component"), "{e}");
    let e = board(r#"{"size":16,"components":[{"outline":[[1,1],[2,2]],"lines":[]}]}"#);
    assert!(e.contains("component 1"), "{e}");

    let options = |doc: &str| {
        serde_json::from_str::<MeshOptions>(doc)
            .unwrap_err()
            .to_string()
    };
    let all = |unit: &str, near: &str| {
        format!(
            r#"{{"mode":"Book","grid_unit":{unit},"near_size":{near},"max_size":null,"max_triangles":null}}"#
        )
    };
    let e = options(&all("3", "null"));
    assert!(e.contains("grid unit 3"), "{e}");
    let e = options(&all("null", "0"));
    assert!(e.contains("near size 0 is not positive"), "{e}");
    let e = options(&all("null", "null").replace("Book", "Finest"));
    assert!(e.contains("Finest"), "{e}");
}

/// Every check a mesh can pass without its board.
fn sound(mesh: &Mesh) -> bool {
    let ccw = mesh.triangles.iter().all(|t| {
        let [a, b, c] = t.map(|v| mesh.vertices[v as usize].map(i128::from));
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0
    });
    mesh.check_indices().is_ok() && ccw && HalfEdges::new(mesh).is_ok()
}

proptest! {
    #![proptest_config(config(300, 0x5e7d_e003))]

    /// A mutated mesh document is refused, or read back as a sound mesh.
    #[test]
    fn mutated_mesh_documents_are_refused_or_sound(
        steps in prop::collection::vec((any::<u64>(), any::<u8>()), 1..4),
    ) {
        let mesh = MeshOptions::new().mode(Mode::Coarsest).generate(&figure()).unwrap().mesh;
        let mut v = serde_json::to_value(&mesh).unwrap();
        let done: Vec<String> = steps.iter().map(|&(at, kind)| mutate(&mut v, at, kind)).collect();
        if let Ok(back) = serde_json::from_value::<Mesh>(v) {
            prop_assert!(sound(&back), "{done:?}");
        }
    }
}
