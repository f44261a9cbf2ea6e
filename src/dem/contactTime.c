/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact-time estimate: the shortest contact over the
  material pairs present, each from its law (laws/).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "law.h"
#include <math.h>

/* Smallest contact time over material pairs present.  v_imp <= 0 with a
 * Hertz law: Rayleigh time only. */
dem_status dem_contact_time_internal(const dem_world *w, double v_imp, int rayleigh, int damped, double *tc)
{
    *tc = INFINITY;
    int nm = w->nmat;
    const dem_law *L = dem_law_of(w);
    if (nm == 0 || w->n + w->ng == 0) return DEM_OK;
    double rmin[64], mmin[64], rhomax[64];
    int present[64];
    if (nm > 64) nm = 64; /* contact-time estimate over the first 64 materials */
    for (int m = 0; m < nm; ++m) { rmin[m] = INFINITY; mmin[m] = INFINITY; rhomax[m] = 0; present[m] = 0; }
    for (size_t i = 0; i < w->n + w->ng; ++i) {
        int m = w->mat_of[i];
        if (m >= nm) continue;
        present[m] = 1;
        if (w->rad[i] < rmin[m]) rmin[m] = w->rad[i];
        if (w->mass[i] < mmin[m]) mmin[m] = w->mass[i];
        if (w->rho[i] > rhomax[m]) rhomax[m] = w->rho[i];
    }
    int wallmat[64] = {0};
    for (int k = 0; k < w->nplanes; ++k) if (w->planes[k].material < nm) wallmat[w->planes[k].material] = 1;
    for (int k = 0; k < w->nmeshes; ++k) if (w->meshes[k].material < nm) wallmat[w->meshes[k].material] = 1;
    for (int a = 0; a < nm; ++a) {
        if (!present[a]) continue;
        for (int b = 0; b < nm; ++b) {
            if (!present[b] && !wallmat[b]) continue;
            const dem_pair *q = &w->pair[a * w->nmat + b];
            /* particle-particle (smallest of each) and particle-wall */
            double meff_pp = present[b] ? mmin[a] * mmin[b] / (mmin[a] + mmin[b]) : INFINITY;
            double rs_pp = present[b] ? rmin[a] * rmin[b] / (rmin[a] + rmin[b]) : INFINITY;
            for (int wall = 0; wall < 2; ++wall) {
                double meff = wall ? mmin[a] : meff_pp, rs = wall ? rmin[a] : rs_pp;
                if (wall && !wallmat[b]) continue;
                if (!isfinite(meff)) continue;
                const dem_time_pair tp = {q, &w->mat[a], meff, rs, rmin[a], rhomax[a], wall};
                double t = L->contact_time(&tp, v_imp, rayleigh, damped);
                if (t < *tc) *tc = t;
            }
        }
    }
    return DEM_OK;
}

dem_status dem_world_contact_time(const dem_world *wc, double impact_speed, double *t_contact)
{
    if (!wc) return DEM_ERR_ARG;
    DEM_NEED(wc, t_contact, "contact_time");
    dem_world *w = (dem_world *)wc; /* pair table is a cache */
    dem_status s = dem_pairs_update(w);
    if (s) return s;
    return dem_contact_time_internal(w, impact_speed, 0, 0, t_contact);
}

dem_status dem_world_contact_time_damped(const dem_world *wc, double impact_speed, double *t_contact)
{
    if (!wc) return DEM_ERR_ARG;
    DEM_NEED(wc, t_contact, "contact_time_damped");
    dem_world *w = (dem_world *)wc; /* pair table is a cache */
    dem_status s = dem_pairs_update(w);
    if (s) return s;
    return dem_contact_time_internal(w, impact_speed, 0, 1, t_contact);
}
