/*---------------------------------------------------------------------------*\
  demFoam / Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  triad - memory bandwidth of this machine as the DEM step sees it: the
  STREAM triad a[i] = b[i] + s c[i] (McCalpin's STREAM benchmark kernel)
  over three double arrays whose total size is given, best of REPS passes.
  Bandwidth counts 24 bytes per element (two reads, one write; the
  write-allocate read of a is not counted, as in STREAM).

  Usage: triad TOTAL_BYTES [REPS]
  Output: triad_bytes=<total> triad_best_GB_per_s=<GB/s> triad_mean_GB_per_s=<GB/s>
  (bench/dem/profile runs it at the working-set size of each bed and at
  1.5 GB, beyond every cache).
\*---------------------------------------------------------------------------*/
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    timespec_get(&t, TIME_UTC);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: triad TOTAL_BYTES [REPS]\n");
        return 2;
    }
    const double total = strtod(argv[1], NULL);
    const int reps = argc == 3 ? atoi(argv[2]) : 0;
    const size_t n = (size_t)(total / 24.0);
    if (n < 1024) { fprintf(stderr, "triad: TOTAL_BYTES too small\n"); return 2; }
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *c = malloc(n * sizeof *c);
    if (!a || !b || !c) { fprintf(stderr, "triad: out of memory\n"); return 1; }
    for (size_t i = 0; i < n; ++i) { a[i] = 0.0; b[i] = 1.0 + 1e-9 * (double)i; c[i] = 2.0; }
    /* enough passes for ~0.5 s of work at 20 GB/s unless given */
    const int np = reps > 0 ? reps : (int)(1e10 / (24.0 * (double)n)) + 5;
    const double s = 3.0;
    double best = 1e300, sum = 0.0, chk = 0.0;
    for (int r = 0; r < np; ++r) {
        const double t0 = now();
        for (size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
        const double t = now() - t0;
        chk += a[r % n];
        b[0] += 1e-300;            /* keeps the passes from being merged */
        if (r > 0) { sum += t; if (t < best) best = t; }   /* the first pass warms the caches */
    }
    const double bytes = 24.0 * (double)n;
    printf("triad_bytes=%.0f\ntriad_passes=%d\ntriad_best_GB_per_s=%.2f\ntriad_mean_GB_per_s=%.2f\n", bytes, np,
           bytes / best * 1e-9, bytes / (sum / (np - 1)) * 1e-9);
    if (chk == 12345.678) printf("\n");  /* uses the results */
    free(a); free(b); free(c);
    return 0;
}
