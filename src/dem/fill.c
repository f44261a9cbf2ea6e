/*---------------------------------------------------------------------------*\
  demFoam DEM core - filling a region (box, cylinder) with particles.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  Region filling is random sequential addition: each particle (size and
  density drawn from the template's distributions) is tried at up to
  DEM_FILL_TRIES random positions inside the region and accepted if it
  overlaps neither an existing particle nor one placed before it (checked
  on a private linked-cell grid).  Seeded by dem_config.seed: deterministic.
  With a keep filter (dem_world_set_keep_filter, decomposed set-up) the
  particles it refuses are placed all the same but kept as centre and radius
  only (the shadow list): the draws and ids stay the unfiltered ones.
\*---------------------------------------------------------------------------*/
#include "placementGrid.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEM_FILL_TRIES 1000   /* attempts per particle before giving up */

/* Region description for the generic filler. */
typedef struct {
    int kind; /* 0 box, 1 cylinder */
    double lo[3], hi[3];
    dem_inside_fn inside; void *user;
    double base[3], e1[3], e2[3], ax[3], R, L;
} region;

static int sample(dem_world *w, const region *rg, double r, double x[3])
{
    if (rg->kind == 0) {
        for (int k = 0; k < 3; ++k) {
            double span = rg->hi[k] - rg->lo[k] - 2.0 * r;
            if (span < 0) return 0;
            x[k] = rg->lo[k] + r + span * dem_rng_uniform(w);
        }
        if (rg->inside && !rg->inside(x, rg->user)) return -1;
        return 1;
    }
    double rho = rg->R - r, hl = rg->L - 2.0 * r;
    if (rho < 0 || hl < 0) return 0;
    double u, v;
    do { u = 2.0 * dem_rng_uniform(w) - 1.0; v = 2.0 * dem_rng_uniform(w) - 1.0; } while (u * u + v * v > 1.0);
    double hh = r + hl * dem_rng_uniform(w);
    for (int k = 0; k < 3; ++k) x[k] = rg->base[k] + rho * (u * rg->e1[k] + v * rg->e2[k]) + hh * rg->ax[k];
    return 1;
}

static dem_status fill(dem_world *w, const region *rg, size_t n, const dem_particle_template *t,
                       size_t *inserted)
{
    if (inserted) *inserted = 0;
    double dmax;
    dem_status s = dem_template_check(w, t, &dmax, rg->kind == 0 ? "fill_box" : "fill_cylinder");
    if (s) return s;
    if ((s = dem_room_for(w, w->keep ? 0 : n, rg->kind == 0 ? "fill_box" : "fill_cylinder"))) return s;
    if (n == 0) return DEM_OK;
    double amax = 0.5 * dmax;
    for (size_t i = 0; i < w->n; ++i) amax = fmax(amax, w->rad[i]);
    for (size_t i = 0; i < w->nshadow; ++i) amax = fmax(amax, w->shadow[4 * i + 3]);
    dem_pgrid g;
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) { lo[k] = rg->lo[k] - 2 * amax; hi[k] = rg->hi[k] + 2 * amax; }
    if (!dem_pgrid_init(&g, lo, hi, 2.0 * amax, n + w->n + w->nshadow)) { dem_pgrid_free(&g); return DEM_FAIL(w, DEM_ERR_NOMEM, "fill grid"); }
    /* the stored particles and the shadow ones (keep filter), in the order
       they were placed: the grid is the unfiltered fill's */
    for (size_t i = 0; i < w->n + w->nshadow; ++i) {
        const double *x = i < w->n ? w->x + 3 * i : w->shadow + 4 * (i - w->n);
        double r = i < w->n ? w->rad[i] : x[3];
        int in = 1;
        for (int k = 0; k < 3; ++k) in = in && x[k] > lo[k] && x[k] < hi[k];
        if (in && !dem_pgrid_add(&g, x, r)) { dem_pgrid_free(&g); return DEM_FAIL(w, DEM_ERR_NOMEM, "fill grid"); }
    }
    s = dem_reserve(w, w->n + w->ng + (w->keep ? 0 : n));
    if (s) { dem_pgrid_free(&g); return s; }
    size_t done = 0;
    for (size_t q = 0; q < n; ++q) {
        double d = dem_dist_draw(w, &t->diameter), rho = dem_dist_draw(w, &t->density), r = 0.5 * d;
        double x[3];
        int ok = 0;
        for (int tr = 0; tr < DEM_FILL_TRIES && !ok; ++tr) {
            int sm = sample(w, rg, r, x);
            if (sm == 0) break;
            if (sm < 0) continue;
            ok = dem_pgrid_free_at(&g, x, r);
        }
        if (!ok) break;
        if (!dem_pgrid_add(&g, x, r)) { dem_pgrid_free(&g); return DEM_FAIL(w, DEM_ERR_NOMEM, "fill grid"); }
        dem_particle p;
        memset(&p, 0, sizeof p);
        p.id = -1;
        memcpy(p.x, x, sizeof x);
        memcpy(p.v, t->velocity, sizeof p.v);
        p.radius = r; p.density = rho; p.material = t->material;
        s = w->keep && !w->keep(x, w->keep_user) ? dem_shadow_particle(w, &p) : dem_append_particle(w, &p);
        if (s) { dem_pgrid_free(&g); return s; }
        w->inserted++;
        done++;
    }
    dem_pgrid_free(&g);
    if (inserted) *inserted = done;
    if (done < n)
        return DEM_FAIL(w, DEM_ERR_FULL, "placed %zu of %zu particles (%d attempts each)", done, n, DEM_FILL_TRIES);
    return DEM_OK;
}

dem_status dem_world_fill_box(dem_world *w, const double lo[3], const double hi[3],
                              dem_inside_fn inside, void *user, size_t n,
                              const dem_particle_template *t, size_t *inserted)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, lo, "fill_box");
    DEM_NEED(w, hi, "fill_box");
    region rg;
    memset(&rg, 0, sizeof rg);
    for (int k = 0; k < 3; ++k) {
        if (!(hi[k] > lo[k]) || !isfinite(hi[k] - lo[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "fill_box: lo[%d] = %g, hi[%d] = %g; need finite lo < hi with a "
                            "finite difference", k, lo[k], k, hi[k]);
        rg.lo[k] = lo[k]; rg.hi[k] = hi[k];
    }
    rg.inside = inside; rg.user = user;
    return fill(w, &rg, n, t, inserted);
}

dem_status dem_cylinder_frame(dem_world *w, const char *fn, const double base[3], const double axis[3],
                              double radius, double length, double ax[3], double e1[3], double e2[3])
{
    DEM_NEED(w, base, fn);
    DEM_NEED(w, axis, fn);
    double al = sqrt(dem_dot(axis, axis));
    if (!(al > 0) || !isfinite(al))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: axis (%g %g %g); need finite, with a length > 0 "
                        "and finite", fn, axis[0], axis[1], axis[2]);
    if (!(radius > 0) || !(length > 0) || !isfinite(radius) || !isfinite(length))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: radius = %g, length = %g; need > 0 and finite", fn, radius, length);
    for (int k = 0; k < 3; ++k)
        if (!isfinite(base[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: base[%d] = %g; must be finite", fn, k, base[k]);
    for (int k = 0; k < 3; ++k) ax[k] = axis[k] / al;
    double tmp[3] = {1, 0, 0};
    if (fabs(ax[0]) > 0.9) { tmp[0] = 0; tmp[1] = 1; }
    dem_cross(ax, tmp, e1);
    double l1 = sqrt(dem_dot(e1, e1));
    for (int k = 0; k < 3; ++k) e1[k] /= l1;
    dem_cross(ax, e1, e2);
    return DEM_OK;
}

dem_status dem_world_fill_cylinder(dem_world *w, const double base[3], const double axis[3],
                                   double radius, double length, size_t n,
                                   const dem_particle_template *t, size_t *inserted)
{
    if (!w) return DEM_ERR_ARG;
    region rg;
    memset(&rg, 0, sizeof rg);
    dem_status s = dem_cylinder_frame(w, "fill_cylinder", base, axis, radius, length, rg.ax, rg.e1, rg.e2);
    if (s) return s;
    rg.kind = 1;
    rg.R = radius; rg.L = length;
    for (int k = 0; k < 3; ++k) rg.base[k] = base[k];
    for (int k = 0; k < 3; ++k) {
        double top = base[k] + length * rg.ax[k];
        rg.lo[k] = fmin(base[k], top) - radius;
        rg.hi[k] = fmax(base[k], top) + radius;
        if (!isfinite(rg.hi[k] - rg.lo[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "fill_cylinder: base (%g %g %g), radius = %g, length = %g; the "
                            "bounding box must be finite", base[0], base[1], base[2], radius, length);
    }
    return fill(w, &rg, n, t, inserted);
}
