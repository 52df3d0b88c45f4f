"""scipy's cKDTree on the workloads of `joins_compare`, over the points the Rust side wrote.

Reads little-endian f64 points (DIM per point, row after row) from POINTS, builds cKDTree with
its defaults (leafsize 16, balanced, compact nodes) and runs one workload; prints its timings
(medians of REPS runs after one untimed warm-up, in milliseconds) and its answers, one
`key value` line each:

    build <ms>          the median build time
    query <ms>          the median time of the workload
    count <n>           answers over the workload (neighbours, pairs)
    items <n>           the sum of the answers' indices, where they cannot tie
    dist2 <x>           the sum of the answers' squared distances
    counts <c1,c2,...>  count_neighbors' counts, one per radius

Workloads:
    periodic  --queries FILE --k K --boxsize L  k nearest of each query, boxsize L on every axis
    knn       --k K --workers W                 the K nearest others of every point (query with
                                                 k = K + 1 on the points themselves)
    pairs     --r R [--output ndarray|set]      query_pairs(R): the pairs as an array (its fastest
                                                 form), or as scipy returns them by default, a
                                                 set of (i, j) tuples
    count     --radii R1,R2,...                 count_neighbors(self, radii)
"""

import argparse
import statistics
import sys
import time

import numpy as np
from scipy.spatial import cKDTree


def median_ms(reps, f):
    """The median time of `reps` runs of `f` in ms after one untimed run, and its last result."""
    result = f()
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        result = f()
        times.append((time.perf_counter() - start) * 1e3)
    return statistics.median(times), result


def read_points(path, dim):
    """The points of file `path`, as an (n, dim) array."""
    raw = np.fromfile(path, dtype="<f8")
    if raw.size % dim != 0:
        sys.exit(f"error: {path} holds {raw.size} values, not a multiple of {dim}")
    return raw.reshape(-1, dim)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("workload", choices=["periodic", "knn", "pairs", "count"])
    ap.add_argument("points")
    ap.add_argument("dim", type=int)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--queries")
    ap.add_argument("--k", type=int, default=10)
    ap.add_argument("--boxsize", type=float)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--r", type=float)
    ap.add_argument("--radii")
    ap.add_argument("--output", choices=["ndarray", "set"], default="ndarray")
    a = ap.parse_args()
    pts = read_points(a.points, a.dim)
    boxsize = a.boxsize if a.workload == "periodic" else None
    build, tree = median_ms(a.reps, lambda: cKDTree(pts, boxsize=boxsize))
    print(f"build {build!r}")
    if a.workload == "periodic":
        qs = read_points(a.queries, a.dim)
        t, (d, i) = median_ms(a.reps, lambda: tree.query(qs, k=a.k))
        print(f"query {t!r}")
        print(f"count {d.size}")
        print(f"items {int(i.sum(dtype=np.int64))}")
        print(f"dist2 {float(np.square(d).sum())!r}")
    elif a.workload == "knn":
        t, (d, _) = median_ms(a.reps, lambda: tree.query(pts, k=a.k + 1, workers=a.workers))
        print(f"query {t!r}")
        # Column 0 is the point itself (distance 0; the points have no duplicates).
        print(f"count {d[:, 1:].size}")
        print(f"dist2 {float(np.square(d[:, 1:]).sum())!r}")
    elif a.workload == "pairs":
        t, p = median_ms(a.reps, lambda: tree.query_pairs(a.r, output_type=a.output))
        print(f"query {t!r}")
        print(f"count {len(p)}")
        if a.output == "set":
            p = np.array(list(p), dtype=np.int64).reshape(-1, 2)
        print(f"items {int(p.sum(dtype=np.int64))}")
    else:
        radii = np.array([float(x) for x in a.radii.split(",")])
        t, c = median_ms(a.reps, lambda: tree.count_neighbors(tree, radii))
        print(f"query {t!r}")
        print("counts " + ",".join(str(int(x)) for x in c))


if __name__ == "__main__":
    main()
