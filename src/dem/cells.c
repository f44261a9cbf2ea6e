/*---------------------------------------------------------------------------*\
  demFoam DEM core - the cell grid of a neighbour-list build: cell size and
  skin, periodic wrap, spatial sort of the owned particles, cell lists of
  particles and triangles.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "neighbour.h"
#include <string.h>


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
    /* The grid spans the box of the particle centres (owned and ghosts)
       clipped to the domain on open axes, and the domain on periodic ones:
       its cells are then no larger than the cutoff for the particles
       present, also on a processor that holds a small part of a large
       domain (docs/demCore.md, "Neighbour search and contact history").  Centres outside fall
       into the boundary cells. */
    double glen[3];
    for (int k = 0; k < 3; ++k) { w->plo[k] = HUGE_VAL; w->phi[k] = -HUGE_VAL; }
    for (size_t i = 0; i < np; ++i)
        for (int k = 0; k < 3; ++k) {
            const double x = w->x[3 * i + k];
            w->plo[k] = x < w->plo[k] ? x : w->plo[k];
            w->phi[k] = x > w->phi[k] ? x : w->phi[k];
        }
    for (int k = 0; k < 3; ++k) {
        const double dlo = w->cfg.domain_lo[k], dhi = w->cfg.domain_hi[k];
        if (w->cfg.periodic[k] || np == 0) {
            w->glo[k] = dlo;
            glen[k] = dhi - dlo;
            continue;
        }
        double lo = w->plo[k] < dlo ? dlo : (w->plo[k] > dhi ? dhi : w->plo[k]);
        double hi = w->phi[k] < dlo ? dlo : (w->phi[k] > dhi ? dhi : w->phi[k]);
        w->glo[k] = lo;
        glen[k] = hi - lo > w->cutoff ? hi - lo : w->cutoff;
    }
    double cs = w->cutoff;
    double limit = 8.0 * (double)np + 4096.0;
    for (;;) {
        double prod = 1;
        for (int k = 0; k < 3; ++k) {
            double L = glen[k];
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

/* Triangles into the cells within a_max + skin of them (the current wall positions). */
dem_status dem_bin_triangles(dem_world *w)
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
            /* no particle centre within the margin of this triangle: it
               cannot be a wall candidate at this build */
            int away = 0;
            for (int k = 0; k < 3; ++k)
                away |= !w->cfg.periodic[k] && (lo[k] > w->phi[k] || hi[k] < w->plo[k]);
            if (away) continue;
            int clo[3], chi[3];
            dem_cell_coords(w, lo, clo);
            dem_cell_coords(w, hi, chi);
            const double *nrm = m->nrm + 3 * t;
            double hd = 0.5 * sqrt(w->cs[0] * w->cs[0] + w->cs[1] * w->cs[1] + w->cs[2] * w->cs[2]);
            for (int cz = clo[2]; cz <= chi[2]; ++cz)
                for (int cy = clo[1]; cy <= chi[1]; ++cy)
                    for (int cx = clo[0]; cx <= chi[0]; ++cx) {
                        double cc[3] = {w->glo[0] + (cx + 0.5) * w->cs[0],
                                        w->glo[1] + (cy + 0.5) * w->cs[1],
                                        w->glo[2] + (cz + 0.5) * w->cs[2]};
                        /* clamped boundary cells hold everything outside: keep them */
                        int edge = cx == 0 || cy == 0 || cz == 0 || cx == w->nc[0] - 1 ||
                                   cy == w->nc[1] - 1 || cz == w->nc[2] - 1;
                        double d[3] = {cc[0] - P[0][0], cc[1] - P[0][1], cc[2] - P[0][2]};
                        if (!edge && fabs(dem_dot(d, nrm)) > hd + margin) continue;
                        int c3[3] = {cx, cy, cz};
                        size_t ci = dem_cell_index(w, c3);
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

/* The grid of a build: cells, periodic wrap, owned particles sorted by cell
 * (dem_config.spatial_sort), the particles of each cell. */
dem_status dem_cells_build(dem_world *w)
{
    size_t np = w->n + w->ng;
    dem_status st;
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
        dem_cell_coords(w, xi, c);
        w->cell_of[i] = (int)dem_cell_index(w, c);
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
                for (int k = 0; k < DEM_N_TAGS; ++k) permute_i64(w, w->tag[k], n);
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
    return DEM_OK;
}

/* The build-only work arrays: released at the end of a build (not needed
 * between builds: memory per particle). */
void dem_cells_release(dem_world *w)
{
    free(w->cell_of); w->cell_of = NULL;
    free(w->perm); w->perm = NULL;
    free(w->tmp); w->tmp = NULL;
    free(w->cell_item); w->cell_item = NULL;
    free(w->cell_start); w->cell_start = NULL;
    free(w->tcell_start); w->tcell_start = NULL;
    w->capcells = 0;
    free(w->tcell_item); w->tcell_item = NULL;
    w->captcell_item = 0;
}
