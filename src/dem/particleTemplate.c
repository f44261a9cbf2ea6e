/*---------------------------------------------------------------------------*\
  demFoam DEM core - the particle template of fills and inlets: checks of
  its material, velocity and size and density distributions.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <stdio.h>

/* Checks a distribution; *dmin, *dmax: the smallest and largest value it can draw. */
static dem_status check_dist(dem_world *w, const dem_distribution *d, const char *what, double *dmin, double *dmax)
{
    switch (d->kind) {
    case DEM_DIST_FIXED:
        *dmin = *dmax = d->a;
        if (!(d->a > 0) || !isfinite(d->a))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: fixed value a = %g; allowed > 0 and finite", what, d->a);
        return DEM_OK;
    case DEM_DIST_UNIFORM:
        *dmin = d->a; *dmax = d->b;
        if (!(d->a > 0 && d->b >= d->a) || !isfinite(d->b - d->a))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: uniform [a, b] = [%g, %g]; need 0 < a <= b, both finite",
                            what, d->a, d->b);
        return DEM_OK;
    case DEM_DIST_NORMAL:
        *dmin = d->a - 3.0 * d->b; *dmax = d->a + 3.0 * d->b;
        if (!(d->a - 3.0 * d->b > 0) || !(d->b >= 0) || !isfinite(d->a + 3.0 * d->b))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: normal mean a = %g, std dev b = %g; need a - 3 b > 0, b >= 0, "
                            "both finite", what, d->a, d->b);
        return DEM_OK;
    case DEM_DIST_DISCRETE: {
        if (d->n == 0 || !d->values || !d->weights)
            return DEM_FAIL(w, DEM_ERR_ARG, "%s: discrete distribution with n = %zu, values %s, weights %s; "
                            "need n > 0 values and weights", what, d->n, d->values ? "given" : "NULL",
                            d->weights ? "given" : "NULL");
        double tot = 0, mx = 0, mn = INFINITY;
        for (size_t k = 0; k < d->n; ++k) {
            if (!(d->values[k] > 0) || !(d->weights[k] >= 0) || !isfinite(d->values[k]) || !isfinite(d->weights[k]))
                return DEM_FAIL(w, DEM_ERR_RANGE, "%s: discrete values[%zu] = %g, weights[%zu] = %g; need "
                                "value > 0, weight >= 0, both finite", what, k, d->values[k], k, d->weights[k]);
            tot += d->weights[k];
            mx = fmax(mx, d->values[k]);
            mn = fmin(mn, d->values[k]);
        }
        if (!(tot > 0) || !isfinite(tot))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: discrete weights sum to %g; need > 0 and finite", what, tot);
        *dmin = mn; *dmax = mx;
        return DEM_OK;
    }
    }
    return DEM_FAIL(w, DEM_ERR_ARG, "%s: distribution kind %d; allowed 0..3 (fixed, uniform, normal, discrete)",
                    what, (int)d->kind);
}

/* Checks of a template (fn: the caller in messages); *dmax: the largest diameter it can draw. */
dem_status dem_template_check(dem_world *w, const dem_particle_template *t, double *dmax, const char *fn)
{
    DEM_NEED(w, t, fn);
    if (t->material < 0 || t->material >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "%s: template material = %d; allowed 0..%d (%d materials defined)",
                        fn, t->material, w->nmat - 1, w->nmat);
    if (dem_material_rigid(&w->mat[t->material], w->cfg.contact_law))
        return DEM_FAIL(w, DEM_ERR_ARG, "%s: template material %d is rigid (DEM_RIGID); allowed for walls only",
                        fn, t->material);
    for (int k = 0; k < 3; ++k)
        if (!isfinite(t->velocity[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: template velocity[%d] = %g; must be finite", fn, k, t->velocity[k]);
    double dmin, rmin, rmax;
    char what[64];
    snprintf(what, sizeof what, "%s: template diameter", fn);
    dem_status s = check_dist(w, &t->diameter, what, &dmin, dmax);
    if (s) return s;
    snprintf(what, sizeof what, "%s: template density", fn);
    if ((s = check_dist(w, &t->density, what, &rmin, &rmax))) return s;
    /* mass and inertia grow with both: the extremes bound every particle */
    if (!dem_mass_ok(0.5 * dmin, rmin) || !dem_mass_ok(0.5 * *dmax, rmax))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: template diameters %g..%g and densities %g..%g give a mass or "
                        "moment of inertia that is not a finite normal double", fn, dmin, *dmax, rmin, rmax);
    return DEM_OK;
}
