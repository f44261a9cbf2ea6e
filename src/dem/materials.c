/*---------------------------------------------------------------------------*\
  demFoam DEM core - materials: adding them, pair overrides, their checks
  and the values derived under the contact law.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "law.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

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
