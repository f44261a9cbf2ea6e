/*---------------------------------------------------------------------------*\
  demFoam DEM core - world handle: creation, configuration, destruction, clock.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>
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
    for (int k = 0; k < DEM_N_TAGS; ++k) free(w->tag[k]);
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
    free(w->shadow);
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

dem_status dem_world_get_config(const dem_world *w, dem_config *c)
{
    if (!w || !c) return DEM_ERR_ARG;
    *c = w->cfg;
    return DEM_OK;
}

dem_status dem_world_configure_run(dem_world *w, const dem_config *c)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, c, "configure_run");
    /* the fixed settings taken from the world, the changeable ones from c */
    dem_config m = w->cfg;
    m.dt = c->dt;
    memcpy(m.gravity, c->gravity, sizeof m.gravity);
    m.max_dt_fraction = c->max_dt_fraction;
    m.max_overlap_ratio = c->max_overlap_ratio;
    m.spatial_sort = c->spatial_sort;
    m.impact_speed = c->impact_speed;
    return dem_world_configure(w, &m);
}

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
