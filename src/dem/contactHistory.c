/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact history kept by particle ids while the particles
  are away (removal by migration, ghost exchange); the list build picks it up.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <stdlib.h>
#include <string.h>

/* The non-zero tangential history of the current list into the pending
 * store by id: of the pairs of particle index `only` (only >= 0), or of all
 * owned-ghost pairs (only < 0).  fn names the caller in messages. */
dem_status dem_history_to_pending(dem_world *w, ptrdiff_t only, const char *fn)
{
    if (!w->nb_off || !w->nrows) return DEM_OK;
    int row = -1;
    if (only >= 0) {
        row = w->list_index[only];
        if (row < 0 || (size_t)row >= w->nrows) return DEM_OK;
    }
    int *inv = malloc((w->nrows + 1) * sizeof(int));
    if (!inv) return DEM_FAIL(w, DEM_ERR_NOMEM, "%s: row map of %zu rows", fn, w->nrows);
    for (size_t r = 0; r < w->nrows; ++r) inv[r] = -1;
    for (size_t q = 0; q < w->n + w->ng; ++q) {
        int r = w->list_index[q];
        if (r >= 0 && (size_t)r < w->nrows) inv[r] = (int)q;
    }
    for (size_t r = 0; r < w->nrows; ++r) {
        for (int k = w->nb_off[r]; k < w->nb_off[r + 1]; ++k) {
            const double *h = w->nb_h + 3 * (size_t)k;
            if (h[0] == 0 && h[1] == 0 && h[2] == 0) continue;
            if (only >= 0 && (int)r != row && w->nb_j[k] != row) continue;
            int a = inv[r], b = inv[w->nb_j[k]];
            if (a < 0 || b < 0) continue;
            if (only < 0 && (size_t)a < w->n && (size_t)b < w->n) continue;
            if (w->npend == w->cappend) {
                size_t nc = w->cappend ? 2 * w->cappend : 64;
                dem_pending *q = realloc(w->pend, nc * sizeof *q);
                if (!q) { free(inv); return DEM_FAIL(w, DEM_ERR_NOMEM, "%s: %zu pending contacts", fn, nc); }
                w->pend = q; w->cappend = nc;
            }
            dem_pending *d = &w->pend[w->npend++];
            d->ia = w->id[a]; d->ib = w->id[b];
            memcpy(d->h, h, sizeof d->h);
        }
    }
    free(inv);
    return DEM_OK;
}
