/*---------------------------------------------------------------------------*\
  demFoam DEM core - outlets (plane, box, or none: removal by the caller),
  their totals and the removal records.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static dem_status new_outlet(dem_world *w, int kind, const double *a, const double *b, int *id)
{
    dem_outlet *o = realloc(w->outlets, (size_t)(w->noutlets + 1) * sizeof *o);
    if (!o) return DEM_FAIL(w, DEM_ERR_NOMEM, "outlets");
    w->outlets = o;
    dem_outlet *z = &w->outlets[w->noutlets];
    memset(z, 0, sizeof *z);
    z->kind = kind;
    if (a) memcpy(z->a, a, sizeof z->a);
    if (b) memcpy(z->b, b, sizeof z->b);
    if (id) *id = w->noutlets;
    w->noutlets++;
    return DEM_OK;
}

dem_status dem_world_add_outlet_plane(dem_world *w, const double point[3], const double normal[3], int *outlet_id)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, point, "add_outlet_plane");
    DEM_NEED(w, normal, "add_outlet_plane");
    double l = sqrt(dem_dot(normal, normal));
    if (!(l > 0) || !isfinite(l))
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_outlet_plane: normal (%g %g %g); need finite, with a length > 0 "
                        "and finite", normal[0], normal[1], normal[2]);
    for (int k = 0; k < 3; ++k)
        if (!isfinite(point[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "add_outlet_plane: point[%d] = %g; must be finite", k, point[k]);
    double n[3] = {normal[0] / l, normal[1] / l, normal[2] / l};
    return new_outlet(w, 0, point, n, outlet_id);
}

dem_status dem_world_add_outlet_box(dem_world *w, const double lo[3], const double hi[3], int *outlet_id)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, lo, "add_outlet_box");
    DEM_NEED(w, hi, "add_outlet_box");
    for (int k = 0; k < 3; ++k)
        if (!(hi[k] > lo[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "add_outlet_box: lo[%d] = %g, hi[%d] = %g; need lo < hi (infinite "
                            "bounds allowed)", k, lo[k], k, hi[k]);
    return new_outlet(w, 1, lo, hi, outlet_id);
}

dem_status dem_world_add_outlet(dem_world *w, int *outlet_id)
{
    if (!w) return DEM_ERR_ARG;
    return new_outlet(w, 2, NULL, NULL, outlet_id);
}

dem_status dem_outlets_run(dem_world *w)
{
    for (int q = 0; q < w->noutlets; ++q) {
        const dem_outlet *o = &w->outlets[q];
        if (o->kind == 2) continue;
        for (size_t i = w->n; i-- > 0;) {
            const double *x = w->x + 3 * i;
            int out;
            if (o->kind == 0)
                out = (x[0] - o->a[0]) * o->b[0] + (x[1] - o->a[1]) * o->b[1] + (x[2] - o->a[2]) * o->b[2] > 0;
            else
                out = x[0] > o->a[0] && x[0] < o->b[0] && x[1] > o->a[1] && x[1] < o->b[1] &&
                      x[2] > o->a[2] && x[2] < o->b[2];
            if (out) {
                dem_status s = dem_remove_booked(w, i, q);
                if (s) return s;
            }
        }
    }
    return DEM_OK;
}

dem_status dem_world_outlet_totals(const dem_world *w, int outlet_id, int64_t *count, double *mass)
{
    if (!w) return DEM_ERR_ARG;
    if (outlet_id < 0 || outlet_id >= w->noutlets)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "outlet_totals: outlet %d; allowed 0..%d (%d outlets defined)",
                        outlet_id, w->noutlets - 1, w->noutlets);
    if (count) *count = w->outlets[outlet_id].count;
    if (mass) *mass = w->outlets[outlet_id].mass;
    return DEM_OK;
}

dem_status dem_world_removed_records(const dem_world *w, const dem_removed_record **records, size_t *n)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, records, "removed_records");
    DEM_NEED(w, n, "removed_records");
    *records = w->rec;
    *n = w->nrec;
    return DEM_OK;
}

void dem_world_clear_removed_records(dem_world *w)
{
    if (w) w->nrec = 0;
}
