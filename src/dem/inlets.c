/*---------------------------------------------------------------------------*\
  demFoam DEM core - inlets: particles streamed through a polygon at a
  number or mass rate.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEM_INLET_TRIES 20    /* attempts per inlet particle per step */

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
    dem_status s = dem_template_check(w, t, &dmax, "add_inlet");
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
    dem_status s = dem_template_check(w, &t, &dmax, what);
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

dem_status dem_world_clear_inlets(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    for (int i = 0; i < w->ninlets; ++i) free(w->inlets[i].poly);
    w->ninlets = 0;
    return DEM_OK;
}
