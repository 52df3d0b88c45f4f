/* p4est's fractal refinement (its timings example), then p4est_balance: the workload of
 * orthtree's `dist_balance` example, at any rank count, for the comparison crate's
 * `p4est_balance` program. Compiled twice by the build script: for 2D, and with -DP4_TO_P8 for
 * 3D (p4est's own renaming header).
 *
 *   p4est_balance_2d LEVEL face|edge|corner REPS
 *
 * Prints the leaf counts before and after balance and the balance time (maximum over ranks,
 * median of REPS runs, each on a fresh copy of the refined forest). Like `dist_balance`, the
 * uniform level L - 4 is split evenly over the ranks and the refinement is not repartitioned. */
#ifdef P4_TO_P8
#include <p4est_to_p8est.h>
#include <p8est_bits.h>
#include <p8est_extended.h>
#else
#include <p4est_bits.h>
#include <p4est_extended.h>
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int refine_level;

/* The fractal: every cell above L - 4; below, a cell whose child id has an even number of set
 * bits (0 or 3 in 2D; 0, 3, 5 or 6 in 3D), down to level L. */
static int refine_fractal(p4est_t *p4est, p4est_topidx_t which_tree, p4est_quadrant_t *q) {
  int qid, bits;
  (void) p4est;
  (void) which_tree;
  if ((int) q->level >= refine_level) {
    return 0;
  }
  if ((int) q->level < refine_level - 4) {
    return 1;
  }
  qid = p4est_quadrant_child_id(q);
  bits = (qid & 1) + ((qid >> 1) & 1) + ((qid >> 2) & 1);
  return bits % 2 == 0;
}

static int compare_double(const void *a, const void *b) {
  double x = *(const double *) a, y = *(const double *) b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  int rank, reps, i, uniform;
  p4est_connect_type_t btype;
  p4est_connectivity_t *conn;
  p4est_t *p4est, *copy;
  double *times;
  long long before, after = 0;

  sc_MPI_Init(&argc, &argv);
  sc_MPI_Comm_rank(sc_MPI_COMM_WORLD, &rank);
  if (argc != 4) {
    if (rank == 0) {
      fprintf(stderr, "usage: %s LEVEL face|edge|corner REPS\n", argv[0]);
    }
    sc_MPI_Finalize();
    return 2;
  }
  refine_level = atoi(argv[1]);
  reps = atoi(argv[3]);
  if (refine_level < 0 || refine_level > P4EST_QMAXLEVEL || reps < 1 || reps > 100) {
    if (rank == 0) {
      fprintf(stderr, "error: LEVEL 0..%d and REPS 1..100\n", P4EST_QMAXLEVEL);
    }
    sc_MPI_Finalize();
    return 2;
  }
  if (strcmp(argv[2], "face") == 0) {
    btype = P4EST_CONNECT_FACE;
#ifdef P4_TO_P8
  } else if (strcmp(argv[2], "edge") == 0) {
    btype = P8EST_CONNECT_EDGE;
#else
  } else if (strcmp(argv[2], "edge") == 0) {
    btype = P4EST_CONNECT_FULL;
#endif
  } else if (strcmp(argv[2], "corner") == 0) {
    btype = P4EST_CONNECT_FULL;
  } else {
    if (rank == 0) {
      fprintf(stderr, "error: connect %s: expected face, edge or corner\n", argv[2]);
    }
    sc_MPI_Finalize();
    return 2;
  }
  sc_init(sc_MPI_COMM_WORLD, 0, 0, NULL, SC_LP_ERROR);
  p4est_init(NULL, SC_LP_ERROR);
#ifdef P4_TO_P8
  conn = p8est_connectivity_new_unitcube();
#else
  conn = p4est_connectivity_new_unitsquare();
#endif
  uniform = refine_level >= 4 ? refine_level - 4 : 0;
  p4est = p4est_new_ext(sc_MPI_COMM_WORLD, conn, 0, uniform, 1, 0, NULL, NULL);
  p4est_refine(p4est, 1, refine_fractal, NULL);
  before = (long long) p4est->global_num_quadrants;
  times = malloc(sizeof(double) * (size_t) reps);
  for (i = 0; i < reps; i++) {
    double t, most;
    copy = p4est_copy(p4est, 0);
    sc_MPI_Barrier(sc_MPI_COMM_WORLD);
    t = sc_MPI_Wtime();
    p4est_balance(copy, btype, NULL);
    t = sc_MPI_Wtime() - t;
    sc_MPI_Allreduce(&t, &most, 1, sc_MPI_DOUBLE, sc_MPI_MAX, sc_MPI_COMM_WORLD);
    times[i] = most;
    after = (long long) copy->global_num_quadrants;
    p4est_destroy(copy);
  }
  qsort(times, (size_t) reps, sizeof(double), compare_double);
  if (rank == 0) {
    printf("p4est_balance: dim %d, level %d, %s\n", P4EST_DIM, refine_level, argv[2]);
    printf("leaves before balance: %lld\n", before);
    printf("leaves after balance:  %lld\n", after);
    printf("balance time:          %.4f s (median of %d)\n", times[reps / 2], reps);
  }
  free(times);
  p4est_destroy(p4est);
  p4est_connectivity_destroy(conn);
  sc_finalize();
  sc_MPI_Finalize();
  return 0;
}
