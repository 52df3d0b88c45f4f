//! p4est 2.2's balance (`p4est_balance`, feature `p4est`) run under `mpirun` at one and two
//! ranks as a user runs it: its leaf counts before and after balance equal those of orthtree's
//! serial `Tree::balance` of the same fractal, for face, edge and corner balance in 2D and 3D,
//! so the comparison's two sides balance the same forest to the same leaves.
#![cfg(feature = "p4est")]

use orthtree::tree::fractal::fractal;
use orthtree::Connectivity;
use std::path::Path;
use std::time::Duration;

#[path = "../../../tests/programs/mod.rs"]
#[allow(dead_code)] // this test only starts programs under mpirun, it checks no refusal
mod programs;

/// The number after `label` on its line of `out`.
fn count(out: &str, label: &str) -> usize {
    let line = out.lines().find(|l| l.starts_with(label));
    let value = line.and_then(|l| l[label.len()..].trim().parse().ok());
    value.unwrap_or_else(|| panic!("{label:?} in:\n{out}"))
}

/// orthtree's leaf counts of the fractal at `level` before and after serial balance.
fn ours<const D: usize>(level: u8, connect: Connectivity) -> (usize, usize) {
    let mut tree = fractal::<D>(level);
    let before = tree.leaf_count();
    tree.balance(connect);
    (before, tree.leaf_count())
}

#[test]
fn p4est_balances_the_fractal_to_the_same_leaves_as_orthtree() {
    let exe = Path::new(env!("CARGO_BIN_EXE_p4est_balance"));
    for (dim, level) in [(2, 7), (3, 5)] {
        for (name, connect) in [
            ("face", Connectivity::Face),
            ("edge", Connectivity::Edge),
            ("corner", Connectivity::Corner),
        ] {
            let want = match dim {
                2 => ours::<2>(level, connect),
                _ => ours::<3>(level, connect),
            };
            let (dim_arg, level_arg) = (dim.to_string(), level.to_string());
            let args = ["--dim", &dim_arg, "--level", &level_arg, "--connect", name];
            for np in [1, 2] {
                let r = programs::mpirun(np, exe, &args, Duration::from_secs(120));
                assert_eq!(r.code, 0, "{args:?} at {np} ranks: {}", r.stderr);
                let got = (
                    count(&r.stdout, "leaves before balance:"),
                    count(&r.stdout, "leaves after balance:"),
                );
                assert_eq!(got, want, "{args:?} at {np} ranks:\n{}", r.stdout);
            }
        }
    }
}
