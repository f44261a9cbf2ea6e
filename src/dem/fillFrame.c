/*---------------------------------------------------------------------------*\
  demFoam DEM core - the frame of index-computed fills (fillFrame.h).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "fillFrame.h"
#include <math.h>
#include <string.h>

uint64_t dem_mix64(uint64_t z)
{
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

dem_status dem_fill_frame_box(dem_world *w, const char *fn, const double lo[3], const double hi[3],
                              dem_fill_frame *f)
{
    DEM_NEED(w, lo, fn);
    DEM_NEED(w, hi, fn);
    memset(f, 0, sizeof *f);
    for (int k = 0; k < 3; ++k) {
        if (!(hi[k] > lo[k]) || !isfinite(hi[k] - lo[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: lo[%d] = %g, hi[%d] = %g; need finite lo < hi "
                            "with a finite difference", fn, k, lo[k], k, hi[k]);
        f->o[k] = lo[k]; f->e[k][k] = 1; f->len[k] = hi[k] - lo[k];
    }
    return DEM_OK;
}

dem_status dem_fill_frame_cylinder(dem_world *w, const char *fn, const double base[3], const double axis[3],
                                   double radius, double length, dem_fill_frame *f)
{
    memset(f, 0, sizeof *f);
    dem_status s = dem_cylinder_frame(w, fn, base, axis, radius, length, f->e[2], f->e[0], f->e[1]);
    if (s) return s;
    for (int k = 0; k < 3; ++k) f->o[k] = base[k] - radius * (f->e[0][k] + f->e[1][k]);
    f->len[0] = f->len[1] = 2 * radius; f->len[2] = length;
    f->R = radius;
    return DEM_OK;
}

dem_status dem_fill_region_free(dem_world *w, const dem_fill_frame *f, const char *fn)
{
    for (size_t i = 0; i < w->n + w->nshadow; ++i) {
        const double *x = i < w->n ? w->x + 3 * i : w->shadow + 4 * (i - w->n);
        double r = i < w->n ? w->rad[i] : x[3], q[3];
        for (int k = 0; k < 3; ++k) q[k] = x[k] - f->o[k];
        int in = 1;
        for (int a = 0; a < 3; ++a) {
            double c = dem_dot(q, f->e[a]);
            in = in && c > -r && c < f->len[a] + r;
        }
        if (in)
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: particle id %lld at (%g %g %g) lies in the region; this "
                            "fill needs a region free of particles placed before it", fn,
                            (long long)(i < w->n ? w->id[i] : -1), x[0], x[1], x[2]);
    }
    return DEM_OK;
}

int dem_fill_keep_extent(const dem_world *w, const dem_fill_frame *f, double mn[3], double mx[3])
{
    if (!w->keep || !w->keep_box_set) return 0;
    for (int a = 0; a < 3; ++a) { mn[a] = INFINITY; mx[a] = -INFINITY; }
    for (int corner = 0; corner < 8; ++corner) {
        double q[3];
        for (int k = 0; k < 3; ++k) q[k] = ((corner >> k & 1) ? w->keep_hi[k] : w->keep_lo[k]) - f->o[k];
        for (int a = 0; a < 3; ++a) {
            double v = dem_dot(q, f->e[a]);
            mn[a] = fmin(mn[a], v); mx[a] = fmax(mx[a], v);
        }
    }
    return 1;
}

void dem_fill_frame_point(const dem_fill_frame *f, const double c[3], double x[3])
{
    for (int k = 0; k < 3; ++k) x[k] = 0;
    for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 3; ++k) x[k] += c[a] * f->e[a][k];
    for (int k = 0; k < 3; ++k) x[k] += f->o[k];
}

dem_status dem_fill_in_box(dem_world *w, const char *fn, dem_frame_fill fill, const double lo[3],
                           const double hi[3], size_t n, const dem_particle_template *t, size_t *inserted)
{
    if (!w) return DEM_ERR_ARG;
    dem_fill_frame f;
    dem_status s = dem_fill_frame_box(w, fn, lo, hi, &f);
    return s ? s : fill(w, &f, n, t, inserted, fn);
}

dem_status dem_fill_in_cylinder(dem_world *w, const char *fn, dem_frame_fill fill, const double base[3],
                                const double axis[3], double radius, double length, size_t n,
                                const dem_particle_template *t, size_t *inserted)
{
    if (!w) return DEM_ERR_ARG;
    dem_fill_frame f;
    dem_status s = dem_fill_frame_cylinder(w, fn, base, axis, radius, length, &f);
    return s ? s : fill(w, &f, n, t, inserted, fn);
}

dem_status dem_fill_append(dem_world *w, const dem_particle_template *t, int64_t id, const double x[3],
                           double r, double rho)
{
    dem_particle p;
    memset(&p, 0, sizeof p);
    p.id = id;
    memcpy(p.x, x, sizeof p.x);
    memcpy(p.v, t->velocity, sizeof p.v);
    p.radius = r; p.density = rho; p.material = t->material;
    return dem_append_particle(w, &p);
}

void dem_fill_done(dem_world *w, int64_t base, size_t n, size_t *inserted)
{
    if (w->next_id < base + (int64_t)n) w->next_id = base + (int64_t)n;
    w->inserted += (int64_t)n;
    if (inserted) *inserted = n;
}
