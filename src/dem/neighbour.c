/*---------------------------------------------------------------------------*\
  demFoam DEM core - neighbour search.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  Linked cells (cell >= 2 a_max + skin) give a half Verlet list in CSR form
  (row i holds partners j > i within a_i + a_j + skin).  Owned particles are
  sorted by cell at every build (memory locality).  The tangential history
  of each pair lives beside its list entry; on a rebuild the touching pairs
  of the old list are mapped to the new indices (list_index: the row each
  particle had in the old list, kept through swaps/insertions) and their
  history is copied into the new entries.  Contacts restored by unpack wait
  in a pending store keyed by ids.  Wall candidates (planes, triangles within
  a + skin) form a second CSR list with their own history.
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define GROWTO(ptr, cap, need, type) do {                                   \
    if ((need) > (cap)) {                                                     \
        size_t nc_ = (cap) ? (cap) : 64;                                      \
        while (nc_ < (need)) nc_ *= 2;                                        \
        type *q_ = realloc((ptr), nc_ * sizeof(type));                        \
        if (!q_) return DEM_FAIL(w, DEM_ERR_NOMEM, "neighbour list: %zu entries", nc_); \
        (ptr) = q_; (cap) = nc_;                                              \
    } } while (0)

/* Cell of a point; clamped in floating point before the conversion, so that
 * points far outside the domain (or a non-finite one: cell 0) convert safely. */
static void cell_coords(const dem_world *w, const double *x, int c[3])
{
    for (int k = 0; k < 3; ++k) {
        double q = floor((x[k] - w->cfg.domain_lo[k]) / w->cs[k]);
        c[k] = q >= 0 ? (q < w->nc[k] ? (int)q : w->nc[k] - 1) : 0;
    }
}

/* Apply permutation perm[new] = old to a per-particle array of width m doubles. */
static void permute_d(dem_world *w, double *a, int m, size_t n)
{
    double *t = w->tmp;
    for (size_t p = 0; p < n; ++p)
        for (int k = 0; k < m; ++k) t[m * p + k] = a[m * (size_t)w->perm[p] + k];
    memcpy(a, t, (size_t)m * n * sizeof(double));
}
static void permute_f3(dem_world *w, float *a, size_t n)
{
    float *t = (float *)w->tmp;
    for (size_t p = 0; p < n; ++p)
        for (int k = 0; k < 3; ++k) t[3 * p + k] = a[3 * (size_t)w->perm[p] + k];
    memcpy(a, t, 3 * n * sizeof(float));
}
static void permute_i(dem_world *w, int *a, size_t n)
{
    int *t = (int *)w->tmp;
    for (size_t p = 0; p < n; ++p) t[p] = a[w->perm[p]];
    memcpy(a, t, n * sizeof(int));
}
static void permute_i64(dem_world *w, int64_t *a, size_t n)
{
    int64_t *t = (int64_t *)w->tmp;
    for (size_t p = 0; p < n; ++p) t[p] = a[w->perm[p]];
    memcpy(a, t, n * sizeof(int64_t));
}

/* Largest radius of the particles present (owned + ghosts); 1e-300 if none. */
static double largest_radius(const dem_world *w)
{
    size_t np = w->n + w->ng;
    double amax = 0;
    for (size_t i = 0; i < np; ++i) if (w->rad[i] > amax) amax = w->rad[i];
    return amax > 0 ? amax : 1e-300;
}

/* The skin: dem_config.skin if > 0, else 0.2 x the largest diameter. */
static double skin_for(const dem_world *w, double amax)
{
    return w->cfg.skin > 0 ? w->cfg.skin : 0.4 * amax;
}

double dem_world_skin(const dem_world *w)
{
    if (!w) return 0.0;
    if (w->cfg.skin > 0) return w->cfg.skin;
    if (w->nbuilds > 0) return w->skin;                /* chosen at the last build */
    if (w->n + w->ng == 0) return 0.0;
    return skin_for(w, largest_radius(w));             /* what a build now would choose */
}

static dem_status setup_grid(dem_world *w)
{
    size_t np = w->n + w->ng;
    double amax = largest_radius(w);
    w->amax = amax;
    w->skin = skin_for(w, amax);
    w->cutoff = 2.0 * amax + w->skin;
    for (int k = 0; k < 3; ++k) {
        double L = w->cfg.domain_hi[k] - w->cfg.domain_lo[k];
        if (w->cfg.periodic[k] && !(L > 2.0 * w->cutoff))
            return DEM_FAIL(w, DEM_ERR_RANGE, "periodic axis %d: period %g must exceed twice the "
                            "neighbour cutoff 2 a_max + skin = %g", k, L, w->cutoff);
    }
    double cs = w->cutoff;
    double limit = 8.0 * (double)np + 4096.0;
    for (;;) {
        double prod = 1;
        for (int k = 0; k < 3; ++k) {
            double L = w->cfg.domain_hi[k] - w->cfg.domain_lo[k];
            double m = floor(L / cs);
            if (m < 1) m = 1;
            if (m > 1e6) m = 1e6;
            w->nc[k] = (int)m;
            w->cs[k] = L / m;
            prod *= m;
        }
        if (prod <= limit) break;
        cs *= 1.25;
    }
    size_t nc = (size_t)w->nc[0] * w->nc[1] * w->nc[2];
    w->ncells = nc;
    if (nc + 1 > w->capcells) {
        int *a = realloc(w->cell_start, (nc + 1) * sizeof(int));
        if (!a) return DEM_FAIL(w, DEM_ERR_NOMEM, "cell grid: %zu cells", nc);
        w->cell_start = a;
        int *b = realloc(w->tcell_start, (nc + 1) * sizeof(int));
        if (!b) return DEM_FAIL(w, DEM_ERR_NOMEM, "cell grid: %zu cells", nc);
        w->tcell_start = b;
        w->capcells = nc + 1;
    }
    for (int sz = -1; sz <= 1; ++sz)
        for (int sy = -1; sy <= 1; ++sy)
            for (int sx = -1; sx <= 1; ++sx) {
                int code = (sx + 1) + 3 * (sy + 1) + 9 * (sz + 1);
                int s[3] = {sx, sy, sz};
                for (int k = 0; k < 3; ++k)
                    w->shift[code][k] = w->cfg.periodic[k]
                        ? s[k] * (w->cfg.domain_hi[k] - w->cfg.domain_lo[k]) : 0.0;
            }
    return DEM_OK;
}

static inline size_t cell_index(const dem_world *w, const int c[3])
{
    return (size_t)c[0] + (size_t)w->nc[0] * ((size_t)c[1] + (size_t)w->nc[1] * (size_t)c[2]);
}

/* Current position of wall vertex / plane point. */
static dem_status bin_triangles(dem_world *w)
{
    size_t nc = w->ncells;
    memset(w->tcell_start, 0, (nc + 1) * sizeof(int));
    if (w->ntri_all == 0) return DEM_OK;
    double margin = w->amax + w->skin;
    for (int pass = 0; pass < 2; ++pass) {
        for (size_t g = 0; g < w->ntri_all; ++g) {
            const dem_mesh *m = &w->meshes[w->tri_mesh[g]];
            int t = w->tri_local[g];
            double off[3], P[3][3], lo[3], hi[3];
            for (int k = 0; k < 3; ++k) off[k] = m->vel[k] * (w->time - m->t0);
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 3; ++k) P[c][k] = m->v0[3 * (size_t)m->tri[3 * t + c] + k] + off[k];
            for (int k = 0; k < 3; ++k) {
                lo[k] = fmin(P[0][k], fmin(P[1][k], P[2][k])) - margin;
                hi[k] = fmax(P[0][k], fmax(P[1][k], P[2][k])) + margin;
            }
            int clo[3], chi[3];
            cell_coords(w, lo, clo);
            cell_coords(w, hi, chi);
            const double *nrm = m->nrm + 3 * t;
            double hd = 0.5 * sqrt(w->cs[0] * w->cs[0] + w->cs[1] * w->cs[1] + w->cs[2] * w->cs[2]);
            for (int cz = clo[2]; cz <= chi[2]; ++cz)
                for (int cy = clo[1]; cy <= chi[1]; ++cy)
                    for (int cx = clo[0]; cx <= chi[0]; ++cx) {
                        double cc[3] = {w->cfg.domain_lo[0] + (cx + 0.5) * w->cs[0],
                                        w->cfg.domain_lo[1] + (cy + 0.5) * w->cs[1],
                                        w->cfg.domain_lo[2] + (cz + 0.5) * w->cs[2]};
                        /* clamped boundary cells hold everything outside: keep them */
                        int edge = cx == 0 || cy == 0 || cz == 0 || cx == w->nc[0] - 1 ||
                                   cy == w->nc[1] - 1 || cz == w->nc[2] - 1;
                        double d[3] = {cc[0] - P[0][0], cc[1] - P[0][1], cc[2] - P[0][2]};
                        if (!edge && fabs(dem_dot(d, nrm)) > hd + margin) continue;
                        int c3[3] = {cx, cy, cz};
                        size_t ci = cell_index(w, c3);
                        if (pass == 0) w->tcell_start[ci + 1]++;
                        else w->tcell_item[w->tcell_start[ci]++] = (int)g;
                    }
        }
        if (pass == 0) {
            for (size_t c = 0; c < nc; ++c) w->tcell_start[c + 1] += w->tcell_start[c];
            size_t need = (size_t)w->tcell_start[nc];
            GROWTO(w->tcell_item, w->captcell_item, need + 1, int);
            w->ntcell_item = need;
        }
    }
    /* shift starts back */
    for (size_t c = nc; c > 0; --c) w->tcell_start[c] = w->tcell_start[c - 1];
    w->tcell_start[0] = 0;
    return DEM_OK;
}

static uint64_t hash64(int64_t k)
{
    uint64_t z = (uint64_t)k * 0x9E3779B97F4A7C15ull;
    return z ^ (z >> 29);
}

/* id -> index table (open addressing) for resolving pending contacts. */
typedef struct { int64_t *key; int *val; size_t mask; } idmap;
static int idmap_build(idmap *m, const dem_world *w)
{
    size_t np = w->n + w->ng, sz = 16;
    while (sz < 2 * np + 2) sz *= 2;
    m->key = malloc(sz * sizeof(int64_t));
    m->val = malloc(sz * sizeof(int));
    if (!m->key || !m->val) { free(m->key); free(m->val); return 0; }
    m->mask = sz - 1;
    for (size_t i = 0; i < sz; ++i) m->val[i] = -1;
    for (size_t i = 0; i < np; ++i) {
        size_t h = hash64(w->id[i]) & m->mask;
        while (m->val[h] >= 0) h = (h + 1) & m->mask;
        m->key[h] = w->id[i];
        m->val[h] = (int)i;
    }
    return 1;
}
static int idmap_get(const idmap *m, int64_t id)
{
    size_t h = hash64(id) & m->mask;
    while (m->val[h] >= 0) {
        if (m->key[h] == id) return m->val[h];
        h = (h + 1) & m->mask;
    }
    return -1;
}

static dem_status push_carry(dem_world *w, int a, int b, const double *h)
{
    if (a < 0 || b < 0 || a == b) return DEM_OK;
    GROWTO(w->carry, w->capcarry, w->ncarry + 1, dem_carry);
    dem_carry *c = &w->carry[w->ncarry++];
    if (a < b) { c->a = a; c->b = b; for (int k = 0; k < 3; ++k) c->h[k] = h[k]; }
    else { c->a = b; c->b = a; for (int k = 0; k < 3; ++k) c->h[k] = -h[k]; }
    return DEM_OK;
}

typedef struct { int p, wall, tri; double h[3]; } wcarry;

static int cmp_wcarry(const void *a, const void *b)
{
    const wcarry *x = a, *y = b;
    if (x->p != y->p) return x->p < y->p ? -1 : 1;
    if (x->wall != y->wall) return x->wall < y->wall ? -1 : 1;
    return (x->tri > y->tri) - (x->tri < y->tri);
}

/* Per-row contact buffer of the phased pair loop: longest row entries. */
dem_status dem_scratch_ensure(dem_world *w)
{
    size_t maxrow = 1;
    for (size_t i = 0; i < w->nrows; ++i)
        if ((size_t)(w->nb_off[i + 1] - w->nb_off[i]) > maxrow)
            maxrow = (size_t)(w->nb_off[i + 1] - w->nb_off[i]);
    maxrow += DEM_SCRATCH_EXTRA;
    if (maxrow <= w->capscratch) return DEM_OK;
    size_t nc = 2 * maxrow;
    void *sc = realloc(w->scratch, nc * DEM_SCRATCH_ENTRY);
    if (!sc) return DEM_FAIL(w, DEM_ERR_NOMEM, "contact buffer: %zu entries", nc);
    w->scratch = sc;
    w->capscratch = nc;
    return DEM_OK;
}

dem_status dem_list_build(dem_world *w)
{
    dem_status st;
    size_t np = w->n + w->ng;
    if ((st = setup_grid(w))) return st;
    /* build-only work arrays: allocated here, released at the end of the
       build (they are not needed between builds: memory per particle) */
    {
        size_t cap = np + 1;
        int *a = realloc(w->cell_of, cap * sizeof(int));
        if (a) w->cell_of = a;
        int *b = realloc(w->perm, cap * sizeof(int));
        if (b) w->perm = b;
        double *c = realloc(w->tmp, 3 * cap * sizeof(double));
        if (c) w->tmp = c;
        if (!a || !b || !c) return DEM_FAIL(w, DEM_ERR_NOMEM, "list build work arrays: %zu particles", np);
    }
    /* periodic wrap */
    for (int k = 0; k < 3; ++k) {
        if (!w->cfg.periodic[k]) continue;
        double lo = w->cfg.domain_lo[k], L = w->cfg.domain_hi[k] - lo;
        for (size_t i = 0; i < np; ++i) {
            double x = w->x[3 * i + k];
            if (x < lo || x >= lo + L) {
                x -= L * floor((x - lo) / L);
                if (x >= lo + L) x -= L;
                if (x < lo) x = lo;
                w->x[3 * i + k] = x;
            }
        }
    }
    /* cells and counting sort of the owned particles */
    size_t nc = w->ncells;
    int *cs = w->cell_start;
    memset(cs, 0, (nc + 1) * sizeof(int));
    for (size_t i = 0; i < np; ++i) {
        int c[3];
        const double *xi = w->x + 3 * i;
        if (!isfinite(xi[0] + xi[1] + xi[2]))
            return DEM_FAIL(w, DEM_ERR_NAN, "particle index %zu id %lld: non-finite position (%g %g %g)",
                            i, (long long)w->id[i], xi[0], xi[1], xi[2]);
        cell_coords(w, xi, c);
        w->cell_of[i] = (int)cell_index(w, c);
        cs[w->cell_of[i] + 1]++;
    }
    for (size_t c = 0; c < nc; ++c) cs[c + 1] += cs[c];
    if (w->cfg.spatial_sort && w->n > 1) {
        /* perm[new] = old over owned particles (stable counting sort) */
        int *pos = malloc((nc + 1) * sizeof(int));
        if (!pos) return DEM_FAIL(w, DEM_ERR_NOMEM, "sort: %zu cells", nc);
        memset(pos, 0, (nc + 1) * sizeof(int));
        for (size_t i = 0; i < w->n; ++i) pos[w->cell_of[i] + 1]++;
        for (size_t c = 0; c < nc; ++c) pos[c + 1] += pos[c];
        for (size_t i = 0; i < w->n; ++i) w->perm[pos[w->cell_of[i]]++] = (int)i;
        free(pos);
        int identity = 1;
        for (size_t i = 0; i < w->n && identity; ++i) identity = w->perm[i] == (int)i;
        if (!identity) {
            size_t n = w->n;
            permute_d(w, w->x, 3, n); permute_d(w, w->v, 3, n); permute_d(w, w->w, 3, n);
            permute_d(w, w->f, 3, n); permute_d(w, w->t, 3, n);
            permute_d(w, w->rad, 1, n); permute_d(w, w->mass, 1, n); permute_d(w, w->rho, 1, n);
            permute_i(w, w->mat_of, n); permute_i(w, w->list_index, n); permute_i(w, w->cell_of, n);
            permute_i64(w, w->id, n);
            permute_f3(w, w->x0, n);
            if (w->have_ext) {
                permute_d(w, w->fext, 3, n); permute_d(w, w->text, 3, n); permute_d(w, w->uf, 3, n);
                permute_d(w, w->J, 3, n); permute_d(w, w->K, 1, n); permute_d(w, w->Ma, 1, n);
            }
            w->reorders++;
        }
    }
    /* cell item lists */
    {
        int *a = realloc(w->cell_item, (np + 1) * sizeof(int));
        if (!a) return DEM_FAIL(w, DEM_ERR_NOMEM, "cell items: %zu", np);
        w->cell_item = a;
        int *fill = malloc((nc + 1) * sizeof(int));
        if (!fill) return DEM_FAIL(w, DEM_ERR_NOMEM, "cell items: %zu cells", nc);
        memcpy(fill, cs, (nc + 1) * sizeof(int));
        for (size_t i = 0; i < np; ++i) w->cell_item[fill[w->cell_of[i]]++] = (int)i;
        free(fill);
    }

    /* harvest the touching contacts of the old list into new indices */
    w->ncarry = 0;
    size_t oldrows = w->nrows;
    int *old2new = NULL;
    if (oldrows) {
        old2new = malloc(oldrows * sizeof(int));
        if (!old2new) return DEM_FAIL(w, DEM_ERR_NOMEM, "old2new: %zu", oldrows);
        for (size_t r = 0; r < oldrows; ++r) old2new[r] = -1;
        for (size_t p = 0; p < np; ++p) {
            int r = w->list_index[p];
            if (r >= 0 && (size_t)r < oldrows) old2new[r] = (int)p;
        }
        for (size_t r = 0; r < oldrows; ++r) {
            for (int k = w->nb_off[r]; k < w->nb_off[r + 1]; ++k) {
                const double *h = w->nb_h + 3 * (size_t)k;
                if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
                int b = w->nb_j[k];
                if ((st = push_carry(w, old2new[r], (size_t)b < oldrows ? old2new[b] : -1, h))) {
                    free(old2new); return st;
                }
            }
        }
    }
    idmap im = {0};
    int have_map = 0;
    if (w->npend || w->nwpend) {
        if (!idmap_build(&im, w)) { free(old2new); return DEM_FAIL(w, DEM_ERR_NOMEM, "id map"); }
        have_map = 1;
        for (size_t k = 0; k < w->npend; ++k) {
            int a = idmap_get(&im, w->pend[k].ia), b = idmap_get(&im, w->pend[k].ib);
            if ((st = push_carry(w, a, b, w->pend[k].h))) { free(old2new); free(im.key); free(im.val); return st; }
        }
        w->npend = 0;
    }
    /* carry CSR by row a: counting sort */
    GROWTO(w->carry_off, w->capcarry_off, np + 2, int);
    dem_carry *cs2 = malloc((w->ncarry + 1) * sizeof(dem_carry));
    if (!cs2) { free(old2new); free(im.key); free(im.val); return DEM_FAIL(w, DEM_ERR_NOMEM, "carry"); }
    memset(w->carry_off, 0, (np + 2) * sizeof(int));
    for (size_t k = 0; k < w->ncarry; ++k) w->carry_off[w->carry[k].a + 1]++;
    for (size_t p = 0; p < np; ++p) w->carry_off[p + 1] += w->carry_off[p];
    for (size_t k = 0; k < w->ncarry; ++k) cs2[w->carry_off[w->carry[k].a]++] = w->carry[k];
    for (size_t p = np; p > 0; --p) w->carry_off[p] = w->carry_off[p - 1];
    w->carry_off[0] = 0;

    /* wall history carry */
    size_t nwc_old = w->nwc;
    wcarry *wcar = NULL; size_t nwcar = 0;
    if (oldrows || w->nwpend) {
        wcar = malloc((nwc_old + w->nwpend + 1) * sizeof(wcarry));
        if (!wcar) { free(cs2); free(old2new); free(im.key); free(im.val); return DEM_FAIL(w, DEM_ERR_NOMEM, "wall carry"); }
        for (size_t r = 0; r < oldrows && w->wc_off; ++r) {
            if (old2new[r] < 0) continue;
            for (int k = w->wc_off[r]; k < w->wc_off[r + 1]; ++k) {
                const double *h = w->wc_h + 3 * (size_t)k;
                if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
                wcarry *c = &wcar[nwcar++];
                c->p = old2new[r]; c->wall = w->wc_wall[k]; c->tri = w->wc_tri[k];
                memcpy(c->h, h, 3 * sizeof(double));
            }
        }
        for (size_t k = 0; k < w->nwpend; ++k) {
            int p = have_map ? idmap_get(&im, w->wpend[k].id) : -1;
            if (p < 0) continue;
            wcarry *c = &wcar[nwcar++];
            c->p = p; c->wall = w->wpend[k].wall; c->tri = w->wpend[k].tri;
            memcpy(c->h, w->wpend[k].h, 3 * sizeof(double));
        }
        w->nwpend = 0;
        qsort(wcar, nwcar, sizeof *wcar, cmp_wcarry);
    }
    free(old2new);
    if (have_map) { free(im.key); free(im.val); }

    /* build the half list */
    GROWTO(w->nb_off, w->caprows, np + 1, int);
    size_t cnt = 0;
    w->nb_off[0] = 0;
    const double skin = w->skin;
    for (size_t i = 0; i < np; ++i) {
        const double *xi = w->x + 3 * i;
        double ai = w->rad[i];
        int c[3];
        cell_coords(w, xi, c);
        int ghost_i = i >= w->n;
        for (int dz = -1; dz <= 1; ++dz) {
            int cz = c[2] + dz, sz = 0;
            if (cz < 0 || cz >= w->nc[2]) {
                if (!w->cfg.periodic[2]) continue;
                if (cz < 0) { cz += w->nc[2]; sz = 1; } else { cz -= w->nc[2]; sz = -1; }
            }
            for (int dy = -1; dy <= 1; ++dy) {
                int cy = c[1] + dy, sy = 0;
                if (cy < 0 || cy >= w->nc[1]) {
                    if (!w->cfg.periodic[1]) continue;
                    if (cy < 0) { cy += w->nc[1]; sy = 1; } else { cy -= w->nc[1]; sy = -1; }
                }
                for (int dx = -1; dx <= 1; ++dx) {
                    int cx = c[0] + dx, sx = 0;
                    if (cx < 0 || cx >= w->nc[0]) {
                        if (!w->cfg.periodic[0]) continue;
                        if (cx < 0) { cx += w->nc[0]; sx = 1; } else { cx -= w->nc[0]; sx = -1; }
                    }
                    int code = (sx + 1) + 3 * (sy + 1) + 9 * (sz + 1);
                    const double *sh = w->shift[code];
                    int c3[3] = {cx, cy, cz};
                    size_t ci = cell_index(w, c3);
                    for (int s = cs[ci]; s < cs[ci + 1]; ++s) {
                        size_t j = (size_t)w->cell_item[s];
                        if (j <= i) continue;
                        if (ghost_i && j >= w->n) continue;
                        const double *xj = w->x + 3 * j;
                        double d0 = xi[0] - xj[0] + sh[0], d1 = xi[1] - xj[1] + sh[1],
                               d2 = xi[2] - xj[2] + sh[2];
                        double rc = ai + w->rad[j] + skin;
                        if (d0 * d0 + d1 * d1 + d2 * d2 >= rc * rc) continue;
                        if (cnt + 1 > w->capnb) {
                            size_t ncap = w->capnb ? w->capnb + w->capnb / 2 + 64 : 8 * (np + 1);
                            int *a = realloc(w->nb_j, ncap * sizeof(int));
                            if (!a) { free(cs2); free(wcar); return DEM_FAIL(w, DEM_ERR_NOMEM, "list: %zu", ncap); }
                            w->nb_j = a;
                            unsigned char *b = realloc(w->nb_s, ncap);
                            if (!b) { free(cs2); free(wcar); return DEM_FAIL(w, DEM_ERR_NOMEM, "list: %zu", ncap); }
                            w->nb_s = b;
                            double *hh = realloc(w->nb_h, 3 * ncap * sizeof(double));
                            if (!hh) { free(cs2); free(wcar); return DEM_FAIL(w, DEM_ERR_NOMEM, "list: %zu", ncap); }
                            w->nb_h = hh;
                            w->capnb = ncap;
                        }
                        w->nb_j[cnt] = (int)j;
                        w->nb_s[cnt] = (unsigned char)code;
                        double *h = w->nb_h + 3 * cnt;
                        h[0] = h[1] = h[2] = 0.0;
                        for (int q = w->carry_off[i]; q < w->carry_off[i + 1]; ++q)
                            if (cs2[q].b == (int)j) { memcpy(h, cs2[q].h, 3 * sizeof(double)); break; }
                        cnt++;
                    }
                }
            }
        }
        w->nb_off[i + 1] = (int)cnt;
    }
    w->nnb = cnt;
    free(cs2);
    /* trim the list storage to the need (+1/8): memory per particle */
    {
        size_t want = cnt + cnt / 8 + 64;
        if (w->capnb > want + want / 2) {
            int *a = realloc(w->nb_j, want * sizeof(int));
            unsigned char *b = realloc(w->nb_s, want);
            double *hh = realloc(w->nb_h, 3 * want * sizeof(double));
            if (a) w->nb_j = a;
            if (b) w->nb_s = b;
            if (hh) w->nb_h = hh;
            w->capnb = want; /* a block whose shrink failed is only larger than that */
        }
    }
    w->nrows = np;
    if ((st = dem_scratch_ensure(w))) { free(wcar); return st; }

    /* wall candidates */
    st = bin_triangles(w);
    if (st) { free(wcar); return st; }
    {
        int *off = realloc(w->wc_off, (np + 1) * sizeof(int));
        if (!off) { free(wcar); return DEM_FAIL(w, DEM_ERR_NOMEM, "wall list: %zu rows", np); }
        w->wc_off = off;
        size_t q = 0, wq = 0;
        for (size_t i = 0; i < np; ++i) {
            off[i] = (int)q;
            if (i >= w->n || w->nwalls == 0) continue;
            while (wq < nwcar && wcar[wq].p < (int)i) wq++;
            const double *xi = w->x + 3 * i;
            double rc = w->rad[i] + skin;
            int ncand = 0, cwall[256], ctri[256];
            for (int pl = 0; pl < w->nplanes && ncand < 256; ++pl) {
                const dem_plane *P = &w->planes[pl];
                double d = 0;
                for (int k = 0; k < 3; ++k)
                    d += (xi[k] - P->x0[k] - P->vel[k] * (w->time - P->t0)) * P->n[k];
                if (fabs(d) >= rc) continue;
                cwall[ncand] = P->wall; ctri[ncand] = -1; ncand++;
            }
            if (w->ntri_all) {
                int c[3];
                cell_coords(w, xi, c);
                size_t ci = cell_index(w, c);
                for (int s = w->tcell_start[ci]; s < w->tcell_start[ci + 1] && ncand < 256; ++s) {
                    int g = w->tcell_item[s];
                    const dem_mesh *m = &w->meshes[w->tri_mesh[g]];
                    int t = w->tri_local[g];
                    double P[3][3], cp[3], d2 = 0;
                    for (int v = 0; v < 3; ++v)
                        for (int k = 0; k < 3; ++k)
                            P[v][k] = m->v0[3 * (size_t)m->tri[3 * t + v] + k] + m->vel[k] * (w->time - m->t0);
                    dem_closest_on_triangle(xi, P[0], P[1], P[2], cp);
                    for (int k = 0; k < 3; ++k) d2 += (xi[k] - cp[k]) * (xi[k] - cp[k]);
                    if (d2 >= rc * rc) continue;
                    cwall[ncand] = m->wall; ctri[ncand] = t; ncand++;
                }
            }
            size_t capold = w->capwc;
            GROWTO(w->wc_wall, w->capwc, q + (size_t)ncand + 1, int);
            if (w->capwc != capold || !w->wc_tri) {
                size_t capw = w->capwc;
                int *a = realloc(w->wc_tri, capw * sizeof(int));
                double *hh = realloc(w->wc_h, 3 * capw * sizeof(double));
                if (a) w->wc_tri = a;
                if (hh) w->wc_h = hh;
                if (!a || !hh) { free(wcar); return DEM_FAIL(w, DEM_ERR_NOMEM, "wall list: %zu", capw); }
            }
            for (int k = 0; k < ncand; ++k) {
                w->wc_wall[q] = cwall[k];
                w->wc_tri[q] = ctri[k];
                double *h = w->wc_h + 3 * q;
                h[0] = h[1] = h[2] = 0.0;
                for (size_t z = wq; z < nwcar && wcar[z].p == (int)i; ++z)
                    if (wcar[z].wall == cwall[k] && wcar[z].tri == ctri[k]) {
                        memcpy(h, wcar[z].h, 3 * sizeof(double));
                        break;
                    }
                q++;
            }
        }
        off[np] = (int)q;
        w->nwc = q;
    }
    free(wcar);

    /* reset displacement references */
    for (size_t i = 0; i < 3 * np; ++i) w->x0[i] = (float)w->x[i];
    for (size_t i = 0; i < np; ++i) w->list_index[i] = (int)i;
    w->nrows = np;
    w->t_build = w->time;
    w->nbuilds++;
    dem_log_(w, DEM_LOG_DEBUG, "neighbour list %lld at step %lld: %zu particles, %zu entries, %zu wall candidates, "
             "cells %d x %d x %d, skin %g m", (long long)w->nbuilds, (long long)w->step, np, w->nnb, w->nwc,
             w->nc[0], w->nc[1], w->nc[2], w->skin);
    w->list_valid = 1;
    free(w->cell_of); w->cell_of = NULL;
    free(w->perm); w->perm = NULL;
    free(w->tmp); w->tmp = NULL;
    free(w->cell_item); w->cell_item = NULL;
    free(w->cell_start); w->cell_start = NULL;
    free(w->tcell_start); w->tcell_start = NULL;
    w->capcells = 0;
    free(w->tcell_item); w->tcell_item = NULL;
    w->captcell_item = 0;
    return DEM_OK;
}
