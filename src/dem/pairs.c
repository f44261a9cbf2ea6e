/*---------------------------------------------------------------------------*\
  demFoam DEM core - the pair table: constants of every material pair,
  computed once per change of materials (combination rules of dem.h; the
  law's own constants from its table entry, laws/).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "law.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Combined parameters of one material pair (combination rules of dem.h). */
static void pair_compute(int law, int pred, const dem_material *a, double ea, double ca,
                         const dem_material *b, double eb, double cb, int like, dem_pair *q)
{
    memset(q, 0, sizeof *q);
    /* a rigid body does not deform: the other one's elasticity alone */
    int ra = dem_material_rigid(a, law), rb = dem_material_rigid(b, law);
    q->mu = fmin(a->friction, b->friction);
    q->mu_r = fmin(a->rolling_friction, b->rolling_friction);
    q->nu = ra && !rb ? b->poisson_ratio : rb && !ra ? a->poisson_ratio : 0.5 * (a->poisson_ratio + b->poisson_ratio);
    /* two rigid bodies never touch (walls only): no elastic constants */
    if (ra && rb) return;
    q->mindlin = (2.0 - q->nu) / (2.0 * (1.0 - q->nu));
    q->pred = pred ? 1.0 : 0.0;
    dem_laws[law]->pair(q, a, ea, ca, b, eb, cb, like, ra, rb);
}

dem_status dem_pairs_update(dem_world *w)
{
    if (!w->pairs_dirty) return DEM_OK;
    int nm = w->nmat;
    dem_pair *p = realloc(w->pair, (nm > 0 ? (size_t)nm * (size_t)nm : 1) * sizeof *p);
    if (!p) return DEM_FAIL(w, DEM_ERR_NOMEM, "pair table %d x %d", nm, nm);
    w->pair = p;
    if (nm == 0) memset(p, 0, sizeof *p); /* the kernels read entry 0 */
    int law = w->cfg.contact_law;
    const dem_law *L = dem_laws[law];
    for (int i = 0; i < nm; ++i) {
        const dem_material *a = &w->mat[i];
        if (!(L->stiffness(a) > 0))
            return DEM_FAIL(w, DEM_ERR_RANGE, "material %d: %s = %g; allowed > 0 (law %s)",
                            i, L->stiffness_name, L->stiffness(a), L->name);
    }
    if (w->derived_law != (int)law) w->nmat_derived = 0;
    if (w->nmat_derived < nm) {
        double *e = realloc(w->mat_e, (size_t)nm * sizeof(double));
        if (e) w->mat_e = e;
        double *c = realloc(w->mat_c, (size_t)nm * sizeof(double));
        if (c) w->mat_c = c;
        if (!e || !c) return DEM_FAIL(w, DEM_ERR_NOMEM, "material cache %d", nm);
        for (int i = w->nmat_derived; i < nm; ++i) L->derived(&w->mat[i], &w->mat_e[i], &w->mat_c[i]);
        w->nmat_derived = nm;
        w->derived_law = law;
    }
    for (int i = 0; i < nm; ++i)
        for (int j = 0; j < nm; ++j)
            pair_compute(law, w->cfg.damping_predicted, &w->mat[i], w->mat_e[i], w->mat_c[i], &w->mat[j], w->mat_e[j], w->mat_c[j],
                         i == j, &p[(size_t)i * (size_t)nm + (size_t)j]);
    for (int k = 0; k < w->novr; ++k) {
        const dem_pair_override *o = &w->ovr[k];
        if (o->a >= nm || o->b >= nm) continue;
        double e, c;
        L->derived(&o->m, &e, &c);
        pair_compute(law, w->cfg.damping_predicted, &o->m, e, c, &o->m, e, c, 1, &p[(size_t)o->a * (size_t)nm + (size_t)o->b]);
        p[(size_t)o->b * (size_t)nm + (size_t)o->a] = p[(size_t)o->a * (size_t)nm + (size_t)o->b];
    }
    w->pairs_dirty = 0;
    return DEM_OK;
}
