/*---------------------------------------------------------------------------*\
  demFoam DEM core - private pieces of a neighbour-list build shared by
  cells.c, contactHistory.c and neighbourList.c (docs/demCore.md).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#ifndef DEM_NEIGHBOUR_H
#define DEM_NEIGHBOUR_H
#include "dem_private.h"
#include <math.h>
#include <stdlib.h>

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
static inline void dem_cell_coords(const dem_world *w, const double *x, int c[3])
{
    for (int k = 0; k < 3; ++k) {
        double q = floor((x[k] - w->glo[k]) / w->cs[k]);
        c[k] = q >= 0 ? (q < w->nc[k] ? (int)q : w->nc[k] - 1) : 0;
    }
}

static inline size_t dem_cell_index(const dem_world *w, const int c[3])
{
    return (size_t)c[0] + (size_t)w->nc[0] * ((size_t)c[1] + (size_t)w->nc[1] * (size_t)c[2]);
}

/* A wall contact carried across a list build: particle (new index), wall, triangle (-1: plane) */
typedef struct { int p, wall, tri; double h[3]; } dem_wcarry;
/* The history carried into a new list (dem_carry_collect): pair contacts
 * sorted by row a (rows in w->carry_off), wall contacts sorted by particle. */
typedef struct { dem_carry *pairs; dem_wcarry *walls; size_t nwalls; } dem_carried;

/* cells.c: the cell grid of a build (periodic wrap, spatial sort, cell
 * lists), the triangle bins, and the release of the build-only arrays */
dem_status dem_cells_build(dem_world *w);
dem_status dem_bin_triangles(dem_world *w);
void       dem_cells_release(dem_world *w);
/* contactHistory.c: the touching contacts of the old list and the pending
 * ones, in new indices; the caller frees c->pairs and c->walls */
dem_status dem_carry_collect(dem_world *w, dem_carried *c);

#endif
