/*---------------------------------------------------------------------------*\
  demFoam DEM core - the neighbour-list build: the half Verlet list and the
  wall candidate list.
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
#include "neighbour.h"
#include <string.h>

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

/* The half list in CSR form with the carried pair history (cs2: sorted by row a). */
static dem_status pair_list(dem_world *w, const dem_carry *cs2)
{
    size_t np = w->n + w->ng;
    const int *cs = w->cell_start;
    GROWTO(w->nb_off, w->caprows, np + 1, int);
    size_t cnt = 0;
    w->nb_off[0] = 0;
    const double skin = w->skin;
    for (size_t i = 0; i < np; ++i) {
        /* a ghost row is empty (j > i >= n would be a ghost-ghost pair) */
        if (i >= w->n) { w->nb_off[i + 1] = (int)cnt; continue; }
        const double *xi = w->x + 3 * i;
        double ai = w->rad[i];
        int c[3];
        dem_cell_coords(w, xi, c);
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
                    size_t ci = dem_cell_index(w, c3);
                    /* a cell's items are in ascending index order: start at
                       the first j > i (the same entries in the same order as
                       testing every item; skips most of the cells below i's
                       at once when the owned particles are sorted by cell) */
                    int s = cs[ci];
                    const int e = cs[ci + 1];
                    if (s == e || (size_t)w->cell_item[e - 1] <= i) continue;
                    while ((size_t)w->cell_item[s] <= i) ++s;
                    for (; s < e; ++s) {
                        size_t j = (size_t)w->cell_item[s];
                        const double *xj = w->x + 3 * j;
                        double d0 = xi[0] - xj[0] + sh[0], d1 = xi[1] - xj[1] + sh[1],
                               d2 = xi[2] - xj[2] + sh[2];
                        double rc = ai + w->rad[j] + skin;
                        if (d0 * d0 + d1 * d1 + d2 * d2 >= rc * rc) continue;
                        if (cnt + 1 > w->capnb) {
                            size_t ncap = w->capnb ? w->capnb + w->capnb / 2 + 64 : 8 * (np + 1);
                            int *a = realloc(w->nb_j, ncap * sizeof(int));
                            if (!a) return DEM_FAIL(w, DEM_ERR_NOMEM, "list: %zu", ncap);
                            w->nb_j = a;
                            unsigned char *b = realloc(w->nb_s, ncap);
                            if (!b) return DEM_FAIL(w, DEM_ERR_NOMEM, "list: %zu", ncap);
                            w->nb_s = b;
                            double *hh = realloc(w->nb_h, 3 * ncap * sizeof(double));
                            if (!hh) return DEM_FAIL(w, DEM_ERR_NOMEM, "list: %zu", ncap);
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
    return DEM_OK;
}

/* Wall candidates (planes, triangles within a + skin) in CSR form by row, with the carried wall history. */
static dem_status wall_list(dem_world *w, const dem_wcarry *wcar, size_t nwcar)
{
    size_t np = w->n + w->ng;
    const double skin = w->skin;
    int *off = realloc(w->wc_off, (np + 1) * sizeof(int));
    if (!off) return DEM_FAIL(w, DEM_ERR_NOMEM, "wall list: %zu rows", np);
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
            dem_cell_coords(w, xi, c);
            size_t ci = dem_cell_index(w, c);
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
            if (!a || !hh) return DEM_FAIL(w, DEM_ERR_NOMEM, "wall list: %zu", capw);
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
    return DEM_OK;
}

dem_status dem_list_build(dem_world *w)
{
    dem_status st;
    size_t np = w->n + w->ng;
    if ((st = dem_cells_build(w))) return st;
    dem_carried car;
    if ((st = dem_carry_collect(w, &car))) return st;
    st = pair_list(w, car.pairs);
    free(car.pairs);
    if (!st) st = dem_scratch_ensure(w);
    if (!st) st = dem_bin_triangles(w);
    if (!st) st = wall_list(w, car.walls, car.nwalls);
    free(car.walls);
    if (st) return st;

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
    dem_cells_release(w);
    return DEM_OK;
}
