/*---------------------------------------------------------------------------*\
  demFoam DEM core - the linked-cell grid of the random fills (placementGrid.h).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "placementGrid.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

int dem_pgrid_init(dem_pgrid *g, const double lo[3], const double hi[3], double cs, size_t expect)
{
    memset(g, 0, sizeof *g);
    g->cs = cs;
    double tot = 1, m[3];
    for (int k = 0; k < 3; ++k) {
        g->lo[k] = lo[k];
        m[k] = ceil((hi[k] - lo[k]) / cs);
        if (!(m[k] >= 1)) m[k] = 1;
        tot *= m[k];
    }
    while (tot > 4.0 * (double)expect + 1e6) { /* keep the grid bounded */
        g->cs *= 1.5;
        tot = 1;
        for (int k = 0; k < 3; ++k) {
            m[k] = ceil((hi[k] - lo[k]) / g->cs);
            if (!(m[k] >= 1)) m[k] = 1;
            tot *= m[k];
        }
    }
    for (int k = 0; k < 3; ++k) g->nc[k] = (int)m[k]; /* <= tot, bounded above */
    g->head = malloc((size_t)tot * sizeof(int));
    g->cap = expect + 16;
    g->next = malloc(g->cap * sizeof(int));
    g->xr = malloc(4 * g->cap * sizeof(double));
    if (!g->head || !g->next || !g->xr) return 0;
    for (size_t c = 0; c < (size_t)tot; ++c) g->head[c] = -1;
    return 1;
}
void dem_pgrid_free(dem_pgrid *g) { free(g->head); free(g->next); free(g->xr); }
static void pgrid_cell(const dem_pgrid *g, const double *x, int c[3])
{
    for (int k = 0; k < 3; ++k) {
        double q = floor((x[k] - g->lo[k]) / g->cs);
        c[k] = q >= 0 ? (q < g->nc[k] ? (int)q : g->nc[k] - 1) : 0; /* clamped before the cast (NaN: 0) */
    }
}
int dem_pgrid_add(dem_pgrid *g, const double *x, double r)
{
    if (g->n == g->cap) {
        size_t nc = 2 * g->cap;
        int *a = realloc(g->next, nc * sizeof(int));
        if (!a) return 0;
        g->next = a;
        double *b = realloc(g->xr, 4 * nc * sizeof(double));
        if (!b) return 0;
        g->xr = b;
        g->cap = nc;
    }
    int c[3];
    pgrid_cell(g, x, c);
    size_t ci = (size_t)c[0] + (size_t)g->nc[0] * ((size_t)c[1] + (size_t)g->nc[1] * (size_t)c[2]);
    double *p = g->xr + 4 * g->n;
    p[0] = x[0]; p[1] = x[1]; p[2] = x[2]; p[3] = r;
    g->next[g->n] = g->head[ci];
    g->head[ci] = (int)g->n;
    g->n++;
    return 1;
}
/* 1 if a sphere (x, r) overlaps nothing in the grid (cell >= 2 r_max). */
int dem_pgrid_free_at(const dem_pgrid *g, const double *x, double r)
{
    int c[3];
    pgrid_cell(g, x, c);
    for (int dz = -1; dz <= 1; ++dz) {
        int cz = c[2] + dz; if (cz < 0 || cz >= g->nc[2]) continue;
        for (int dy = -1; dy <= 1; ++dy) {
            int cy = c[1] + dy; if (cy < 0 || cy >= g->nc[1]) continue;
            for (int dx = -1; dx <= 1; ++dx) {
                int cx = c[0] + dx; if (cx < 0 || cx >= g->nc[0]) continue;
                size_t ci = (size_t)cx + (size_t)g->nc[0] * ((size_t)cy + (size_t)g->nc[1] * (size_t)cz);
                for (int it = g->head[ci]; it >= 0; it = g->next[it]) {
                    const double *p = g->xr + 4 * (size_t)it;
                    double d0 = x[0] - p[0], d1 = x[1] - p[1], d2 = x[2] - p[2], s = r + p[3];
                    if (d0 * d0 + d1 * d1 + d2 * d2 < s * s) return 0;
                }
            }
        }
    }
    return 1;
}
