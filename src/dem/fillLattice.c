/*---------------------------------------------------------------------------*\
  demFoam DEM core - filling a box or cylinder on a jittered lattice.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  The region is cut into layers (along z for a box, along the axis for a
  cylinder) of cubic cells of edge s; a cell counts when it lies inside the
  region.  s is the largest spacing with at least n cells; the n particles
  take the full layers from the bottom up and, in the last layer, the cells
  with the smallest hash of their index.  Particle g (global cell index)
  draws its diameter, density and a jitter of its centre within its cell
  (at most (s - d)/2 per direction, so no two overlap) from a random stream
  seeded by (dem_config.seed, first id + g): every particle is a function of
  its index alone.  So a processor of a decomposed run (keep filter, keep
  box) computes only the cells near its part, with no shadow list: O(N/P)
  work and memory; the counting costs one layer, O(N^(2/3)).
  docs/demProperties.md, "arrangement lattice".
\*---------------------------------------------------------------------------*/
#include "fillFrame.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef dem_fill_frame frame;

/* cells along one axis of extent L and their first centre */
static long ncells(double L, double s, double *c0)
{
    double m = floor(L / s * (1 + 1e-12));
    if (!(m >= 0)) m = 0;
    *c0 = 0.5 * (L - m * s) + 0.5 * s;
    return (long)m;
}

/* whether in-layer cell (a, b) (centre coordinates from o) is inside */
static int cell_in(const frame *f, double a, double b, double s)
{
    if (f->R <= 0) return 1;
    double ca = fabs(a - f->R) + 0.5 * s, cb = fabs(b - f->R) + 0.5 * s;
    return ca * ca + cb * cb <= f->R * f->R;
}

/* cells per layer and layers at spacing s */
static size_t count_cells(const frame *f, double s, long *nl)
{
    double c0[3];
    long m[3];
    for (int k = 0; k < 3; ++k) m[k] = ncells(f->len[k], s, &c0[k]);
    size_t per = 0;
    for (long j = 0; j < m[1]; ++j)
        for (long i = 0; i < m[0]; ++i)
            per += (size_t)cell_in(f, c0[0] + i * s, c0[1] + j * s, s);
    *nl = m[2];
    return per;
}

typedef struct { uint64_t h; size_t j; } hkey;
static int by_hash(const void *a, const void *b)
{
    const hkey *p = a, *q = b;
    return p->h < q->h ? -1 : p->h > q->h ? 1 : (p->j < q->j ? -1 : p->j > q->j);
}

static dem_status fill_lattice(dem_world *w, const frame *f, size_t n, const dem_particle_template *t,
                               size_t *inserted, const char *fn)
{
    if (inserted) *inserted = 0;
    double dmax;
    dem_status st = dem_template_check(w, t, &dmax, fn);
    if (st) return st;
    if (n == 0) return DEM_OK;
    /* the region must be free of particles placed before (this fill checks
       no overlaps with them) */
    if ((st = dem_fill_region_free(w, f, fn))) return st;
    /* the largest spacing with at least n cells (bisection; cells(s) is
       not strictly monotone, any s with enough cells will do) */
    long nl;
    size_t per = count_cells(f, dmax, &nl);
    if ((double)per * (double)nl < (double)n)
        return DEM_FAIL(w, DEM_ERR_FULL, "%s: placed 0 of %zu particles: %zu cells of the largest diameter %g "
                        "fit (lattice)", fn, n, per * (size_t)nl, dmax);
    double slo = dmax, shi = fmax(fmax(f->len[0], f->len[1]), f->len[2]);
    for (int it = 0; it < 60; ++it) {
        double s = 0.5 * (slo + shi);
        per = count_cells(f, s, &nl);
        if ((double)per * (double)nl >= (double)n) slo = s; else shi = s;
    }
    const double s = slo;
    per = count_cells(f, s, &nl);
    double c0[3];
    long m[3];
    for (int k = 0; k < 3; ++k) m[k] = ncells(f->len[k], s, &c0[k]);
    const size_t full = n / per, rest = n % per;

    /* in-layer cells in row order; the chosen ones of the last layer */
    size_t *cells = malloc(per * sizeof *cells);       /* i + m0 j */
    unsigned char *last = calloc(per, 1);
    hkey *hk = malloc(per * sizeof *hk);
    size_t *rank = malloc(per * sizeof *rank);         /* index among the chosen of the last layer */
    if (!cells || !last || !hk || !rank) {
        free(cells); free(last); free(hk); free(rank);
        return DEM_FAIL(w, DEM_ERR_NOMEM, "%s: %zu cells per layer", fn, per);
    }
    size_t c = 0;
    for (long j = 0; j < m[1]; ++j)
        for (long i = 0; i < m[0]; ++i)
            if (cell_in(f, c0[0] + i * s, c0[1] + j * s, s)) cells[c++] = (size_t)i + (size_t)m[0] * (size_t)j;
    const int64_t base = w->next_id;
    for (size_t q = 0; q < per; ++q) { hk[q].h = dem_mix64(w->cfg.seed ^ dem_mix64((uint64_t)base + q)); hk[q].j = q; }
    qsort(hk, per, sizeof *hk, by_hash);
    for (size_t q = 0; q < rest; ++q) last[hk[q].j] = 1;
    for (size_t q = 0, r = 0; q < per; ++q) rank[q] = last[q] ? r++ : 0;
    free(hk);

    /* the layers and rows near the keep box (all without one) */
    long lo[3] = {0, 0, 0}, hi[3] = {m[0] - 1, m[1] - 1, (long)full - (rest ? 0 : 1)};
    double mn[3], mx[3];
    if (dem_fill_keep_extent(w, f, mn, mx)) {
        for (int a = 0; a < 3; ++a) {
            /* cells whose centre is within one spacing of the box */
            double l = fmax(floor((mn[a] - c0[a]) / s) - 1, (double)lo[a]);
            double h = fmin(ceil((mx[a] - c0[a]) / s) + 1, (double)hi[a]);
            if (!(l <= h)) { l = 1; h = 0; }
            lo[a] = (long)l; hi[a] = (long)h;
        }
    }

    uint64_t saved[4];
    memcpy(saved, w->rng, sizeof saved);
    st = DEM_OK;
    for (long k = lo[2]; k <= hi[2] && !st; ++k) {
        const int partial = (size_t)k == full;
        for (size_t q = 0; q < per && !st; ++q) {
            const long i = (long)(cells[q] % (size_t)m[0]), j = (long)(cells[q] / (size_t)m[0]);
            if (i < lo[0] || i > hi[0] || j < lo[1] || j > hi[1]) continue;
            if (partial && !last[q]) continue;
            const size_t g = (size_t)k * per + (partial ? rank[q] : q);
            dem_rng_seed(w, dem_mix64(w->cfg.seed) ^ dem_mix64((uint64_t)base + g + 0x5bd1e995ull));
            const double d = dem_dist_draw(w, &t->diameter), rho = dem_dist_draw(w, &t->density);
            const double cc[3] = {c0[0] + i * s, c0[1] + j * s, c0[2] + k * s};
            double off[3], x[3];
            for (int a = 0; a < 3; ++a) off[a] = cc[a] + (2 * dem_rng_uniform(w) - 1) * 0.5 * (s - d);
            dem_fill_frame_point(f, off, x);
            if (w->keep && !w->keep(x, w->keep_user)) continue;
            st = dem_fill_append(w, t, base + (int64_t)g, x, 0.5 * d, rho);
        }
    }
    memcpy(w->rng, saved, sizeof saved);
    free(cells); free(last); free(rank);
    if (st) return st;
    dem_fill_done(w, base, n, inserted);
    return DEM_OK;
}

dem_status dem_world_fill_lattice_box(dem_world *w, const double lo[3], const double hi[3], size_t n,
                                     const dem_particle_template *t, size_t *inserted)
{
    return dem_fill_in_box(w, "fill_lattice_box", fill_lattice, lo, hi, n, t, inserted);
}

dem_status dem_world_fill_lattice_cylinder(dem_world *w, const double base[3], const double axis[3],
                                          double radius, double length, size_t n,
                                          const dem_particle_template *t, size_t *inserted)
{
    return dem_fill_in_cylinder(w, "fill_lattice_cylinder", fill_lattice, base, axis, radius, length, n, t, inserted);
}
