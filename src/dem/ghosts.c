/*---------------------------------------------------------------------------*\
  demFoam DEM core - ghosts: dropping them (their contact history kept by id)
  and setting their positions, velocities and spins in place.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <string.h>

dem_status dem_world_clear_ghosts(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    if (w->ng == 0) return DEM_OK;
    /* keep the history of owned-ghost contacts by id (a ghost unpacked
       again with the same id gets it back at the next list build) */
    dem_status st = dem_history_to_pending(w, -1, NULL, "clear_ghosts");
    if (st) return st;
    for (size_t i = w->n; i < w->n + w->ng; ++i) w->list_index[i] = -1;
    w->ng = 0;
    w->list_valid = 0;
    w->reorders++;
    return DEM_OK;
}

dem_status dem_world_set_ghost_states(dem_world *w, size_t first, size_t count, const double *xvw)
{
    if (!w) return DEM_ERR_ARG;
    if (count == 0) {
        if (first > w->ng)
            return DEM_FAIL(w, DEM_ERR_RANGE, "set_ghost_states: first = %zu; allowed 0..%zu (%zu ghosts)",
                            first, w->ng, w->ng);
        return DEM_OK;
    }
    DEM_NEED(w, xvw, "set_ghost_states");
    if (first >= w->ng || count > w->ng - first)
        return DEM_FAIL(w, DEM_ERR_RANGE, "set_ghost_states: ghosts [%zu, %zu) (first = %zu, count = %zu); "
                        "allowed within [0, %zu) (%zu ghosts present)", first, first + count, first, count,
                        w->ng, w->ng);
    /* all or nothing: check every value first */
    static const char *const what[3] = {"x", "v", "omega"};
    for (size_t k = 0; k < 9 * count; ++k)
        if (!isfinite(xvw[k]))
            return DEM_FAIL(w, DEM_ERR_NAN, "set_ghost_states: ghost position %zu (id %lld): %s[%d] = %g "
                            "(xvw[%zu]); must be finite", first + k / 9, (long long)w->id[w->n + first + k / 9],
                            what[(k % 9) / 3], (int)(k % 3), xvw[k], k);
    for (size_t g = 0; g < count; ++g) {
        size_t i = w->n + first + g;
        const double *s = xvw + 9 * g;
        memcpy(w->x + 3 * i, s, 3 * sizeof(double));
        memcpy(w->v + 3 * i, s + 3, 3 * sizeof(double));
        memcpy(w->w + 3 * i, s + 6, 3 * sizeof(double));
    }
    /* list, history, x0 and the storage order are untouched (no reorder) */
    return DEM_OK;
}
