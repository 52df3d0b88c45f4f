"""Open3D's point-cloud operations on the workloads of `cloud_compare`, over the points the Rust
side wrote.

Reads little-endian f64 points (3 per point, row after row) from POINTS into an
`open3d.geometry.PointCloud` and runs one workload; prints its timings (medians of REPS runs
after one untimed warm-up, in milliseconds) and its answers, one `key value` line each:

    build <ms>    the median time of making the PointCloud from the numpy array
    query <ms>    the median time of the workload
    count <n>     points out (voxels of the downsampled cloud, points kept)
    dist2 <x>     the sum of the output points' squared norms (a checksum of where they are)

Workloads:
    voxel     --size S             voxel_down_sample(S): one point per voxel, the centroid
    outliers  --k K --ratio R      remove_statistical_outlier(K, R): K neighbours, the point
                                   itself among them
"""

import argparse
import statistics
import sys
import time

import numpy as np
import open3d as o3d


def median_ms(reps, f):
    """The median time of `reps` runs of `f` in ms after one untimed run, and its last result."""
    result = f()
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        result = f()
        times.append((time.perf_counter() - start) * 1e3)
    return statistics.median(times), result


def read_points(path):
    """The points of file `path`, as an (n, 3) array."""
    raw = np.fromfile(path, dtype="<f8")
    if raw.size % 3 != 0:
        sys.exit(f"error: {path} holds {raw.size} values, not a multiple of 3")
    return raw.reshape(-1, 3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("workload", choices=["voxel", "outliers"])
    ap.add_argument("points")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--size", type=float)
    ap.add_argument("--k", type=int, default=20)
    ap.add_argument("--ratio", type=float, default=2.0)
    a = ap.parse_args()
    pts = read_points(a.points)
    make = lambda: o3d.geometry.PointCloud(o3d.utility.Vector3dVector(pts))
    build, cloud = median_ms(a.reps, make)
    print(f"build {build!r}")
    if a.workload == "voxel":
        t, out = median_ms(a.reps, lambda: cloud.voxel_down_sample(a.size))
        kept = np.asarray(out.points)
    else:
        t, (out, _) = median_ms(
            a.reps, lambda: cloud.remove_statistical_outlier(a.k, a.ratio)
        )
        kept = np.asarray(out.points)
    print(f"query {t!r}")
    print(f"count {len(kept)}")
    print(f"dist2 {float(np.square(kept).sum())!r}")


if __name__ == "__main__":
    main()
