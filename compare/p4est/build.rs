//! With the feature `p4est`: compiles the p4est driver (`balance.c`, beside this script) twice
//! with the MPI C compiler (`mpicc`, or the one `MPICC` names), for 2D and 3D, against the
//! system's p4est 2.2 (`libp4est-dev`), and hands their paths to `p4est_balance`. Without the
//! feature it does nothing, so the default build needs neither MPI nor p4est.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=balance.c");
    println!("cargo:rerun-if-env-changed=MPICC");
    if std::env::var_os("CARGO_FEATURE_P4EST").is_none() {
        return;
    }
    compile();
}

#[cfg(feature = "p4est")]
fn compile() {
    use std::path::PathBuf;
    use std::process::Command;
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let mpicc = std::env::var("MPICC").unwrap_or_else(|_| "mpicc".into());
    for (dim, define) in [(2, None), (3, Some("-DP4_TO_P8"))] {
        let exe = out.join(format!("p4est_balance_{dim}d"));
        let compiler = cc::Build::new()
            .compiler(&mpicc)
            .opt_level(2)
            .warnings(true)
            .get_compiler();
        let mut cmd: Command = compiler.to_command();
        cmd.args(define).arg("-o").arg(&exe).arg("balance.c");
        cmd.args(["-lp4est", "-lsc", "-lm"]);
        let status = cmd
            .status()
            .unwrap_or_else(|e| panic!("{mpicc} could not run ({e}): install libopenmpi-dev"));
        assert!(
            status.success(),
            "compiling balance.c failed: install libp4est-dev (p4est 2.2)"
        );
        println!("cargo:rustc-env=P4EST_BALANCE_{dim}D={}", exe.display());
    }
}

#[cfg(not(feature = "p4est"))]
fn compile() {}
