/*---------------------------------------------------------------------------*\
  demFoam DEM core - particle storage (SoA): capacity, checks, adding and
  removing particles (removals booked on outlets), the arrays of the API.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GROW(ptr, n) do { void *q_ = realloc((ptr), (n) * sizeof *(ptr)); if (!q_) return DEM_ERR_NOMEM; (ptr) = q_; } while (0)

static dem_status reserve_raw(dem_world *w, size_t cap)
{
    GROW(w->id, cap); GROW(w->x, 3 * cap); GROW(w->v, 3 * cap); GROW(w->w, 3 * cap);
    GROW(w->f, 3 * cap); GROW(w->t, 3 * cap); GROW(w->rad, cap); GROW(w->mass, cap);
    GROW(w->rho, cap); GROW(w->mat_of, cap); GROW(w->x0, 3 * cap); GROW(w->list_index, cap);
    if (w->have_ext) {
        GROW(w->fext, 3 * cap); GROW(w->text, 3 * cap); GROW(w->K, cap);
        GROW(w->uf, 3 * cap); GROW(w->J, 3 * cap); GROW(w->Ma, cap);
        for (int k = 0; k < DEM_N_TAGS; ++k) GROW(w->tag[k], cap);
    }
    w->cap = cap;
    return DEM_OK;
}

dem_status dem_reserve(dem_world *w, size_t cap)
{
    if (cap <= w->cap) return DEM_OK;
    /* one more particle (insertion one at a time): grow by half; a bulk
       request (several particles): to the need, or by an eighth when that
       is more (repeated bulk adds stay amortised), so that the capacity
       slack stays below 1/8 of the arrays (memory per particle) */
    const int one = cap == w->cap + 1;
    size_t nc = one ? w->cap + w->cap / 2 : w->cap + w->cap / 8;
    if (nc < 64) nc = 64;
    if (nc < cap) nc = cap;
    if (reserve_raw(w, nc) != DEM_OK)
        return DEM_FAIL(w, DEM_ERR_NOMEM, "particle storage for %zu particles", nc);
    return DEM_OK;
}

dem_status dem_ext_alloc(dem_world *w)
{
    if (w->have_ext) return DEM_OK;
    size_t cap = w->cap ? w->cap : 1;
    w->fext = calloc(3 * cap, sizeof(double));
    w->text = calloc(3 * cap, sizeof(double));
    w->K = calloc(cap, sizeof(double));
    w->uf = calloc(3 * cap, sizeof(double));
    w->J = calloc(3 * cap, sizeof(double));
    w->Ma = calloc(cap, sizeof(double));
    int tags_ok = 1;
    for (int k = 0; k < DEM_N_TAGS; ++k) {
        w->tag[k] = malloc(cap * sizeof(int64_t));
        tags_ok = tags_ok && w->tag[k];
    }
    if (!w->fext || !w->text || !w->K || !w->uf || !w->J || !w->Ma || !tags_ok) {
        free(w->fext); free(w->text); free(w->K); free(w->uf); free(w->J); free(w->Ma);
        w->fext = w->text = w->K = w->uf = w->J = w->Ma = NULL;
        for (int k = 0; k < DEM_N_TAGS; ++k) { free(w->tag[k]); w->tag[k] = NULL; }
        return DEM_FAIL(w, DEM_ERR_NOMEM, "coupling arrays for %zu particles", cap);
    }
    dem_tags_reset(w, 0, cap);
    w->have_ext = 1;
    return DEM_OK;
}

/* Copy particle src to slot dst (both < cap). */
static void move_particle(dem_world *w, size_t dst, size_t src)
{
    if (dst == src) return;
    w->id[dst] = w->id[src];
    memcpy(w->x + 3 * dst, w->x + 3 * src, 3 * sizeof(double));
    memcpy(w->v + 3 * dst, w->v + 3 * src, 3 * sizeof(double));
    memcpy(w->w + 3 * dst, w->w + 3 * src, 3 * sizeof(double));
    memcpy(w->f + 3 * dst, w->f + 3 * src, 3 * sizeof(double));
    memcpy(w->t + 3 * dst, w->t + 3 * src, 3 * sizeof(double));
    memcpy(w->x0 + 3 * dst, w->x0 + 3 * src, 3 * sizeof(float));
    w->rad[dst] = w->rad[src]; w->mass[dst] = w->mass[src]; w->rho[dst] = w->rho[src];
    w->mat_of[dst] = w->mat_of[src]; w->list_index[dst] = w->list_index[src];
    if (w->have_ext) {
        memcpy(w->fext + 3 * dst, w->fext + 3 * src, 3 * sizeof(double));
        memcpy(w->text + 3 * dst, w->text + 3 * src, 3 * sizeof(double));
        memcpy(w->uf + 3 * dst, w->uf + 3 * src, 3 * sizeof(double));
        memcpy(w->J + 3 * dst, w->J + 3 * src, 3 * sizeof(double));
        w->K[dst] = w->K[src];
        w->Ma[dst] = w->Ma[src];
        for (int k = 0; k < DEM_N_TAGS; ++k) w->tag[k][dst] = w->tag[k][src];
    }
}

/* Move the block of cnt particles [src, src + cnt) to [dst, dst + cnt)
 * (overlap allowed; all per-particle arrays, memmove): the ghost block is
 * shifted this way so that ghosts keep their order (dem.h). */
static void move_block(dem_world *w, size_t dst, size_t src, size_t cnt)
{
    if (dst == src || cnt == 0) return;
#define MB(a, m) memmove((a) + (m) * dst, (a) + (m) * src, (m) * cnt * sizeof *(a))
    MB(w->id, 1); MB(w->x, 3); MB(w->v, 3); MB(w->w, 3); MB(w->f, 3); MB(w->t, 3); MB(w->x0, 3);
    MB(w->rad, 1); MB(w->mass, 1); MB(w->rho, 1); MB(w->mat_of, 1); MB(w->list_index, 1);
    if (w->have_ext) {
        MB(w->fext, 3); MB(w->text, 3); MB(w->uf, 3); MB(w->J, 3); MB(w->K, 1); MB(w->Ma, 1);
        for (int k = 0; k < DEM_N_TAGS; ++k) MB(w->tag[k], 1);
    }
#undef MB
}

/* 1 if a sphere of this radius and density has a mass, a moment of inertia
 * and a squared radius that are finite normal doubles (the integrator
 * divides by them), computed as dem_append_particle does. */
int dem_inertia_ok(double m, double r)
{
    double r2 = r * r, I = 0.4 * m * r2;
    return isfinite(m) && m >= DBL_MIN && isfinite(r2) && r2 >= DBL_MIN && isfinite(I) && I >= DBL_MIN &&
           isfinite(2.5 / m / r2);
}
int dem_mass_ok(double r, double rho) { return dem_inertia_ok(rho * 4.0 / 3.0 * DEM_PI * r * r * r, r); }

/* Room for n more particles (owned + ghosts stay within DEM_MAX_PARTICLES). */
dem_status dem_room_for(dem_world *w, size_t n, const char *what)
{
    size_t have = w->n + w->ng;
    if (n > (size_t)DEM_MAX_PARTICLES - have)
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: %zu more particles with %zu present; at most %d particles "
                        "(owned + ghosts) per world", what, n, have, DEM_MAX_PARTICLES);
    return DEM_OK;
}

/* The checks of one particle before it is stored. */
dem_status dem_particle_check(dem_world *w, const dem_particle *p, const char *what)
{
    if (!(p->radius > 0) || !isfinite(p->radius))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: particle id %lld: radius = %g; allowed > 0 and finite",
                        what, (long long)p->id, p->radius);
    if (!(p->density > 0) || !isfinite(p->density))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: particle id %lld: density = %g; allowed > 0 and finite",
                        what, (long long)p->id, p->density);
    if (!dem_mass_ok(p->radius, p->density))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: particle id %lld: radius = %g and density = %g give a mass or "
                        "moment of inertia that is not a finite normal double (%g kg)", what, (long long)p->id,
                        p->radius, p->density, p->density * 4.0 / 3.0 * DEM_PI * p->radius * p->radius * p->radius);
    if (p->material < 0 || p->material >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "%s: particle id %lld: material = %d; allowed 0..%d (%d materials "
                        "defined)", what, (long long)p->id, p->material, w->nmat - 1, w->nmat);
    if (dem_material_rigid(&w->mat[p->material], w->cfg.contact_law))
        return DEM_FAIL(w, DEM_ERR_ARG, "%s: particle id %lld: material %d is rigid (DEM_RIGID); allowed for "
                        "walls only", what, (long long)p->id, p->material);
    for (int k = 0; k < 3; ++k)
        if (!isfinite(p->x[k]) || !isfinite(p->v[k]) || !isfinite(p->omega[k]))
            return DEM_FAIL(w, DEM_ERR_NAN, "%s: particle id %lld: x[%d] = %g, v[%d] = %g, omega[%d] = %g; "
                            "must be finite", what, (long long)p->id, k, p->x[k], k, p->v[k], k, p->omega[k]);
    if (p->id == INT64_MAX)
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: particle id %lld; allowed 0..%lld (or < 0: assigned)", what,
                        (long long)p->id, (long long)(INT64_MAX - 1));
    if (p->id < 0 && w->next_id == INT64_MAX)
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: no free particle id left (largest id in use %lld)", what,
                        (long long)(INT64_MAX - 1));
    return DEM_OK;
}

/* Validated append of one owned particle (the ghost block, if any, is
 * shifted up by one as a whole: ghosts keep their order). */
dem_status dem_append_particle(dem_world *w, const dem_particle *p)
{
    dem_status s = dem_particle_check(w, p, "add particle");
    if (s) return s;
    if ((s = dem_room_for(w, 1, "add particle"))) return s;
    s = dem_reserve(w, w->n + w->ng + 1);
    if (s) return s;
    size_t i = w->n;
    move_block(w, w->n + 1, w->n, w->ng); /* ghosts up by one, order kept */
    w->id[i] = p->id >= 0 ? p->id : w->next_id;
    if (w->id[i] >= w->next_id) w->next_id = w->id[i] + 1;
    for (int k = 0; k < 3; ++k) {
        w->x[3 * i + k] = p->x[k]; w->v[3 * i + k] = p->v[k]; w->w[3 * i + k] = p->omega[k];
        w->f[3 * i + k] = 0.0; w->t[3 * i + k] = 0.0; w->x0[3 * i + k] = (float)p->x[k];
    }
    w->rad[i] = p->radius;
    w->rho[i] = p->density;
    w->mass[i] = p->density * 4.0 / 3.0 * DEM_PI * p->radius * p->radius * p->radius;
    w->mat_of[i] = p->material;
    w->list_index[i] = -1;
    if (w->have_ext) {
        for (int k = 0; k < 3; ++k)
            w->fext[3 * i + k] = w->text[3 * i + k] = w->uf[3 * i + k] = w->J[3 * i + k] = 0.0;
        w->K[i] = 0.0;
        w->Ma[i] = 0.0;
        dem_tags_reset(w, i, 1);
    }
    w->n++;
    w->list_valid = 0;
    /* forces_valid is kept: the stored forces of the others stay those of the
       last evaluation (recomputing them here would change the damping
       velocities); the new particle starts with f = 0 until the next one */
    w->reorders++;
    return DEM_OK;
}

dem_status dem_world_add_particles(dem_world *w, size_t n, const dem_particle *p)
{
    if (!w) return DEM_ERR_ARG;
    if (n) DEM_NEED(w, p, "add_particles");
    if (w->nmat == 0) return DEM_FAIL(w, DEM_ERR_STATE, "add_particles: no materials yet; add a material before particles");
    dem_status s = dem_room_for(w, w->keep ? 0 : n, "add_particles");
    if (s) return s;
    /* all or nothing: check every particle first */
    for (size_t i = 0; i < n; ++i) {
        char what[64];
        snprintf(what, sizeof what, "add_particles: p[%zu]", i);
        if ((s = dem_particle_check(w, &p[i], what))) return s;
        if (p[i].id < 0 && w->next_id > INT64_MAX - 1 - (int64_t)i)
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: no free particle id left", what);
    }
    s = dem_reserve(w, w->n + w->ng + (w->keep ? 0 : n));
    if (s) return s;
    for (size_t i = 0; i < n; ++i) {
        s = w->keep && !w->keep(p[i].x, w->keep_user) ? dem_shadow_particle(w, &p[i])
                                                        : dem_append_particle(w, &p[i]);
        if (s) return s;
        w->inserted++;
    }
    return DEM_OK;
}

void dem_remove_index(dem_world *w, size_t i)
{
    size_t last = w->n - 1;
    move_particle(w, i, last);
    move_block(w, last, w->n, w->ng); /* ghosts down by one, order kept */
    w->n--;
    w->list_valid = 0;
    w->reorders++;
}

static dem_status book_removal(dem_world *w, size_t i, int outlet)
{
    if (outlet < 0) return DEM_OK;
    if (w->nrec == w->caprec) {
        size_t nc = w->caprec ? 2 * w->caprec : 64;
        dem_removed_record *r = realloc(w->rec, nc * sizeof *r);
        if (!r) return DEM_FAIL(w, DEM_ERR_NOMEM, "removal records: %zu", nc);
        w->rec = r;
        w->caprec = nc;
    }
    dem_removed_record *r = &w->rec[w->nrec++];
    memset(r, 0, sizeof *r); /* padding too: records go into state files */
    r->id = w->id[i];
    r->time = w->time;
    r->diameter = 2.0 * w->rad[i];
    r->density = w->rho[i];
    r->outlet = outlet;
    w->removed++; /* stats.removed: removals booked on an outlet only */
    w->outlets[outlet].count++;
    w->outlets[outlet].mass += w->mass[i];
    return DEM_OK;
}

dem_status dem_remove_booked(dem_world *w, size_t i, int outlet)
{
    dem_status s = book_removal(w, i, outlet);
    if (s) return s;
    dem_remove_index(w, i);
    return DEM_OK;
}

dem_status dem_world_remove_particle(dem_world *w, size_t index, int outlet)
{
    if (!w) return DEM_ERR_ARG;
    if (w->n == 0)
        return DEM_FAIL(w, DEM_ERR_RANGE, "remove_particle: index %zu; there are no owned particles", index);
    if (index >= w->n)
        return DEM_FAIL(w, DEM_ERR_RANGE, "remove_particle: index %zu; allowed 0..%zu (%zu owned particles)",
                        index, w->n - 1, w->n);
    if (outlet >= w->noutlets || outlet < -1)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "remove_particle: outlet %d; allowed -1 (none) or 0..%d "
                        "(%d outlets defined)", outlet, w->noutlets - 1, w->noutlets);
    if (outlet < 0) {
        /* no outlet (e.g. migration to another rank): the particle's non-zero
           pair history goes to the pending store by id, so that a partner
           owned here keeps it when the particle comes back as a ghost before
           the next list build (entries whose particles are not both here
           then are dropped there) */
        dem_status s = dem_history_to_pending(w, (ptrdiff_t)index, NULL, "remove_particle");
        if (s) return s;
    }
    return dem_remove_booked(w, index, outlet);
}

/* Removes the owned particles with how[i] != 0 (1: no outlet, 2 + k: on
 * outlet k; how NULL: those in gone, none on an outlet) in one pass over the
 * list for the pair history of those in gone (the ones without an outlet),
 * then from the highest index down: each removal moves the last particle,
 * one that stays, into the hole, as repeated remove_particle calls from the
 * top would. */
static dem_status remove_marked(dem_world *w, const int *how, const unsigned char *gone, const char *fn)
{
    dem_status st = dem_history_to_pending(w, -1, gone, fn);
    if (st) return st;
    for (size_t i = w->n; i-- > 0;) {
        const int o = how ? how[i] : gone[i];
        if (o && (st = dem_remove_booked(w, i, o - 2))) return st;
    }
    return DEM_OK;
}

dem_status dem_world_remove_unkept(dem_world *w, const unsigned char *keep)
{
    if (!w) return DEM_ERR_ARG;
    const size_t n = w->n;
    if (!n) return DEM_OK;  /* nothing to remove; an empty mask may be NULL */
    DEM_NEED(w, keep, "remove_unkept");
    unsigned char *gone = calloc(n, 1);
    if (!gone) return DEM_FAIL(w, DEM_ERR_NOMEM, "remove_unkept: mask of %zu particles", n);
    for (size_t i = 0; i < n; ++i) gone[i] = !keep[i];
    const dem_status st = remove_marked(w, NULL, gone, "remove_unkept");
    free(gone);
    return st;
}

dem_status dem_world_remove_particles(dem_world *w, const size_t *index, const int *outlet, size_t m)
{
    if (!w) return DEM_ERR_ARG;
    if (!m) return DEM_OK;
    DEM_NEED(w, index, "remove_particles");
    const size_t n = w->n;
    /* per owned particle: 0 stays, 1 goes without an outlet, 2 + k on outlet k */
    int *how = calloc(n ? n : 1, sizeof *how);
    unsigned char *gone = calloc(n ? n : 1, 1);
    dem_status st = DEM_OK;
    if (!how || !gone) { st = DEM_FAIL(w, DEM_ERR_NOMEM, "remove_particles: masks of %zu particles", n); goto out; }
    for (size_t q = 0; q < m; ++q) {
        const size_t i = index[q];
        const int o = outlet ? outlet[q] : -1;
        if (i >= n) {
            st = DEM_FAIL(w, DEM_ERR_RANGE, "remove_particles: index[%zu] = %zu; allowed 0..%zu (%zu owned "
                          "particles)", q, i, n ? n - 1 : 0, n);
            goto out;
        }
        if (o >= w->noutlets || o < -1) {
            st = DEM_FAIL(w, DEM_ERR_NOTFOUND, "remove_particles: outlet[%zu] = %d; allowed -1 (none) or 0..%d "
                          "(%d outlets defined)", q, o, w->noutlets - 1, w->noutlets);
            goto out;
        }
        if (how[i]) {
            st = DEM_FAIL(w, DEM_ERR_ARG, "remove_particles: index %zu given twice (index[%zu]); each particle "
                          "once", i, q);
            goto out;
        }
        how[i] = o < 0 ? 1 : 2 + o;
        gone[i] = o < 0;
    }
    st = remove_marked(w, how, gone, "remove_particles");
out:
    free(how);
    free(gone);
    return st;
}

dem_status dem_world_arrays(dem_world *w, dem_arrays *a)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, a, "arrays");
    if (!w->cap) { dem_status s = dem_reserve(w, 64); if (s) return s; }
    dem_status s = dem_ext_alloc(w);
    if (s) return s;
    a->n_owned = w->n;
    a->n_ghost = w->ng;
    a->id = w->id;
    a->x = w->x; a->v = w->v; a->omega = w->w;
    a->radius = w->rad; a->mass = w->mass; a->density = w->rho;
    a->material = w->mat_of;
    a->force_ext = w->fext; a->torque_ext = w->text;
    a->drag_coeff = w->K; a->fluid_velocity = w->uf; a->drag_impulse = w->J;
    a->added_mass = w->Ma;
    for (int k = 0; k < DEM_N_TAGS; ++k) a->tag[k] = w->tag[k];
    return DEM_OK;
}

/* a particle the keep filter refuses: its id, centre and radius only
   (docs/parallel.md, "Initial particles and settling") */
dem_status dem_shadow_particle(dem_world *w, const dem_particle *p)
{
    dem_status s = dem_particle_check(w, p, "add particle (not kept)");
    if (s) return s;
    if (w->nshadow == w->capshadow) {
        size_t nc = w->capshadow ? w->capshadow + w->capshadow / 2 : 1024;
        double *a = realloc(w->shadow, 4 * nc * sizeof(double));
        if (!a) return DEM_FAIL(w, DEM_ERR_NOMEM, "keep filter: shadow list of %zu particles", nc);
        w->shadow = a; w->capshadow = nc;
    }
    int64_t id = p->id >= 0 ? p->id : w->next_id;
    if (id >= w->next_id) w->next_id = id + 1;
    double *q = w->shadow + 4 * w->nshadow++;
    q[0] = p->x[0]; q[1] = p->x[1]; q[2] = p->x[2]; q[3] = p->radius;
    return DEM_OK;
}
