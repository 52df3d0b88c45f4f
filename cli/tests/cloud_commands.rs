//! `orthtree cloud` run as a user runs it: every command answers `--help`; bad arguments and
//! oversized work are refused with exit 2 and one `error:` line, bad files with exit 1; on the
//! built-in scan and on small files made here, the counts printed and the PLY files written
//! equal what the library computes on the same points, and the saved trees (in memory and out
//! of core) equal the library's bytes.

use orthtree::cloud::voxel::{Representative, VoxelGrid};
use orthtree::cloud::{outliers, Cloud};
use orthtree::io::{ply, xyz};
use std::path::Path;
use std::time::Duration;

#[path = "../../tests/programs/mod.rs"]
mod programs;

#[path = "../src/cloud/scan.rs"]
#[allow(dead_code)]
mod scan;

use programs::{scratch_dir, Run};

const COMMANDS: [&str; 5] = ["info", "downsample", "outliers", "diff", "index"];

/// Runs `orthtree cloud args` in `cwd` (a fresh folder when `None`).
fn run_in(args: &[&str], cwd: Option<&Path>) -> Run {
    let exe = Path::new(env!("CARGO_BIN_EXE_orthtree"));
    let all: Vec<&str> = std::iter::once("cloud")
        .chain(args.iter().copied())
        .collect();
    programs::run(exe, "cloud", &all, cwd, Duration::from_secs(120))
}

fn ok(args: &[&str], cwd: &Path) -> String {
    let r = run_in(args, Some(cwd));
    assert_eq!(r.code, 0, "cloud {args:?}: {}", r.stderr);
    r.stdout
}

/// The number after `label` in `out` (the first run of digits).
fn number_after(out: &str, label: &str) -> u64 {
    let at = out
        .find(label)
        .unwrap_or_else(|| panic!("{label:?} in {out}"))
        + label.len();
    let digits: String = out[at..]
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_digit())
        .collect();
    digits
        .parse()
        .unwrap_or_else(|_| panic!("a number after {label:?} in {out}"))
}

fn read_ply(path: &Path) -> Cloud<f64> {
    ply::read(std::fs::File::open(path).unwrap()).unwrap()
}

#[test]
fn every_cloud_command_answers_help() {
    let r = run_in(&["--help"], None);
    assert_eq!(r.code, 0, "{}", r.stderr);
    for name in COMMANDS {
        assert!(r.stdout.contains(name), "cloud --help lists {name}");
        let r = run_in(&[name, "--help"], None);
        assert_eq!(r.code, 0, "{name}: {}", r.stderr);
        assert!(
            r.stdout.contains(&format!("Usage: orthtree cloud {name}")),
            "{}",
            r.stdout
        );
        assert!(r.stdout.contains("Exit codes:"), "{name}: {}", r.stdout);
    }
}

#[test]
fn bad_arguments_and_oversized_work_are_refused() {
    let refused = |args: &[&str], named: &[&str]| {
        let r = run_in(args, None);
        programs::refusal(&r, "cloud", args, named, "--help");
    };
    for bad in ["0", "-1", "nan", "inf", "x"] {
        refused(&["downsample", "--voxel", bad], &["--voxel"]);
        refused(&["diff", "--voxel", bad], &["--voxel"]);
    }
    refused(&["downsample"], &["required arguments"]);
    refused(&["outliers", "--k", "0"], &["--k"]);
    refused(&["outliers", "--ratio", "nan"], &["--ratio"]);
    refused(&["index", "--budget", "1k"], &["--budget"]);
    refused(&["index", "--budget", "99999999999G"], &["--budget"]);
    refused(&["index", "--bucket-size", "0"], &["--bucket-size"]);
    refused(&["info", "a.obj"], &["a.obj", "extension"]);
    refused(&["diff", "--voxel", "1", "a.ply"], &["two clouds"]);
    refused(&["info", "--out-of-nowhere"], &["--out-of-nowhere"]);
    refused(
        &[
            "downsample",
            "--voxel",
            "1",
            "--out",
            "no/such/folder/x.ply",
        ],
        &["--out"],
    );
    // work the arguments make too large: a grid finer than 2^21 voxels, a scan beyond memory
    refused(
        &["downsample", "--points", "1000", "--voxel", "1e-9"],
        &["--voxel", "2^21"],
    );
    refused(&["info", "--points", "4000000000"], &["--points"]);
    #[cfg(not(feature = "las"))]
    refused(&["info", "scan.LAS"], &["--features las"]);
}

#[test]
fn unreadable_files_exit_1_naming_them() {
    let dir = scratch_dir("cloud-bad");
    std::fs::write(
        dir.join("bad.ply"),
        b"ply\nformat ascii 1.0\nelement vertex 2\n",
    )
    .unwrap();
    std::fs::write(dir.join("bad.xyz"), b"1 2 3\n4 five 6\n").unwrap();
    for (file, named) in [
        ("missing.ply", "missing.ply"),
        ("bad.ply", "bad.ply"),
        ("bad.xyz", "line 2"),
    ] {
        let r = run_in(&["info", file], Some(&dir));
        assert_eq!(r.code, 1, "{file}: {}", r.stderr);
        let first = r.stderr.lines().next().unwrap_or_default();
        assert!(
            first.starts_with("error: ") && first.contains(named),
            "{file}: {first}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_built_in_scan_against_the_library() {
    let dir = scratch_dir("cloud-scan");
    let n = "20000";
    let cloud = scan::scan(1, 20_000, 0);
    // info: the count, the attributes, the picture
    let out = ok(&["info", "--points", n], &dir);
    assert_eq!(
        number_after(&out, "scan (seed 1, epoch 0, 20000 points):"),
        20_000
    );
    assert!(out.contains("intensity, classification"), "{out}");
    let grid = VoxelGrid::with_size(&cloud.points, 1.0).unwrap();
    let voxels = grid
        .voxels(&grid.tree(&cloud.entries().unwrap()).unwrap())
        .unwrap();
    assert_eq!(
        number_after(&out, "occupied voxels of side 1:"),
        voxels.len() as u64
    );
    let picture = if cfg!(feature = "png") {
        "density.png"
    } else {
        "density.svg"
    };
    assert!(dir.join(picture).metadata().unwrap().len() > 100);
    // downsample: the PLY read back equals the library's result
    for (rep, which) in [
        ("centroid", Representative::Centroid),
        ("nearest", Representative::Nearest),
    ] {
        let out = ok(
            &[
                "downsample",
                "--points",
                n,
                "--voxel",
                "2",
                "--representative",
                rep,
            ],
            &dir,
        );
        let grid = VoxelGrid::with_size(&cloud.points, 2.0).unwrap();
        let want = grid.downsample(&cloud, which).unwrap();
        assert_eq!(number_after(&out, "20000 points ->"), want.len() as u64);
        assert_eq!(read_ply(&dir.join("downsampled.ply")), want, "{rep}");
    }
    // outliers: the points kept
    let out = ok(
        &["outliers", "--points", n, "--k", "8", "--ratio", "1.5"],
        &dir,
    );
    let (kept, _) = outliers::remove_statistical(&cloud, 8, 1.5).unwrap();
    assert_eq!(
        number_after(&out, "outliers:"),
        (cloud.len() - kept.len()) as u64
    );
    assert!(kept.len() < cloud.len());
    assert_eq!(read_ply(&dir.join("inliers.ply")), kept);
    // diff: the XOR of the two epochs' occupancies
    let out = ok(&["diff", "--points", n, "--voxel", "2"], &dir);
    let later = scan::scan(1, 20_000, 1);
    let mut both = orthtree::Aabb::new(cloud.points[0], cloud.points[0]).unwrap();
    for p in cloud.points.iter().chain(&later.points) {
        for (k, &x) in p.iter().enumerate() {
            both.min[k] = both.min[k].min(x);
            both.max[k] = both.max[k].max(x);
        }
    }
    let grid = VoxelGrid::for_box(&both, 2.0).unwrap();
    let (a, b) = (
        grid.occupancy_of(&cloud.points).unwrap(),
        grid.occupancy_of(&later.points).unwrap(),
    );
    let changed = a.symmetric_difference_len(&b);
    assert!(changed > 0);
    assert_eq!(number_after(&out, "change:"), changed);
    let map = read_ply(&dir.join("changes.ply"));
    assert_eq!(map.len() as u64, changed);
    let signs = map.attributes.extra_column("change").unwrap();
    assert_eq!(
        signs.iter().filter(|&&s| s < 0.0).count() as u64,
        a.difference_len(&b)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn index_in_memory_and_out_of_core_write_the_library_s_bytes() {
    let dir = scratch_dir("cloud-index");
    let cloud = scan::scan(3, 30_000, 0);
    let tree = orthtree::PointTree::builder()
        .bucket_size(16)
        .build(&cloud.entries().unwrap())
        .unwrap();
    let mut want = Vec::new();
    orthtree::io::saved::write_point_tree(&tree, &mut want).unwrap();
    let base = [
        "index",
        "--points",
        "30000",
        "--seed",
        "3",
        "--bucket-size",
        "16",
    ];
    let out = ok(&[&base[..], &["--out", "a.tree"]].concat(), &dir);
    assert!(out.contains("30000 points"), "{out}");
    // the loaded tree and the map answer the same column (the command fails otherwise)
    assert!(out.contains("(owned tree)"), "{out}");
    assert!(out.contains("centre of the points' bounds"), "{out}");
    assert!(
        std::fs::read(dir.join("a.tree")).unwrap() == want,
        "in memory"
    );
    for budget in ["1M", "4M", "1G"] {
        let out = ok(
            &[&base[..], &["--out", "b.tree", "--budget", budget]].concat(),
            &dir,
        );
        assert!(
            std::fs::read(dir.join("b.tree")).unwrap() == want,
            "budget {budget}"
        );
        assert!(out.contains("through the map"), "{out}");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert!(
            !names.iter().any(|n| n.to_string_lossy().ends_with(".tmp")),
            "{names:?}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn small_files_by_extension_whatever_the_case() {
    let dir = scratch_dir("cloud-files");
    let mut cloud = Cloud::from_points(
        (0..500)
            .map(|i| {
                [
                    (i % 10) as f64 * 0.5,
                    (i / 10 % 10) as f64 * 0.5,
                    (i / 100) as f64 * 0.25,
                ]
            })
            .collect(),
    );
    cloud.attributes.intensity = Some((0..500).map(|i| i as u16).collect());
    ply::write(
        &cloud,
        ply::Encoding::Ascii,
        std::fs::File::create(dir.join("c.PLY")).unwrap(),
    )
    .unwrap();
    xyz::write(&cloud, std::fs::File::create(dir.join("c.Xyz")).unwrap()).unwrap();
    xyz::write(&cloud, std::fs::File::create(dir.join("c.csv")).unwrap()).unwrap();
    let grid = VoxelGrid::with_size(&cloud.points, 1.0).unwrap();
    let want = grid.downsample(&cloud, Representative::Centroid).unwrap();
    for file in ["c.PLY", "c.Xyz", "c.csv"] {
        let out = ok(
            &["downsample", file, "--voxel", "1", "--out", "d.ply"],
            &dir,
        );
        assert_eq!(
            number_after(&out, "500 points ->"),
            want.len() as u64,
            "{file}"
        );
        let got = read_ply(&dir.join("d.ply"));
        assert_eq!(got.points, want.points, "{file}");
        assert_eq!(
            got.attributes.intensity, want.attributes.intensity,
            "{file}"
        );
        let out = ok(&["info", file, "--no-files"], &dir);
        assert_eq!(number_after(&out, &format!("{file}:")), 500, "{out}");
    }
    // a diff of a file with itself changes nothing
    let out = ok(&["diff", "c.PLY", "c.csv", "--voxel", "0.5"], &dir);
    assert_eq!(number_after(&out, "change:"), 0, "{out}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An uncompressed LAS file indexed from its coordinates alone, in memory and streamed out of
/// core: both write the bytes of the library's tree of the file's world coordinates.
#[cfg(feature = "las")]
#[test]
fn index_of_a_las_file_in_memory_and_streamed_out_of_core() {
    use orthtree::cloud::Frame;
    let dir = scratch_dir("cloud-index-las");
    let mut cloud: Cloud<i32> = Cloud::from_points(
        (0..20_000)
            .map(|i: i32| [i % 150 * 40, i / 150 * 40, (i * 7919) % 1000])
            .collect(),
    );
    cloud.frame = Frame {
        scale: [0.01, 0.01, 0.001],
        offset: [500_000.0, 4_000_000.0, 10.0],
    };
    orthtree::io::las::write(&cloud, dir.join("scan.las"), false).unwrap();
    let entries: Vec<([f64; 3], u32)> = cloud.world_points().into_iter().zip(0..).collect();
    let tree = orthtree::PointTree::builder()
        .bucket_size(16)
        .build(&entries)
        .unwrap();
    let mut want = Vec::new();
    orthtree::io::saved::write_point_tree(&tree, &mut want).unwrap();
    let base = [
        "index",
        "scan.las",
        "--bucket-size",
        "16",
        "--out",
        "a.tree",
    ];
    let out = ok(&base, &dir);
    assert!(out.contains("20000 points (coordinates only)"), "{out}");
    assert!(
        std::fs::read(dir.join("a.tree")).unwrap() == want,
        "in memory"
    );
    for budget in ["1M", "64M"] {
        let out = ok(&[&base[..], &["--budget", budget]].concat(), &dir);
        assert!(out.contains("(streamed)"), "{out}");
        assert!(
            std::fs::read(dir.join("a.tree")).unwrap() == want,
            "budget {budget}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// LAS and LAZ input (features `las`, `laz`): the cloud in world coordinates (scale and offset
/// applied), downsampled as the library does.
#[cfg(feature = "laz")]
#[test]
fn las_and_laz_files_in_world_coordinates() {
    use orthtree::cloud::Frame;
    let dir = scratch_dir("cloud-las");
    let mut cloud: Cloud<i32> = Cloud::from_points(
        (0..400)
            .map(|i| [i % 20 * 50, i / 20 * 50, i % 7 * 10])
            .collect(),
    );
    cloud.frame = Frame {
        scale: [0.01; 3],
        offset: [1000.0, 2000.0, 5.0],
    };
    orthtree::io::las::write(&cloud, dir.join("c.LAS"), false).unwrap();
    orthtree::io::las::write(&cloud, dir.join("c.laz"), true).unwrap();
    let world = Cloud::from_points(cloud.world_points());
    let grid = VoxelGrid::with_size(&world.points, 1.0).unwrap();
    let want = grid.downsample(&world, Representative::Centroid).unwrap();
    for file in ["c.LAS", "c.laz"] {
        let out = ok(
            &["downsample", file, "--voxel", "1", "--out", "d.ply"],
            &dir,
        );
        assert_eq!(
            number_after(&out, "400 points ->"),
            want.len() as u64,
            "{file}"
        );
        assert_eq!(read_ply(&dir.join("d.ply")).points, want.points, "{file}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
