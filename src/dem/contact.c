/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact forces: the pair loop of the selected law
  (laws/, one call per evaluation), the law's wall loop, and which
  triangle contacts of a particle count.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  Convention: contactKernel.h.  Each law brings its own loop over the pairs
  of the neighbour list and its wall loop (wallLoop.h), so neither the
  per-pair nor the per-wall-contact work has an indirect call.
\*---------------------------------------------------------------------------*/
#include "wallLoop.h"
#include <stdlib.h>
#include <string.h>

typedef struct { int k; int feature; int nv; int fv[3]; double d2, cp[3]; int acc; } mesh_cand;

int dem_wall_mesh_contacts(dem_world *w, size_t i, int k0, int k1, dem_mesh_contact out[DEM_WALL_MESH_MAX])
{
    const double *xi = w->x + 3 * i;
    const double ai = w->rad[i];
    mesh_cand mc[DEM_WALL_MESH_MAX];
    int nmc = 0;
    for (int k = k0; k < k1; ++k) {
        if (w->wc_tri[k] < 0) continue;
        const dem_mesh *m = &w->meshes[w->wall_index[w->wc_wall[k]]];
        int t = w->wc_tri[k];
        double Pv[3][3], cp[3];
        for (int v = 0; v < 3; ++v)
            for (int c = 0; c < 3; ++c)
                Pv[v][c] = m->v0[3 * (size_t)m->tri[3 * t + v] + c] + m->vel[c] * (w->time - m->t0);
        int feat = dem_closest_on_triangle(xi, Pv[0], Pv[1], Pv[2], cp);
        double d2 = 0;
        for (int c = 0; c < 3; ++c) d2 += (xi[c] - cp[c]) * (xi[c] - cp[c]);
        if (d2 >= ai * ai || nmc >= DEM_WALL_MESH_MAX) { continue; }
        mesh_cand *z = &mc[nmc++];
        z->k = k; z->feature = feat; z->d2 = d2; z->acc = 0;
        memcpy(z->cp, cp, sizeof cp);
        const int *tv = m->tri + 3 * t;
        static const int fv_of[7][3] = {{0, 1, 2}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0},
                                        {0, 1, 0}, {1, 2, 0}, {2, 0, 0}};
        z->nv = feat == 0 ? 3 : (feat <= 3 ? 1 : 2);
        for (int c = 0; c < z->nv; ++c) z->fv[c] = tv[fv_of[feat][c]];
    }
    /* mesh candidates that are not touching lose their history below */
    if (nmc) {
        /* accept in order of distance; an edge/vertex contact whose
           vertices all belong to an accepted triangle is the same contact */
        for (int a = 0; a < nmc; ++a) {
            int best = -1;
            for (int b = 0; b < nmc; ++b)
                if (!mc[b].acc && (best < 0 || mc[b].d2 < mc[best].d2 ||
                                   (mc[b].d2 == mc[best].d2 && mc[b].feature < mc[best].feature)))
                    best = b;
            mesh_cand *z = &mc[best];
            z->acc = 1;
            if (z->feature != 0) {
                int wz = w->wc_wall[z->k];
                for (int b = 0; b < nmc; ++b) {
                    if (b == best || mc[b].acc != 2 || w->wc_wall[mc[b].k] != wz) continue;
                    const dem_mesh *m = &w->meshes[w->wall_index[wz]];
                    const int *tv = m->tri + 3 * w->wc_tri[mc[b].k];
                    int all = 1;
                    for (int c = 0; c < z->nv && all; ++c)
                        all = z->fv[c] == tv[0] || z->fv[c] == tv[1] || z->fv[c] == tv[2];
                    if (all) { z->acc = 3; break; } /* rejected */
                }
            }
            if (z->acc == 1) z->acc = 2; /* accepted */
        }
        /* history hand-over: a new accepted contact takes the history of a
           rejected/ended candidate of the same mesh */
        for (int a = 0; a < nmc; ++a) {
            if (mc[a].acc != 2) continue;
            double *h = w->wc_h + 3 * (size_t)mc[a].k;
            if (h[0] != 0 || h[1] != 0 || h[2] != 0) continue;
            int wz = w->wc_wall[mc[a].k];
            for (int k = k0; k < k1; ++k) {
                if (w->wc_tri[k] < 0 || w->wc_wall[k] != wz || k == mc[a].k) continue;
                int isacc = 0;
                for (int b = 0; b < nmc; ++b) if (mc[b].k == k && mc[b].acc == 2) isacc = 1;
                if (isacc) continue;
                double *h2 = w->wc_h + 3 * (size_t)k;
                if (h2[0] != 0 || h2[1] != 0 || h2[2] != 0) {
                    memcpy(h, h2, 3 * sizeof(double));
                    h2[0] = h2[1] = h2[2] = 0.0;
                    break;
                }
            }
        }
    }
    /* the accepted ones in list order; the others' histories cleared */
    int nout = 0;
    for (int k = k0; k < k1; ++k) {
        if (w->wc_tri[k] < 0) continue;
        int a = -1;
        for (int b = 0; b < nmc; ++b) if (mc[b].k == k) { a = b; break; }
        if (a < 0 || mc[a].acc != 2) { double *h = w->wc_h + 3 * (size_t)k; h[0] = h[1] = h[2] = 0.0; continue; }
        dem_mesh_contact *o = &out[nout++];
        double d = sqrt(mc[a].d2);
        if (d > 0) for (int c = 0; c < 3; ++c) o->n[c] = (xi[c] - mc[a].cp[c]) / (d + (d > 0.0 ? 0.0 : 1.0));
        else {
            const dem_mesh *m = &w->meshes[w->wall_index[w->wc_wall[k]]];
            const double *tn = m->nrm + 3 * w->wc_tri[k];
            for (int c = 0; c < 3; ++c) o->n[c] = tn[c];
        }
        o->k = k;
        o->delta = ai - d;
    }
    return nout;
}

/* Room in the contact record for every list entry and wall candidate (an
 * upper bound of the contacts); 0 if recording is off or memory is short
 * (the evaluation then goes unrecorded and dem_world_contacts says so). */
static int record_ready(dem_world *w)
{
    if (!w->crec_on) return 0;
    size_t need = w->nnb + w->nwc;
    if (need > w->capcrec) {
        size_t cap = need + need / 4 + 16;
        dem_contact *c = realloc(w->crec, cap * sizeof *c);
        if (!c) {
            dem_log_(w, DEM_LOG_WARNING, "contact record: no memory for %zu contacts; step %lld not recorded",
                     cap, (long long)w->step);
            return 0;
        }
        w->crec = c; w->capcrec = cap;
    }
    return 1;
}

void dem_forces(dem_world *w, double hist_dt)
{
    DEM_PROF_START(t0);
    w->hdt = hist_dt;
    w->ncrec = 0;
    w->crec_now = record_ready(w);
    size_t np = w->n + w->ng;
    if (np) {
        memset(w->f, 0, 3 * np * sizeof(double));
        memset(w->t, 0, 3 * np * sizeof(double));
    }
    double movr = 0.0;
    size_t nct = 0;
    int per = w->cfg.periodic[0] || w->cfg.periodic[1] || w->cfg.periodic[2];
    const dem_law *law = dem_law_of(w);
    law->pair_forces(w, per, &movr, &nct);   /* the law's own loop over all pairs */
    w->pair_contacts = nct;
    w->max_overlap = movr;
    w->wall_contacts = 0;
    DEM_PROF_ADD(w, DEM_PROF_PAIRS, t0);
    DEM_PROF_START(t1);
    if (w->nwalls) law->wall_forces(w);      /* the law's wall loop (wallLoop.h) */
    DEM_PROF_ADD(w, DEM_PROF_WALLS, t1);
    w->forces_valid = 1;
    w->crec_valid = w->crec_now;
    w->crec_now = 0;
}
