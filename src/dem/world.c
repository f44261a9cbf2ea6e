/*---------------------------------------------------------------------------*\
  demFoam DEM core - world handle: creation, configuration, errors, logging,
  materials, particle storage, diagnostics.

  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "law.h"
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/*--- world -------------------------------------------------------------------*/
void dem_config_default(dem_config *c)
{
    if (!c) return;
    memset(c, 0, sizeof *c);
    c->contact_law = DEM_CONTACT_HERTZ_MINDLIN;
    c->dt = 1e-6;
    c->gravity[2] = -9.81;
    c->domain_hi[0] = c->domain_hi[1] = c->domain_hi[2] = 1.0;
    c->skin = 0.0;
    c->max_dt_fraction = 0.2;
    c->max_overlap_ratio = 0.1;
    c->seed = 12345u;
    c->spatial_sort = 1;
}

dem_status dem_world_create(dem_world **pw)
{
    if (!pw) return DEM_ERR_ARG;
    dem_world *w = calloc(1, sizeof *w);
    *pw = w;
    if (!w) return DEM_ERR_NOMEM;
    dem_config_default(&w->cfg);
    dem_rng_seed(w, w->cfg.seed);
    w->pairs_dirty = 1;
    w->next_id = 0;
    return DEM_OK;
}

void dem_world_destroy(dem_world **pw)
{
    if (!pw || !*pw) return;
    dem_world *w = *pw;
    free(w->mat); free(w->pair); free(w->mat_e); free(w->mat_c); free(w->ovr);
    free(w->id); free(w->x); free(w->v); free(w->w); free(w->f); free(w->t);
    free(w->rad); free(w->mass); free(w->rho); free(w->mat_of); free(w->x0);
    free(w->list_index);
    free(w->fext); free(w->text); free(w->K); free(w->uf); free(w->J); free(w->Ma);
    free(w->cell_start); free(w->cell_item); free(w->cell_of); free(w->perm);
    free(w->old2new); free(w->tmp);
    free(w->nb_off); free(w->nb_j); free(w->nb_s); free(w->nb_h);
    free(w->wc_off); free(w->wc_wall); free(w->wc_tri); free(w->wc_h);
    free(w->carry); free(w->carry_off); free(w->pend); free(w->wpend);
    free(w->wall_kind); free(w->wall_index); free(w->planes);
    for (int i = 0; i < w->nmeshes; ++i) {
        free(w->meshes[i].v0); free(w->meshes[i].tri); free(w->meshes[i].nrm);
    }
    free(w->meshes);
    free(w->tri_mesh); free(w->tri_local); free(w->tcell_start); free(w->tcell_item);
    for (int i = 0; i < w->ninlets; ++i) free(w->inlets[i].poly);
    free(w->inlets); free(w->outlets); free(w->rec); free(w->scratch); free(w->crec);
    free(w);
    *pw = NULL;
}

/* The checks of dem_world_configure (also applied to a restored configuration). */
dem_status dem_config_check(dem_world *w, const dem_config *c)
{
    if ((int)c->contact_law < 0 || c->contact_law >= DEM_CONTACT_LAW_COUNT)
        return DEM_FAIL(w, DEM_ERR_ARG, "contact_law = %d; allowed 0..%d",
                        (int)c->contact_law, DEM_CONTACT_LAW_COUNT - 1);
    if (!(c->dt > 0) || !isfinite(c->dt))
        return DEM_FAIL(w, DEM_ERR_RANGE, "dt = %g; allowed > 0 and finite", c->dt);
    for (int k = 0; k < 3; ++k) {
        if (!isfinite(c->gravity[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "gravity[%d] = %g; must be finite", k, c->gravity[k]);
        if (!(c->domain_hi[k] > c->domain_lo[k]) || !isfinite(c->domain_hi[k] - c->domain_lo[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "domain_lo[%d] = %g, domain_hi[%d] = %g; need finite lo < hi "
                            "with a finite difference", k, c->domain_lo[k], k, c->domain_hi[k]);
    }
    if (!isfinite(c->skin))
        return DEM_FAIL(w, DEM_ERR_RANGE, "skin = %g; must be finite (<= 0: default)", c->skin);
    if (!(c->max_dt_fraction > 0))
        return DEM_FAIL(w, DEM_ERR_RANGE, "max_dt_fraction = %g; allowed > 0", c->max_dt_fraction);
    if (!(c->impact_speed >= 0) || !isfinite(c->impact_speed))
        return DEM_FAIL(w, DEM_ERR_RANGE, "impact_speed = %g; allowed >= 0 and finite", c->impact_speed);
    if (!(c->max_overlap_ratio > 0))
        return DEM_FAIL(w, DEM_ERR_RANGE, "max_overlap_ratio = %g; allowed > 0", c->max_overlap_ratio);
    return DEM_OK;
}

/* c into a zeroed dst member by member: a struct copy would also copy the
 * caller's padding bytes, which go into state files (equal runs must give
 * byte-identical files). */
static void config_copy(dem_config *dst, const dem_config *c)
{
    memset(dst, 0, sizeof *dst);
    dst->contact_law = c->contact_law;
    dst->dt = c->dt;
    memcpy(dst->gravity, c->gravity, sizeof dst->gravity);
    memcpy(dst->domain_lo, c->domain_lo, sizeof dst->domain_lo);
    memcpy(dst->domain_hi, c->domain_hi, sizeof dst->domain_hi);
    memcpy(dst->periodic, c->periodic, sizeof dst->periodic);
    dst->skin = c->skin;
    dst->max_dt_fraction = c->max_dt_fraction;
    dst->max_overlap_ratio = c->max_overlap_ratio;
    dst->seed = c->seed;
    dst->spatial_sort = c->spatial_sort;
    dst->damping_predicted = c->damping_predicted ? 1 : 0;
    dst->impact_speed = c->impact_speed;
}
_Static_assert(offsetof(dem_config, impact_speed) + sizeof(double) == sizeof(dem_config),
               "config_copy: a member after impact_speed must be copied too");

dem_status dem_world_configure(dem_world *w, const dem_config *c)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, c, "configure");
    if (w->drift_pending)
        return DEM_FAIL(w, DEM_ERR_STATE, "configure: step %lld is half done (dem_world_step_drift was called); "
                        "call dem_world_step_forces first", (long long)w->step);
    dem_status st = dem_config_check(w, c);
    if (st) return st;
    if (w->n + w->ng > 0) {
        int same = c->contact_law == w->cfg.contact_law && c->skin == w->cfg.skin &&
                   (c->damping_predicted != 0) == (w->cfg.damping_predicted != 0);
        for (int k = 0; k < 3; ++k)
            same = same && c->domain_lo[k] == w->cfg.domain_lo[k] &&
                   c->domain_hi[k] == w->cfg.domain_hi[k] &&
                   (c->periodic[k] != 0) == (w->cfg.periodic[k] != 0);
        if (!same)
            return DEM_FAIL(w, DEM_ERR_STATE, "contact_law, damping_predicted, domain, periodic and skin cannot change "
                            "once particles exist (%zu particles); dt, gravity and limits can", w->n);
        double g[3] = {c->gravity[0], c->gravity[1], c->gravity[2]};
        w->cfg.dt = c->dt;
        memcpy(w->cfg.gravity, g, sizeof g);
        w->cfg.max_dt_fraction = c->max_dt_fraction;
        w->cfg.max_overlap_ratio = c->max_overlap_ratio;
        w->cfg.spatial_sort = c->spatial_sort;
        w->cfg.impact_speed = c->impact_speed;
        return DEM_OK;
    }
    uint64_t old_seed = w->cfg.seed;
    config_copy(&w->cfg, c);
    for (int k = 0; k < 3; ++k) w->cfg.periodic[k] = c->periodic[k] ? 1 : 0;
    if (c->seed != old_seed || w->step == 0) dem_rng_seed(w, c->seed);
    w->pairs_dirty = 1;
    w->list_valid = 0;
    return DEM_OK;
}

size_t  dem_world_count(const dem_world *w) { return w ? w->n : 0; }
double  dem_world_time(const dem_world *w) { return w ? w->time : 0.0; }

dem_status dem_world_set_time(dem_world *w, double t)
{
    if (!w) return DEM_ERR_ARG;
    if (!isfinite(t)) return DEM_FAIL(w, DEM_ERR_RANGE, "set_time: t = %g; allowed a finite time", t);
    /* moving walls keep their position: their reference times move with the clock */
    const double shift = t - w->time;
    for (int p = 0; p < w->nplanes; ++p) w->planes[p].t0 += shift;
    for (int m = 0; m < w->nmeshes; ++m) w->meshes[m].t0 += shift;
    w->t_build += shift;
    w->time = t;
    return DEM_OK;
}
int64_t dem_world_step_count(const dem_world *w) { return w ? w->step : 0; }
int64_t dem_world_reorder_count(const dem_world *w) { return w ? w->reorders : 0; }

/*--- materials -----------------------------------------------------------------*/
dem_status dem_world_add_material(dem_world *w, const dem_material *m, int *material_id)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, m, "add_material");
    char what[48];
    snprintf(what, sizeof what, "add_material: material %d", w->nmat);
    dem_status st = dem_material_check(w, m, what, 1);
    if (st) return st;
    if (w->nmat == w->capmat) {
        int nc = w->capmat ? 2 * w->capmat : 4;
        dem_material *p = realloc(w->mat, (size_t)nc * sizeof *p);
        if (!p) return DEM_FAIL(w, DEM_ERR_NOMEM, "materials: %d entries", nc);
        w->mat = p;
        w->capmat = nc;
    }
    dem_material mm = *m;
    if (!(mm.stiffness_t > 0)) mm.stiffness_t = 2.0 / 7.0 * mm.stiffness_n;
    w->mat[w->nmat] = mm;
    if (material_id) *material_id = w->nmat;
    w->nmat++;
    if (w->nmat_derived >= w->nmat) w->nmat_derived = w->nmat - 1;
    w->pairs_dirty = 1;
    return DEM_OK;
}

dem_status dem_world_set_pair(dem_world *w, int material_a, int material_b, const dem_material *m)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, m, "set_pair");
    if (material_a < 0 || material_a >= w->nmat || material_b < 0 || material_b >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "set_pair: material_a = %d, material_b = %d; allowed 0..%d "
                        "(%d materials defined)", material_a, material_b, w->nmat - 1, w->nmat);
    char what[64];
    snprintf(what, sizeof what, "set_pair(%d, %d): material", material_a, material_b);
    dem_status st = dem_material_check(w, m, what, 1);
    if (st) return st;
    int k = 0;
    while (k < w->novr && !((w->ovr[k].a == material_a && w->ovr[k].b == material_b) ||
                            (w->ovr[k].a == material_b && w->ovr[k].b == material_a))) ++k;
    if (k == w->novr) {
        dem_pair_override *o = realloc(w->ovr, (size_t)(w->novr + 1) * sizeof *o);
        if (!o) return DEM_FAIL(w, DEM_ERR_NOMEM, "pair overrides");
        w->ovr = o;
        w->novr++;
    }
    w->ovr[k].a = material_a;
    w->ovr[k].b = material_b;
    w->ovr[k].m = *m;
    if (!(w->ovr[k].m.stiffness_t > 0)) w->ovr[k].m.stiffness_t = 2.0 / 7.0 * w->ovr[k].m.stiffness_n;
    w->pairs_dirty = 1;
    return DEM_OK;
}

/* Checks of a material (what: its name in the message); law_check: also the
 * stiffness the law needs (dem_law.stiffness_name). */
dem_status dem_material_check(dem_world *w, const dem_material *m, const char *what, int law_check)
{
    if (!(m->poisson_ratio >= 0.0 && m->poisson_ratio < 0.5))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: poisson_ratio = %g; allowed [0, 0.5)",
                        what, m->poisson_ratio);
    if (!(m->friction >= 0.0) || !isfinite(m->friction))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: friction = %g; allowed >= 0 and finite", what, m->friction);
    if (!(m->rolling_friction >= 0.0) || !isfinite(m->rolling_friction))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: rolling_friction = %g; allowed >= 0 and finite (a length)",
                        what, m->rolling_friction);
    /* +inf is DEM_RIGID */
    if (isnan(m->youngs_modulus) || isnan(m->stiffness_n) || isnan(m->stiffness_t) ||
        m->youngs_modulus == -INFINITY || m->stiffness_n == -INFINITY || m->stiffness_t == -INFINITY)
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: youngs_modulus = %g, stiffness_n = %g, stiffness_t = %g; "
                        "must be finite (or DEM_RIGID)", what, m->youngs_modulus, m->stiffness_n, m->stiffness_t);
    if (isnan(m->restitution) || isnan(m->damping))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: restitution = %g, damping = %g; give restitution in "
                        "(0, 1] or damping >= 0 (finite), the other < 0", what, m->restitution, m->damping);
    if (m->restitution >= 0.0) {
        if (!(m->restitution > 0.0 && m->restitution <= 1.0))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: restitution = %g; allowed (0, 1] "
                            "(or < 0 to derive it from damping)", what, m->restitution);
        if (m->damping >= 0.0)
            return DEM_FAIL(w, DEM_ERR_ARG, "%s: restitution = %g and damping = %g both given; "
                            "give one and set the other < 0", what, m->restitution, m->damping);
    } else if (!(m->damping >= 0.0) || !isfinite(m->damping)) {
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: restitution = %g and damping = %g; give "
                        "restitution in (0, 1] or damping >= 0 (finite)", what, m->restitution, m->damping);
    }
    if (!law_check) return DEM_OK;
    const dem_law *law = dem_law_of(w);
    if (!(law->stiffness(m) > 0))
        return DEM_FAIL(w, DEM_ERR_RANGE, "%s: %s = %g; allowed > 0 (law %s)",
                        what, law->stiffness_name, law->stiffness(m), law->name);
    return DEM_OK;
}


dem_status dem_world_material_get(const dem_world *w, int id, dem_material *m)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, m, "material_get");
    if (id < 0 || id >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "material_get: material %d; allowed 0..%d (%d defined)", id,
                        w->nmat - 1, w->nmat);
    *m = w->mat[id];
    if (id < w->nmat_derived && w->derived_law == (int)w->cfg.contact_law) {
        m->restitution = w->mat_e[id];
        m->damping = w->mat_c[id];
    } else {
        dem_law_of(w)->derived(&w->mat[id], &m->restitution, &m->damping);
    }
    return DEM_OK;
}

/*--- particle storage ----------------------------------------------------------*/
#define GROW(ptr, n) do { void *q_ = realloc((ptr), (n) * sizeof *(ptr)); if (!q_) return DEM_ERR_NOMEM; (ptr) = q_; } while (0)

static dem_status reserve_raw(dem_world *w, size_t cap)
{
    GROW(w->id, cap); GROW(w->x, 3 * cap); GROW(w->v, 3 * cap); GROW(w->w, 3 * cap);
    GROW(w->f, 3 * cap); GROW(w->t, 3 * cap); GROW(w->rad, cap); GROW(w->mass, cap);
    GROW(w->rho, cap); GROW(w->mat_of, cap); GROW(w->x0, 3 * cap); GROW(w->list_index, cap);
    if (w->have_ext) {
        GROW(w->fext, 3 * cap); GROW(w->text, 3 * cap); GROW(w->K, cap);
        GROW(w->uf, 3 * cap); GROW(w->J, 3 * cap); GROW(w->Ma, cap);
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
    if (!w->fext || !w->text || !w->K || !w->uf || !w->J || !w->Ma) {
        free(w->fext); free(w->text); free(w->K); free(w->uf); free(w->J); free(w->Ma);
        w->fext = w->text = w->K = w->uf = w->J = w->Ma = NULL;
        return DEM_FAIL(w, DEM_ERR_NOMEM, "coupling arrays for %zu particles", cap);
    }
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
    dem_status s = dem_room_for(w, n, "add_particles");
    if (s) return s;
    /* all or nothing: check every particle first */
    for (size_t i = 0; i < n; ++i) {
        char what[64];
        snprintf(what, sizeof what, "add_particles: p[%zu]", i);
        if ((s = dem_particle_check(w, &p[i], what))) return s;
        if (p[i].id < 0 && w->next_id > INT64_MAX - 1 - (int64_t)i)
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: no free particle id left", what);
    }
    s = dem_reserve(w, w->n + w->ng + n);
    if (s) return s;
    for (size_t i = 0; i < n; ++i) {
        s = dem_append_particle(w, &p[i]);
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
        dem_status s = dem_history_to_pending(w, (ptrdiff_t)index, "remove_particle");
        if (s) return s;
    }
    return dem_remove_booked(w, index, outlet);
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
    return DEM_OK;
}

/*--- diagnostics -----------------------------------------------------------------*/
dem_status dem_world_stats(const dem_world *w, dem_stats *s)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, s, "stats");
    memset(s, 0, sizeof *s);
    for (size_t i = 0; i < w->n; ++i) {
        const double *v = w->v + 3 * i, *om = w->w + 3 * i;
        double m = w->mass[i], I = 0.4 * m * w->rad[i] * w->rad[i];
        s->kinetic_energy += 0.5 * m * dem_dot(v, v);
        s->rotational_energy += 0.5 * I * dem_dot(om, om);
        for (int k = 0; k < 3; ++k) s->momentum[k] += m * v[k];
    }
    s->max_overlap_ratio = w->max_overlap;
    s->pair_contacts = w->pair_contacts;
    s->wall_contacts = w->wall_contacts;
    s->inserted = w->inserted;
    s->removed = w->removed;
    s->list_builds = w->nbuilds;
    return DEM_OK;
}

dem_status dem_world_particle_contacts(const dem_world *w, int *coord, double *force)
{
    if (!w) return DEM_ERR_ARG;
    if (w->n == 0) return DEM_OK;
    /* Both come from the last force evaluation, the coordination also from
       its neighbour list.  Before the first evaluation (or after a wall
       change) neither is known; after an insert, remove, restore or
       ghost exchange the list is gone and pairs can no longer be told.
       Say so instead of returning zeros. */
    if ((force || coord) && !w->forces_valid)
        return DEM_FAIL(w, DEM_ERR_STATE, "particle_contacts: no force evaluation since the start or the last "
                        "wall change (step %lld); take a step first", (long long)w->step);
    if (coord && !w->list_valid)
        return DEM_FAIL(w, DEM_ERR_STATE, "particle_contacts: coordination unknown, the neighbour list was "
                        "dropped after the last force evaluation (insert, remove, restore or ghost exchange; "
                        "step %lld); take a step first", (long long)w->step);
    if (force) memcpy(force, w->f, 3 * w->n * sizeof(double));
    if (coord) {
        memset(coord, 0, w->n * sizeof(int));
        for (size_t i = 0; i < w->nrows; ++i) {
            for (int k = w->nb_off[i]; k < w->nb_off[i + 1]; ++k) {
                size_t j = (size_t)w->nb_j[k];
                const double *sh = w->shift[w->nb_s[k]];
                double d[3], r2 = 0, s = w->rad[i] + w->rad[j];
                for (int c = 0; c < 3; ++c) { d[c] = w->x[3 * i + c] - w->x[3 * j + c] + sh[c]; r2 += d[c] * d[c]; }
                if (r2 < s * s) {
                    if (i < w->n) coord[i]++;
                    if (j < w->n) coord[j]++;
                }
            }
        }
    }
    return DEM_OK;
}

dem_status dem_world_memory(const dem_world *w, size_t *particle_bytes, size_t *list_bytes)
{
    if (!w) return DEM_ERR_ARG;
    /* id, x, v, w, f, t, radius, mass, density, material, x0 (float), list_index */
    size_t per = sizeof(int64_t) + 15 * sizeof(double) + 3 * sizeof(double) + sizeof(int) +
                 3 * sizeof(float) + sizeof(int);
    if (w->have_ext) per += 14 * sizeof(double);
    if (particle_bytes) *particle_bytes = w->cap * per;
    if (list_bytes)
        *list_bytes = w->capnb * (sizeof(int) + 1 + 3 * sizeof(double)) + w->caprows * sizeof(int) +
                      w->capwc * (2 * sizeof(int) + 3 * sizeof(double)) +
                      (w->wc_off ? (w->nrows + 1) * sizeof(int) : 0) + w->capscratch * DEM_SCRATCH_ENTRY +
                      w->capcrec * sizeof(dem_contact);
    return DEM_OK;
}

dem_status dem_world_phase_times(const dem_world *w, dem_phase_times *t)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED((dem_world *)w, t, "phase_times");
    t->integrate = w->prof[DEM_PROF_INTEGRATE];
    t->neighbour = w->prof[DEM_PROF_NEIGHBOUR];
    t->pairs = w->prof[DEM_PROF_PAIRS];
    t->walls = w->prof[DEM_PROF_WALLS];
#ifdef DEM_PROFILE
    return DEM_OK;
#else
    return DEM_FAIL((dem_world *)w, DEM_ERR_STATE, "phase_times: the core was built without -DDEM_PROFILE "
                    "(make -C src/dem EXTRA_CFLAGS=-DDEM_PROFILE)");
#endif
}

dem_status dem_world_record_contacts(dem_world *w, int on)
{
    if (!w) return DEM_ERR_ARG;
    if (on != 0 && on != 1)
        return DEM_FAIL(w, DEM_ERR_ARG, "record_contacts: on = %d; allowed 0 (off) or 1 (on)", on);
    w->crec_on = on;
    if (!on) {   /* the record goes with the recording */
        free(w->crec);
        w->crec = NULL; w->ncrec = w->capcrec = 0; w->crec_valid = 0;
    }
    return DEM_OK;
}

dem_status dem_world_contacts(const dem_world *w, dem_contact *out, size_t capacity, size_t *count)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, count, "contacts");
    *count = 0;
    if (!w->crec_valid)
        return DEM_FAIL(w, DEM_ERR_STATE, "contacts: the last force evaluation was not recorded (step %lld); call "
                        "dem_world_record_contacts(w, 1) and take a step first", (long long)w->step);
    /* as dem_world_particle_contacts: a wall change drops the forces, a
       particle change (insert, remove, restore, ghost exchange) the list */
    if (!w->forces_valid || !w->list_valid)
        return DEM_FAIL(w, DEM_ERR_STATE, "contacts: the particles or walls changed since the last force evaluation "
                        "(insert, remove, restore, ghost exchange or wall change; step %lld); take a step first",
                        (long long)w->step);
    *count = w->ncrec;
    if (!out) return DEM_OK;
    if (capacity < w->ncrec)
        return DEM_FAIL(w, DEM_ERR_RANGE, "contacts: capacity = %zu entries; the last force evaluation has %zu "
                        "contacts (*count is set; nothing written)", capacity, w->ncrec);
    if (w->ncrec) memcpy(out, w->crec, w->ncrec * sizeof *out);
    return DEM_OK;
}
