/*---------------------------------------------------------------------------*\
  demFoam DEM core - diagnostics: energies and counters, per-particle contact
  numbers and forces, memory, phase timers, the per-contact record.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <string.h>
#include <stdlib.h>

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
    if (w->have_ext) per += 14 * sizeof(double) + DEM_N_TAGS * sizeof(int64_t);
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
