/*---------------------------------------------------------------------------*\
  demFoam DEM core - insertion (fill a region, stream inlets) and outlets.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  Region filling is random sequential addition: each particle (size and
  density drawn from the template's distributions) is tried at up to
  DEM_FILL_TRIES random positions inside the region and accepted if it
  overlaps neither an existing particle nor one placed before it (checked
  on a private linked-cell grid).  Seeded by dem_config.seed: deterministic.
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEM_FILL_TRIES 1000   /* attempts per particle before giving up */
#define DEM_INLET_TRIES 20    /* attempts per inlet particle per step */

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

static dem_status check_template(dem_world *w, const dem_particle_template *t, double *dmax, const char *fn)
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

/*--- private placement grid -----------------------------------------------------*/
typedef struct {
    double lo[3], cs; int nc[3];
    int *head, *next; double *xr; /* x, y, z, r per item */
    size_t n, cap;
} pgrid;

static int pgrid_init(pgrid *g, const double lo[3], const double hi[3], double cs, size_t expect)
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
static void pgrid_free(pgrid *g) { free(g->head); free(g->next); free(g->xr); }
static void pgrid_cell(const pgrid *g, const double *x, int c[3])
{
    for (int k = 0; k < 3; ++k) {
        double q = floor((x[k] - g->lo[k]) / g->cs);
        c[k] = q >= 0 ? (q < g->nc[k] ? (int)q : g->nc[k] - 1) : 0; /* clamped before the cast (NaN: 0) */
    }
}
static int pgrid_add(pgrid *g, const double *x, double r)
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
static int pgrid_free_at(const pgrid *g, const double *x, double r)
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
    dem_status s = check_template(w, t, &dmax, rg->kind == 0 ? "fill_box" : "fill_cylinder");
    if (s) return s;
    if ((s = dem_room_for(w, n, rg->kind == 0 ? "fill_box" : "fill_cylinder"))) return s;
    if (n == 0) return DEM_OK;
    double amax = 0.5 * dmax;
    for (size_t i = 0; i < w->n; ++i) amax = fmax(amax, w->rad[i]);
    pgrid g;
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) { lo[k] = rg->lo[k] - 2 * amax; hi[k] = rg->hi[k] + 2 * amax; }
    if (!pgrid_init(&g, lo, hi, 2.0 * amax, n + w->n)) { pgrid_free(&g); return DEM_FAIL(w, DEM_ERR_NOMEM, "fill grid"); }
    for (size_t i = 0; i < w->n; ++i) {
        const double *x = w->x + 3 * i;
        int in = 1;
        for (int k = 0; k < 3; ++k) in = in && x[k] > lo[k] && x[k] < hi[k];
        if (in && !pgrid_add(&g, x, w->rad[i])) { pgrid_free(&g); return DEM_FAIL(w, DEM_ERR_NOMEM, "fill grid"); }
    }
    s = dem_reserve(w, w->n + w->ng + n);
    if (s) { pgrid_free(&g); return s; }
    size_t done = 0;
    for (size_t q = 0; q < n; ++q) {
        double d = dem_dist_draw(w, &t->diameter), rho = dem_dist_draw(w, &t->density), r = 0.5 * d;
        double x[3];
        int ok = 0;
        for (int tr = 0; tr < DEM_FILL_TRIES && !ok; ++tr) {
            int sm = sample(w, rg, r, x);
            if (sm == 0) break;
            if (sm < 0) continue;
            ok = pgrid_free_at(&g, x, r);
        }
        if (!ok) break;
        if (!pgrid_add(&g, x, r)) { pgrid_free(&g); return DEM_FAIL(w, DEM_ERR_NOMEM, "fill grid"); }
        dem_particle p;
        memset(&p, 0, sizeof p);
        p.id = -1;
        memcpy(p.x, x, sizeof x);
        memcpy(p.v, t->velocity, sizeof p.v);
        p.radius = r; p.density = rho; p.material = t->material;
        s = dem_append_particle(w, &p);
        if (s) { pgrid_free(&g); return s; }
        w->inserted++;
        done++;
    }
    pgrid_free(&g);
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

dem_status dem_world_fill_cylinder(dem_world *w, const double base[3], const double axis[3],
                                   double radius, double length, size_t n,
                                   const dem_particle_template *t, size_t *inserted)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, base, "fill_cylinder");
    DEM_NEED(w, axis, "fill_cylinder");
    double al = sqrt(dem_dot(axis, axis));
    if (!(al > 0) || !isfinite(al))
        return DEM_FAIL(w, DEM_ERR_RANGE, "fill_cylinder: axis (%g %g %g); need finite, with a length > 0 "
                        "and finite", axis[0], axis[1], axis[2]);
    if (!(radius > 0) || !(length > 0) || !isfinite(radius) || !isfinite(length))
        return DEM_FAIL(w, DEM_ERR_RANGE, "fill_cylinder: radius = %g, length = %g; need > 0 and finite", radius, length);
    for (int k = 0; k < 3; ++k)
        if (!isfinite(base[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "fill_cylinder: base[%d] = %g; must be finite", k, base[k]);
    region rg;
    memset(&rg, 0, sizeof rg);
    rg.kind = 1;
    rg.R = radius; rg.L = length;
    for (int k = 0; k < 3; ++k) { rg.base[k] = base[k]; rg.ax[k] = axis[k] / al; }
    double tmp[3] = {1, 0, 0};
    if (fabs(rg.ax[0]) > 0.9) { tmp[0] = 0; tmp[1] = 1; }
    dem_cross(rg.ax, tmp, rg.e1);
    double l1 = sqrt(dem_dot(rg.e1, rg.e1));
    for (int k = 0; k < 3; ++k) rg.e1[k] /= l1;
    dem_cross(rg.ax, rg.e1, rg.e2);
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

/*--- inlets ------------------------------------------------------------------------*/
/* d into a zeroed dst member by member (no padding bytes of the caller:
 * the inlet goes into state files, which equal runs give byte-identical). */
static void dist_copy(dem_distribution *dst, const dem_distribution *d)
{
    memset(dst, 0, sizeof *dst);
    dst->kind = d->kind;
    dst->a = d->a;
    dst->b = d->b;
    dst->n = d->n;
    dst->values = d->values;
    dst->weights = d->weights;
}
static void template_copy(dem_particle_template *dst, const dem_particle_template *t)
{
    memset(dst, 0, sizeof *dst);
    dist_copy(&dst->diameter, &t->diameter);
    dist_copy(&dst->density, &t->density);
    dst->material = t->material;
    memcpy(dst->velocity, t->velocity, sizeof dst->velocity);
}
_Static_assert(offsetof(dem_distribution, weights) + sizeof(double *) == sizeof(dem_distribution) &&
               offsetof(dem_particle_template, velocity) + 3 * sizeof(double) == sizeof(dem_particle_template),
               "dist_copy/template_copy: a new last member must be copied too");

static void inlet_template(const dem_inlet *in, dem_particle_template *t)
{
    *t = in->t;
    if (t->diameter.kind == DEM_DIST_DISCRETE) { t->diameter.values = in->tw_d; t->diameter.weights = in->tw_d + 32; }
    if (t->density.kind == DEM_DIST_DISCRETE) { t->density.values = in->tw_rho; t->density.weights = in->tw_rho + 32; }
}

dem_status dem_world_add_inlet(dem_world *w, size_t nv, const double *polygon,
                               dem_rate_kind kind, double rate, double t_start, double t_end,
                               const dem_particle_template *t, int *inlet_id)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, polygon, "add_inlet");
    double dmax;
    dem_status s = check_template(w, t, &dmax, "add_inlet");
    if (s) return s;
    if (nv < 3 || nv > 1000000)
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_inlet: nv = %zu polygon vertices; allowed 3..1000000", nv);
    if (kind != DEM_RATE_NUMBER && kind != DEM_RATE_MASS)
        return DEM_FAIL(w, DEM_ERR_ARG, "add_inlet: rate kind %d; allowed %d (number) or %d (mass)", (int)kind,
                        (int)DEM_RATE_NUMBER, (int)DEM_RATE_MASS);
    if (!(rate >= 0) || !isfinite(rate))
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_inlet: rate = %g; allowed >= 0 and finite", rate);
    if (!(t_end >= t_start))
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_inlet: t_start = %g, t_end = %g; need t_start <= t_end", t_start, t_end);
    if ((t->diameter.kind == DEM_DIST_DISCRETE && t->diameter.n > 32) ||
        (t->density.kind == DEM_DIST_DISCRETE && t->density.n > 32))
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_inlet: discrete distributions with %zu (diameter) and %zu (density) "
                        "values; at most 32", t->diameter.kind == DEM_DIST_DISCRETE ? t->diameter.n : 0,
                        t->density.kind == DEM_DIST_DISCRETE ? t->density.n : 0);
    for (size_t i = 0; i < 3 * nv; ++i)
        if (!isfinite(polygon[i]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "add_inlet: polygon vertex %zu coordinate %zu = %g; must be finite",
                            i / 3, i % 3, polygon[i]);
    dem_inlet in;
    memset(&in, 0, sizeof in);
    in.nv = nv;
    in.poly = malloc(3 * nv * sizeof(double));
    if (!in.poly) return DEM_FAIL(w, DEM_ERR_NOMEM, "inlet polygon");
    memcpy(in.poly, polygon, 3 * nv * sizeof(double));
    /* normal and area (Newell) */
    double nrm[3] = {0, 0, 0};
    for (size_t i = 0; i < nv; ++i) {
        const double *a = polygon + 3 * i, *b = polygon + 3 * ((i + 1) % nv);
        nrm[0] += (a[1] - b[1]) * (a[2] + b[2]);
        nrm[1] += (a[2] - b[2]) * (a[0] + b[0]);
        nrm[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    double l = sqrt(dem_dot(nrm, nrm));
    if (!(l > 0) || !isfinite(l)) {
        free(in.poly);
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_inlet: polygon of %zu vertices has area %g; need > 0 and finite",
                        nv, 0.5 * l);
    }
    for (int k = 0; k < 3; ++k) in.n[k] = nrm[k] / l;
    in.area = 0.5 * l;
    in.kind = kind; in.rate = rate; in.t_start = t_start; in.t_end = t_end;
    template_copy(&in.t, t);
    if (t->diameter.kind == DEM_DIST_DISCRETE) {
        memcpy(in.tw_d, t->diameter.values, t->diameter.n * sizeof(double));
        memcpy(in.tw_d + 32, t->diameter.weights, t->diameter.n * sizeof(double));
    }
    if (t->density.kind == DEM_DIST_DISCRETE) {
        memcpy(in.tw_rho, t->density.values, t->density.n * sizeof(double));
        memcpy(in.tw_rho + 32, t->density.weights, t->density.n * sizeof(double));
    }
    in.t.diameter.values = in.t.diameter.weights = NULL;
    in.t.density.values = in.t.density.weights = NULL;
    dem_inlet *a = realloc(w->inlets, (size_t)(w->ninlets + 1) * sizeof *a);
    if (!a) { free(in.poly); return DEM_FAIL(w, DEM_ERR_NOMEM, "inlets"); }
    w->inlets = a;
    w->inlets[w->ninlets] = in;
    if (inlet_id) *inlet_id = w->ninlets;
    w->ninlets++;
    return DEM_OK;
}

/* Checks of a stored inlet (a restored state file). */
dem_status dem_inlet_check(dem_world *w, const dem_inlet *in, const char *what)
{
    if (in->nv < 3 || in->nv > 1000000 || !in->poly)
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: nv = %zu polygon vertices; allowed 3..1000000", what, in->nv);
    for (size_t i = 0; i < 3 * in->nv; ++i)
        if (!isfinite(in->poly[i]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: polygon coordinate %zu = %g; must be finite", what, i, in->poly[i]);
    if (!(in->area > 0) || !isfinite(in->area) || !isfinite(in->n[0] + in->n[1] + in->n[2]))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: area %g, normal (%g %g %g); need a finite area > 0 and normal",
                        what, in->area, in->n[0], in->n[1], in->n[2]);
    if ((in->kind != DEM_RATE_NUMBER && in->kind != DEM_RATE_MASS) || !(in->rate >= 0) || !isfinite(in->rate) ||
        !(in->t_end >= in->t_start))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: rate kind %d, rate %g, t_start %g, t_end %g; need kind 0 or 1, a "
                        "finite rate >= 0, t_start <= t_end", what, (int)in->kind, in->rate, in->t_start, in->t_end);
    if ((in->t.diameter.kind == DEM_DIST_DISCRETE && in->t.diameter.n > 32) ||
        (in->t.density.kind == DEM_DIST_DISCRETE && in->t.density.n > 32))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: discrete distributions of more than 32 values", what);
    if (!(in->due >= 0) || !isfinite(in->due))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: amount owed %g; need finite and >= 0", what, in->due);
    dem_particle_template t;
    inlet_template(in, &t);
    double dmax;
    dem_status s = check_template(w, &t, &dmax, what);
    if (s) return s;
    if (in->have_next && (!(in->next_d > 0) || !(in->next_rho > 0) || !dem_mass_ok(0.5 * in->next_d, in->next_rho)))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: next particle diameter %g, density %g; need a finite positive mass",
                        what, in->next_d, in->next_rho);
    if (in->inserted < 0 || in->inserted > INT64_MAX / 2)
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: inserted count %lld", what, (long long)in->inserted);
    return DEM_OK;
}

/* 1 if a sphere (x, r) at the current time overlaps no wall (planes: on the
 * inner side by at least r; triangles: closest point farther than r). */
static int clear_of_walls(const dem_world *w, const double x[3], double r)
{
    for (int k = 0; k < w->nplanes; ++k) {
        const dem_plane *P = &w->planes[k];
        double d = 0;
        for (int c = 0; c < 3; ++c) d += (x[c] - P->x0[c] - P->vel[c] * (w->time - P->t0)) * P->n[c];
        if (d < r && d > -r) return 0;
    }
    for (int k = 0; k < w->nmeshes; ++k) {
        const dem_mesh *m = &w->meshes[k];
        double off[3];
        for (int c = 0; c < 3; ++c) off[c] = m->vel[c] * (w->time - m->t0);
        for (size_t t = 0; t < m->ntri; ++t) {
            double P[3][3], lo[3], hi[3];
            for (int v = 0; v < 3; ++v)
                for (int c = 0; c < 3; ++c) P[v][c] = m->v0[3 * (size_t)m->tri[3 * t + v] + c] + off[c];
            int far = 0;
            for (int c = 0; c < 3; ++c) {
                lo[c] = fmin(P[0][c], fmin(P[1][c], P[2][c])) - r;
                hi[c] = fmax(P[0][c], fmax(P[1][c], P[2][c])) + r;
                far = far || x[c] < lo[c] || x[c] > hi[c];
            }
            if (far) continue;
            double q[3], d2 = 0;
            dem_closest_on_triangle(x, P[0], P[1], P[2], q);
            for (int c = 0; c < 3; ++c) d2 += (x[c] - q[c]) * (x[c] - q[c]);
            if (d2 < r * r) return 0;
        }
    }
    return 1;
}

static void polygon_point(dem_world *w, const dem_inlet *in, double x[3])
{
    /* fan from vertex 0; pick a triangle by area, uniform inside it */
    const double *p0 = in->poly;
    double u = dem_rng_uniform(w) * in->area, acc = 0;
    size_t tri = 1;
    for (size_t i = 1; i + 1 < in->nv; ++i) {
        const double *a = in->poly + 3 * i, *b = in->poly + 3 * (i + 1);
        double e1[3], e2[3], c[3];
        for (int k = 0; k < 3; ++k) { e1[k] = a[k] - p0[k]; e2[k] = b[k] - p0[k]; }
        dem_cross(e1, e2, c);
        acc += 0.5 * sqrt(dem_dot(c, c));
        tri = i;
        if (u < acc) break;
    }
    const double *a = in->poly + 3 * tri, *b = in->poly + 3 * (tri + 1);
    double r1 = dem_rng_uniform(w), r2 = dem_rng_uniform(w);
    if (r1 + r2 > 1) { r1 = 1 - r1; r2 = 1 - r2; }
    for (int k = 0; k < 3; ++k) x[k] = p0[k] + r1 * (a[k] - p0[k]) + r2 * (b[k] - p0[k]);
}

dem_status dem_inlets_run(dem_world *w)
{
    for (int q = 0; q < w->ninlets; ++q) {
        dem_inlet *in = &w->inlets[q];
        double t0 = w->time - w->cfg.dt, t1 = w->time;
        double a = fmax(t0, in->t_start), b = fmin(t1, in->t_end);
        if (b > a) in->due += in->rate * (b - a);
        dem_particle_template t;
        inlet_template(in, &t);
        if (!in->have_next) {
            in->next_d = dem_dist_draw(w, &t.diameter);
            in->next_rho = dem_dist_draw(w, &t.density);
            in->have_next = 1;
        }
        for (;;) {
            double r = 0.5 * in->next_d;
            double mnext = in->next_rho * 4.0 / 3.0 * DEM_PI * r * r * r;
            double need = in->kind == DEM_RATE_NUMBER ? 1.0 : mnext;
            if (in->due < need) break;
            /* candidate overlap set: particles near the polygon plane */
            double x[3];
            int ok = 0;
            for (int tr = 0; tr < DEM_INLET_TRIES && !ok; ++tr) {
                polygon_point(w, in, x);
                ok = clear_of_walls(w, x, r);
                /* ghosts too: in a decomposed run the inserting rank must
                   not place a particle onto one owned by a neighbour */
                for (size_t i = 0; i < w->n + w->ng && ok; ++i) {
                    const double *y = w->x + 3 * i;
                    double d0 = x[0] - y[0], d1 = x[1] - y[1], d2 = x[2] - y[2], s = r + w->rad[i];
                    if (d0 * d0 + d1 * d1 + d2 * d2 < s * s) ok = 0;
                }
            }
            if (!ok) { /* blocked: keep what is owed for the next step */
                if (!in->warned && in->due > need + 100.0 * (in->kind == DEM_RATE_NUMBER ? 1.0 : mnext)) {
                    in->warned = 1;
                    dem_log_(w, DEM_LOG_WARNING, "inlet %d is blocked at t = %g: %g %s owed", q, w->time,
                             in->due, in->kind == DEM_RATE_NUMBER ? "particles" : "kg");
                }
                break;
            }
            dem_particle p;
            memset(&p, 0, sizeof p);
            p.id = -1;
            memcpy(p.x, x, sizeof x);
            memcpy(p.v, t.velocity, sizeof p.v);
            p.radius = r; p.density = in->next_rho; p.material = t.material;
            dem_status s = dem_append_particle(w, &p);
            if (s) return s;
            w->inserted++;
            in->inserted++;
            in->warned = 0;
            in->due -= need;
            in->next_d = dem_dist_draw(w, &t.diameter);
            in->next_rho = dem_dist_draw(w, &t.density);
        }
    }
    return DEM_OK;
}

/*--- outlets -------------------------------------------------------------------------*/
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

dem_status dem_world_clear_inlets(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    for (int i = 0; i < w->ninlets; ++i) free(w->inlets[i].poly);
    w->ninlets = 0;
    return DEM_OK;
}
