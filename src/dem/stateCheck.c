/*---------------------------------------------------------------------------*\
  demFoam DEM core - the checks of a restored state (stateFile.c) before it
  replaces the world.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

static int finite_all(const double *a, size_t n)
{
    for (size_t i = 0; i < n; ++i) if (!isfinite(a[i])) return 0;
    return 1;
}

static int csr_ok(const int *off, size_t rows, size_t total)
{
    if (off[0] != 0 || (size_t)off[rows] != total) return 0;
    for (size_t r = 0; r < rows; ++r) if (off[r + 1] < off[r]) return 0;
    return 1;
}

/* Checks of everything a restored world relies on: indices in range, sizes
 * consistent, the checks of configure/add_material, particle sizes and
 * masses, walls and inlets.  Positions, velocities, forces, coupling inputs
 * and contact histories are the state as saved (a non-finite one is
 * reported by the next dem_world_step, as before the save).  The message
 * goes to err; returns 1 if the state is unusable. */
static int corrupt(dem_world *err, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static int corrupt(dem_world *err, const char *path, const char *fmt, ...)
{
    char buf[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    DEM_FAIL(err, DEM_ERR_FORMAT, "restore: '%s' is corrupt: %s", path, buf);
    return 1;
}
#define CORRUPT(...) return corrupt(err, path, __VA_ARGS__)
int dem_state_check(dem_world *w, dem_world *err, const char *path)
{
    size_t np = w->n + w->ng;
    if (dem_config_check(w, &w->cfg)) CORRUPT("configuration: %s", dem_error_detail(w));
    for (int i = 0; i < w->nmat; ++i) {
        char what[32];
        snprintf(what, sizeof what, "material %d", i);
        if (dem_material_check(w, &w->mat[i], what, 0)) CORRUPT("%s", dem_error_detail(w));
    }
    for (int k = 0; k < w->novr; ++k) {
        const dem_pair_override *o = &w->ovr[k];
        if (o->a < 0 || o->a >= w->nmat || o->b < 0 || o->b >= w->nmat)
            CORRUPT("pair override %d: materials %d, %d of %d", k, o->a, o->b, w->nmat);
        if (dem_material_check(w, &o->m, "pair override", 0)) CORRUPT("%s", dem_error_detail(w));
    }
    if (w->next_id < 0) CORRUPT("next id %lld", (long long)w->next_id);
    for (size_t i = 0; i < np; ++i) {
        if (w->id[i] < 0 || w->id[i] == INT64_MAX) CORRUPT("particle %zu: id %lld", i, (long long)w->id[i]);
        if (!(w->rad[i] > 0) || !(w->rho[i] > 0) || !isfinite(w->rho[i]) || !dem_inertia_ok(w->mass[i], w->rad[i]))
            CORRUPT("particle %zu (id %lld): radius %g, mass %g, density %g", i, (long long)w->id[i], w->rad[i],
                    w->mass[i], w->rho[i]);
        if (w->mat_of[i] < 0 || w->mat_of[i] >= w->nmat)
            CORRUPT("particle %zu (id %lld): material %d of %d", i, (long long)w->id[i], w->mat_of[i], w->nmat);
        if (w->list_index[i] < -1 || (w->list_index[i] >= 0 && (size_t)w->list_index[i] >= w->nrows))
            CORRUPT("particle %zu: list row %d of %zu", i, w->list_index[i], w->nrows);
    }
    /* neighbour list */
    if (w->list_valid && w->nrows != np) CORRUPT("valid neighbour list of %zu rows for %zu particles", w->nrows, np);
    if (!isfinite(w->skin) || !(w->skin >= 0) || !isfinite(w->amax) || !isfinite(w->cutoff) ||
        !finite_all(&w->shift[0][0], 81) || !isfinite(w->t_build) || w->nbuilds < 0)
        CORRUPT("neighbour list parameters (skin %g, shifts, build time %g, builds %lld)", w->skin, w->t_build,
                (long long)w->nbuilds);
    if (w->nrows) {
        if (!csr_ok(w->nb_off, w->nrows, w->nnb)) CORRUPT("neighbour list offsets");
        for (size_t k = 0; k < w->nnb; ++k)
            if (w->nb_j[k] < 0 || (size_t)w->nb_j[k] >= w->nrows || w->nb_s[k] >= 27)
                CORRUPT("neighbour list entry %zu: partner %d of %zu rows, image %d", k, w->nb_j[k], w->nrows,
                        (int)w->nb_s[k]);
        if (!w->wc_off) CORRUPT("neighbour list without its wall list");
        if (!csr_ok(w->wc_off, w->nrows, w->nwc)) CORRUPT("wall list offsets");
    } else if (w->nnb || w->nwc) CORRUPT("%zu list entries and %zu wall entries without rows", w->nnb, w->nwc);
    /* walls: ids, kinds and indices consistent both ways */
    for (int k = 0; k < w->nwalls; ++k) {
        int kind = w->wall_kind[k], idx = w->wall_index[k];
        if (!((kind == 0 && idx >= 0 && idx < w->nplanes && w->planes[idx].wall == k) ||
              (kind == 1 && idx >= 0 && idx < w->nmeshes && w->meshes[idx].wall == k)))
            CORRUPT("wall %d: kind %d, index %d", k, kind, idx);
    }
    for (int k = 0; k < w->nplanes; ++k) {
        const dem_plane *P = &w->planes[k];
        if (P->wall < 0 || P->wall >= w->nwalls || w->wall_kind[P->wall] != 0 || w->wall_index[P->wall] != k ||
            P->material < 0 || P->material >= w->nmat || !finite_all(P->x0, 3) || !finite_all(P->n, 3) ||
            !finite_all(P->vel, 3) || !isfinite(P->t0) || !(dem_dot(P->n, P->n) > 0))
            CORRUPT("plane %d (wall %d, material %d)", k, P->wall, P->material);
    }
    size_t ntri = 0;
    for (int k = 0; k < w->nmeshes; ++k) {
        const dem_mesh *m = &w->meshes[k];
        if (m->wall < 0 || m->wall >= w->nwalls || w->wall_kind[m->wall] != 1 || w->wall_index[m->wall] != k ||
            m->material < 0 || m->material >= w->nmat || m->ntri == 0 || !finite_all(m->v0, 3 * m->nv) ||
            !finite_all(m->nrm, 3 * m->ntri) || !finite_all(m->vel, 3) || !isfinite(m->t0))
            CORRUPT("mesh %d (wall %d, material %d, %zu triangles)", k, m->wall, m->material, m->ntri);
        for (size_t i = 0; i < 3 * m->ntri; ++i)
            if (m->tri[i] < 0 || (size_t)m->tri[i] >= m->nv)
                CORRUPT("mesh %d: vertex index %d of %zu", k, m->tri[i], m->nv);
        ntri += m->ntri;
    }
    if (ntri != w->ntri_all) CORRUPT("triangle count");
    for (size_t k = 0; k < w->nwc; ++k) {
        int wall = w->wc_wall[k], t = w->wc_tri[k];
        if (wall < 0 || wall >= w->nwalls ||
            (w->wall_kind[wall] == 0 && t != -1) ||
            (w->wall_kind[wall] == 1 && (t < 0 || (size_t)t >= w->meshes[w->wall_index[wall]].ntri)))
            CORRUPT("wall list entry %zu: wall %d, triangle %d", k, wall, t);
    }
    /* time, counters, random numbers */
    if (!isfinite(w->time) || w->step < 0 || w->inserted < 0 || w->inserted > INT64_MAX / 2 || w->removed < 0 ||
        w->removed > INT64_MAX / 2 || w->reorders < 0 || w->reorders > INT64_MAX / 2 || w->nbuilds > INT64_MAX / 2)
        CORRUPT("time %g, step %lld or counters", w->time, (long long)w->step);
    if (!(w->rng[0] | w->rng[1] | w->rng[2] | w->rng[3])) CORRUPT("random number state is zero");
    for (int k = 0; k < w->ninlets; ++k) {
        char what[32];
        snprintf(what, sizeof what, "inlet %d", k);
        if (dem_inlet_check(w, &w->inlets[k], what)) CORRUPT("%s", dem_error_detail(w));
    }
    for (int k = 0; k < w->noutlets; ++k) {
        const dem_outlet *o = &w->outlets[k];
        if (o->kind < 0 || o->kind > 2 || o->count < 0 || o->count > INT64_MAX / 2 ||
            (o->kind == 0 && (!finite_all(o->a, 3) || !finite_all(o->b, 3))) ||
            (o->kind == 1 && (isnan(o->a[0] + o->a[1] + o->a[2]) || isnan(o->b[0] + o->b[1] + o->b[2]))))
            CORRUPT("outlet %d (kind %d)", k, o->kind);
    }
    return 0;
}
#undef CORRUPT
