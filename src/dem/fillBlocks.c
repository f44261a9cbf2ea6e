/*---------------------------------------------------------------------------*\
  demFoam DEM core - random fill of a box or cylinder in blocks, each
  computed from its index, so that a processor of a decomposed run draws
  only the blocks near its part (arrangement randomBlocks).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  The region of the centres (the box, or cylinder, shrunk by the largest
  radius) is cut into blocks of edge at least the largest diameter and about
  four mean spacings (some 64 particles each: smaller blocks jam earlier,
  since a block cannot pass its share on).  The n particles are shared out by stratified
  rounding: layers (along z, or the cylinder's axis) get n times their
  share of the volume, rounded with one random offset; within a layer each
  block its share of the layer's, rounded with the layer's own offset; so a
  block holds the floor or the ceiling of its expected count, and its
  particles have ids from the running sum.  A block then places its
  particles by random sequential addition (fill.c's rule with up to 10 000
  random positions in the block, the first that overlaps nothing placed), from a
  random stream of (seed, first id, block index).  Blocks are placed in
  eight colours, by the parity of their indices: two blocks of one colour
  never touch, so a block depends only on its neighbours of lower colours,
  and those on theirs, at most seven blocks away.  A processor (keep box)
  therefore places the blocks of colour c within 7 - c blocks of the ones
  that meet its keep box, and gets the same particles there as a serial
  run: O(N/P) work and memory per processor, plus one layer's block areas
  (O(N^(2/3))).  docs/demProperties.md, "arrangement randomBlocks".
\*---------------------------------------------------------------------------*/
#include "fillFrame.h"
#include "placementGrid.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BLOCK_TRIES 10000          /* positions per particle (fill.c: 1000; a block cannot pass its share on) */
#define BLOCK_DISC_DRAWS 10000000  /* draws for one position in a block's part of the disc */
#define BLOCK_DEPTH 7              /* highest colour: the dependency reach in blocks */

typedef struct {
    const dem_fill_frame *f;
    double clo[3], chi[3], h[3]; /* centres' region and block edges, frame coordinates */
    long m[3];                   /* blocks per axis */
    double rho;                  /* cylinder: radius of the centres' disc about (R, R); 0: box */
    double *prefix;              /* in-layer block areas summed in row order (m0 m1 + 1) */
    size_t n, per;               /* particles; blocks per layer */
    uint64_t key;                /* stream key of this fill (seed, first id) */
} blocks;

static double unit(uint64_t h) { return (double)(h >> 11) * 0x1.0p-53; }

/* first particle index of layer k (k = m2: n); monotone in k */
static size_t layer_first(const blocks *b, long k)
{
    if (k >= b->m[2]) return b->n;
    const double u = unit(dem_mix64(b->key ^ 0x6c61796572ull));
    const double g = floor((double)b->n * (double)k / (double)b->m[2] + u);
    return g < (double)b->n ? (size_t)g : b->n;
}

/* first particle index of block q of layer k (q = per: the layer's end) */
static size_t block_first(const blocks *b, long k, size_t q)
{
    const size_t g0 = layer_first(b, k), nk = layer_first(b, k + 1) - g0;
    if (q >= b->per) return g0 + nk;
    const double u = unit(dem_mix64(b->key ^ dem_mix64(0x626c6f636bull + (uint64_t)k)));
    const double g = floor((double)nk * (b->prefix[q] / b->prefix[b->per]) + u);
    return g0 + (g < (double)nk ? (size_t)g : nk);
}

/* block i's interval along axis a (the last ends exactly at the region's end) */
static void block_span(const blocks *b, int a, long i, double *lo, double *hi)
{
    *lo = b->clo[a] + (double)i * b->h[a];
    *hi = i + 1 == b->m[a] ? b->chi[a] : b->clo[a] + (double)(i + 1) * b->h[a];
}

/* area of [x0,x1] x [y0,y1] (about the disc's centre) inside the disc of
   radius rho: midpoint rule in x over the chord lengths (only the counts'
   shares depend on it) */
static double disc_area(double rho, double x0, double x1, double y0, double y1)
{
    const double a = fmax(x0, -rho), c = fmin(x1, rho);
    if (!(c > a)) return 0;
    enum { NX = 64 };
    const double dx = (c - a) / NX;
    double s = 0;
    for (int q = 0; q < NX; ++q) {
        const double x = a + (q + 0.5) * dx, half = sqrt(fmax(rho * rho - x * x, 0));
        s += fmax(fmin(y1, half) - fmax(y0, -half), 0);
    }
    return s * dx;
}

/* a uniform position in block (i, j, k) of the centres' region; 0 if the
   disc's part of the block was not hit in BLOCK_DISC_DRAWS draws */
static int block_sample(dem_world *w, const blocks *b, const long ijk[3], double c[3])
{
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) block_span(b, a, ijk[a], &lo[a], &hi[a]);
    c[2] = lo[2] + (hi[2] - lo[2]) * dem_rng_uniform(w);
    if (b->rho <= 0) {
        for (int a = 0; a < 2; ++a) c[a] = lo[a] + (hi[a] - lo[a]) * dem_rng_uniform(w);
        return 1;
    }
    const double R = b->f->R;
    for (long t = 0; t < BLOCK_DISC_DRAWS; ++t) {
        const double x = lo[0] + (hi[0] - lo[0]) * dem_rng_uniform(w) - R;
        const double y = lo[1] + (hi[1] - lo[1]) * dem_rng_uniform(w) - R;
        if (x * x + y * y <= b->rho * b->rho) { c[0] = x + R; c[1] = y + R; return 1; }
    }
    return 0;
}

/* place block (i, j, k)'s particles; keep those the keep filter takes */
static dem_status place_block(dem_world *w, const blocks *b, dem_pgrid *g, const long ijk[3],
                              const dem_particle_template *t, int64_t base, const char *fn)
{
    const size_t q = (size_t)ijk[0] + (size_t)b->m[0] * (size_t)ijk[1];
    const size_t first = block_first(b, ijk[2], q), cnt = block_first(b, ijk[2], q + 1) - first;
    if (!cnt) return DEM_OK;
    dem_rng_seed(w, dem_mix64(b->key ^ dem_mix64((uint64_t)ijk[2] * b->per + q + 0x5bd1e995ull)));
    for (size_t p = 0; p < cnt; ++p) {
        const double d = dem_dist_draw(w, &t->diameter), rho = dem_dist_draw(w, &t->density), r = 0.5 * d;
        double c[3], x[3];
        int ok = 0;
        for (int tr = 0; tr < BLOCK_TRIES && !ok; ++tr) {
            if (!block_sample(w, b, ijk, c)) break;
            dem_fill_frame_point(b->f, c, x);
            ok = dem_pgrid_free_at(g, x, r);
        }
        if (!ok)
            return DEM_FAIL(w, DEM_ERR_FULL, "%s: placed %zu of the %zu particles of block (%ld %ld %ld) of "
                            "%ld x %ld x %ld (%d random positions each, %zu particles in all)", fn, p, cnt,
                            ijk[0], ijk[1], ijk[2], b->m[0], b->m[1], b->m[2], BLOCK_TRIES, b->n);
        if (!dem_pgrid_add(g, x, r)) return DEM_FAIL(w, DEM_ERR_NOMEM, "%s: placement grid", fn);
        if (w->keep && !w->keep(x, w->keep_user)) continue;
        dem_status s = dem_fill_append(w, t, base + (int64_t)(first + p), x, r, rho);
        if (s) return s;
    }
    return DEM_OK;
}

/* blocks of the centres' region and the in-layer area sums */
static dem_status make_blocks(dem_world *w, const dem_fill_frame *f, size_t n, double dmax, blocks *b,
                              const char *fn)
{
    memset(b, 0, sizeof *b);
    b->f = f; b->n = n;
    const double a = 0.5 * dmax;
    for (int k = 0; k < 3; ++k) { b->clo[k] = a; b->chi[k] = f->len[k] - a; }
    b->rho = f->R > 0 ? f->R - a : 0;
    double vol = (b->chi[2] - b->clo[2]) * (f->R > 0 ? DEM_PI * b->rho * b->rho
                                                     : (b->chi[0] - b->clo[0]) * (b->chi[1] - b->clo[1]));
    int fits = f->R > 0 ? b->rho > 0 : 1;
    for (int k = 0; k < 3; ++k) fits = fits && b->chi[k] > b->clo[k];
    if (!fits || !(vol > 0))
        return DEM_FAIL(w, DEM_ERR_FULL, "%s: placed 0 of %zu particles: the largest diameter %g does not fit "
                        "the region", fn, n, dmax);
    /* edge: four mean spacings (about 64 particles a block), at least
       the largest diameter, so that only neighbouring blocks touch */
    const double edge = fmax(dmax, 4 * cbrt(vol / (double)n));
    for (int k = 0; k < 3; ++k) {
        const double ext = b->chi[k] - b->clo[k], m = floor(ext / edge);
        b->m[k] = m >= 1 ? (m < 1e6 ? (long)m : 1000000) : 1;
        b->h[k] = ext / (double)b->m[k];
    }
    b->per = (size_t)b->m[0] * (size_t)b->m[1];
    b->prefix = malloc((b->per + 1) * sizeof *b->prefix);
    if (!b->prefix) return DEM_FAIL(w, DEM_ERR_NOMEM, "%s: %zu blocks per layer", fn, b->per);
    b->prefix[0] = 0;
    for (long j = 0, q = 0; j < b->m[1]; ++j)
        for (long i = 0; i < b->m[0]; ++i, ++q) {
            double x0, x1, y0, y1;
            block_span(b, 0, i, &x0, &x1);
            block_span(b, 1, j, &y0, &y1);
            const double area = f->R > 0 ? disc_area(b->rho, x0 - f->R, x1 - f->R, y0 - f->R, y1 - f->R)
                                         : (x1 - x0) * (y1 - y0);
            b->prefix[q + 1] = b->prefix[q] + area;
        }
    return DEM_OK;
}

static dem_status fill_blocks(dem_world *w, const dem_fill_frame *f, size_t n, const dem_particle_template *t,
                              size_t *inserted, const char *fn)
{
    if (inserted) *inserted = 0;
    double dmax;
    dem_status st = dem_template_check(w, t, &dmax, fn);
    if (st) return st;
    if (n == 0) return DEM_OK;
    if ((st = dem_fill_region_free(w, f, fn))) return st;
    blocks b;
    if ((st = make_blocks(w, f, n, dmax, &b, fn))) { free(b.prefix); return st; }
    const int64_t base = w->next_id;
    b.key = dem_mix64(w->cfg.seed ^ dem_mix64((uint64_t)base + 0x7261626cull));

    /* blocks that meet the keep box (all without one) */
    long klo[3], khi[3];
    double mn[3], mx[3];
    const int boxed = dem_fill_keep_extent(w, f, mn, mx);
    int none = 0;
    for (int a = 0; a < 3; ++a) {
        klo[a] = 0; khi[a] = b.m[a] - 1;
        if (!boxed) continue;
        const double l = floor((mn[a] - b.clo[a]) / b.h[a]), h = floor((mx[a] - b.clo[a]) / b.h[a]);
        if (!(h >= 0 && l <= (double)(b.m[a] - 1))) { none = 1; continue; }
        klo[a] = l > 0 ? (long)l : 0;
        khi[a] = h < (double)(b.m[a] - 1) ? (long)h : b.m[a] - 1;
    }

    uint64_t saved[4];
    memcpy(saved, w->rng, sizeof saved);
    if (!none) {
        /* the placement grid over the colour-0 range (the widest) */
        long lo[3], hi[3];
        double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY}, nb = 1;
        for (int a = 0; a < 3; ++a) {
            lo[a] = klo[a] - BLOCK_DEPTH > 0 ? klo[a] - BLOCK_DEPTH : 0;
            hi[a] = khi[a] + BLOCK_DEPTH < b.m[a] - 1 ? khi[a] + BLOCK_DEPTH : b.m[a] - 1;
            nb *= (double)(hi[a] - lo[a] + 1);
        }
        for (int corner = 0; corner < 8; ++corner) {
            double c[3], x[3], dummy;
            for (int a = 0; a < 3; ++a)
                if (corner >> a & 1) block_span(&b, a, hi[a], &dummy, &c[a]); else block_span(&b, a, lo[a], &c[a], &dummy);
            dem_fill_frame_point(f, c, x);
            for (int k = 0; k < 3; ++k) { blo[k] = fmin(blo[k], x[k] - dmax); bhi[k] = fmax(bhi[k], x[k] + dmax); }
        }
        const double expect = nb * ((double)n / ((double)b.per * (double)b.m[2]) + 1) + 16;
        dem_pgrid g;
        if (!dem_pgrid_init(&g, blo, bhi, dmax, expect < 1e9 ? (size_t)expect : (size_t)1e9))
            st = DEM_FAIL(w, DEM_ERR_NOMEM, "%s: placement grid", fn);
        for (int c = 0; c < 8 && !st; ++c) {
            const long e = BLOCK_DEPTH - c;
            long r0[3], r1[3];
            for (int a = 0; a < 3; ++a) {
                r0[a] = klo[a] - e > 0 ? klo[a] - e : 0;
                r1[a] = khi[a] + e < b.m[a] - 1 ? khi[a] + e : b.m[a] - 1;
                if ((r0[a] & 1) != (c >> a & 1)) r0[a]++; /* the first of this colour's parity */
            }
            long ijk[3];
            for (ijk[2] = r0[2]; ijk[2] <= r1[2] && !st; ijk[2] += 2)
                for (ijk[1] = r0[1]; ijk[1] <= r1[1] && !st; ijk[1] += 2)
                    for (ijk[0] = r0[0]; ijk[0] <= r1[0] && !st; ijk[0] += 2)
                        st = place_block(w, &b, &g, ijk, t, base, fn);
        }
        dem_pgrid_free(&g);
    }
    memcpy(w->rng, saved, sizeof saved);
    free(b.prefix);
    if (st) return st;
    dem_fill_done(w, base, n, inserted);
    return DEM_OK;
}

dem_status dem_world_fill_blocks_box(dem_world *w, const double lo[3], const double hi[3], size_t n,
                                     const dem_particle_template *t, size_t *inserted)
{
    return dem_fill_in_box(w, "fill_blocks_box", fill_blocks, lo, hi, n, t, inserted);
}

dem_status dem_world_fill_blocks_cylinder(dem_world *w, const double base[3], const double axis[3],
                                          double radius, double length, size_t n,
                                          const dem_particle_template *t, size_t *inserted)
{
    return dem_fill_in_cylinder(w, "fill_blocks_cylinder", fill_blocks, base, axis, radius, length, n, t, inserted);
}
