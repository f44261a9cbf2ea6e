/*---------------------------------------------------------------------------*\
  demFoam DEM core - setup comparison: whether two worlds have the same
  contact law, materials, pair overrides, walls, inlets and outlets (e.g.
  the input of a continued run against the state it restores).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <stdio.h>

/* first differing member of two materials, NULL if none (exact compare:
   both sides come from the same text through the same conversions) */
static const char *material_diff(const dem_material *a, const dem_material *b,
                                 double *va, double *vb)
{
#define DEM_CMP(f, name) if (a->f != b->f) { *va = a->f; *vb = b->f; return name; }
    DEM_CMP(youngs_modulus, "youngsModulus")
    DEM_CMP(poisson_ratio, "poissonRatio")
    DEM_CMP(stiffness_n, "stiffnessN")
    DEM_CMP(stiffness_t, "stiffnessT")
    DEM_CMP(friction, "friction")
    DEM_CMP(rolling_friction, "rollingFriction")
    DEM_CMP(restitution, "restitution")
    DEM_CMP(damping, "damping")
#undef DEM_CMP
    return NULL;
}

static int wall_material(const dem_world *w, int wall)
{
    const int i = w->wall_index[wall];
    return w->wall_kind[wall] ? w->meshes[i].material : w->planes[i].material;
}

int dem_world_setup_diff(const dem_world *a, const dem_world *b, char *what, size_t n)
{
    char dummy[1];
    if (!what || n == 0) { what = dummy; n = sizeof dummy; }
    what[0] = '\0';
    if (!a || !b) { snprintf(what, n, "no world"); return 1; }
    const dem_config *ca = &a->cfg, *cb = &b->cfg;
    if (ca->contact_law != cb->contact_law) {
        snprintf(what, n, "contactLaw: %s, the state's %s", dem_contact_law_name(ca->contact_law),
                 dem_contact_law_name(cb->contact_law));
        return 1;
    }
    if (!ca->damping_predicted != !cb->damping_predicted) {
        snprintf(what, n, "dampingPredicted: %s, the state's %s", ca->damping_predicted ? "yes" : "no",
                 cb->damping_predicted ? "yes" : "no");
        return 1;
    }
    for (int k = 0; k < 3; ++k)
        if (!ca->periodic[k] != !cb->periodic[k] ||
            (ca->periodic[k] && (ca->domain_lo[k] != cb->domain_lo[k] || ca->domain_hi[k] != cb->domain_hi[k]))) {
            snprintf(what, n, "the periodic box along axis %d: [%g, %g]%s, the state's [%g, %g]%s", k,
                     ca->domain_lo[k], ca->domain_hi[k], ca->periodic[k] ? "" : " (not periodic)",
                     cb->domain_lo[k], cb->domain_hi[k], cb->periodic[k] ? "" : " (not periodic)");
            return 1;
        }
    if (a->nmat != b->nmat) {
        snprintf(what, n, "%d materials, the state %d", a->nmat, b->nmat);
        return 1;
    }
    double va = 0, vb = 0;
    for (int i = 0; i < a->nmat; ++i) {
        const char *f = material_diff(&a->mat[i], &b->mat[i], &va, &vb);
        if (f) { snprintf(what, n, "material %d: %s %g, the state's %g", i, f, va, vb); return 1; }
    }
    if (a->novr != b->novr) {
        snprintf(what, n, "%d material pairs, the state %d", a->novr, b->novr);
        return 1;
    }
    for (int i = 0; i < a->novr; ++i) {
        const dem_pair_override *p = &a->ovr[i], *q = &b->ovr[i];
        if (p->a != q->a || p->b != q->b) {
            snprintf(what, n, "material pair %d: materials (%d, %d), the state's (%d, %d)", i, p->a, p->b,
                     q->a, q->b);
            return 1;
        }
        const char *f = material_diff(&p->m, &q->m, &va, &vb);
        if (f) {
            snprintf(what, n, "material pair %d (materials %d, %d): %s %g, the state's %g", i, p->a, p->b, f,
                     va, vb);
            return 1;
        }
    }
    if (a->nwalls != b->nwalls || a->nplanes != b->nplanes) {
        snprintf(what, n, "%d walls (%d planes), the state %d (%d planes)", a->nwalls, a->nplanes, b->nwalls,
                 b->nplanes);
        return 1;
    }
    for (int i = 0; i < a->nwalls; ++i) {
        if (a->wall_kind[i] != b->wall_kind[i]) {
            snprintf(what, n, "wall %d: a %s, the state's a %s", i, a->wall_kind[i] ? "mesh" : "plane",
                     b->wall_kind[i] ? "mesh" : "plane");
            return 1;
        }
        if (wall_material(a, i) != wall_material(b, i)) {
            snprintf(what, n, "wall %d: material %d, the state's %d", i, wall_material(a, i),
                     wall_material(b, i));
            return 1;
        }
        if (a->wall_kind[i] && a->meshes[a->wall_index[i]].ntri != b->meshes[b->wall_index[i]].ntri) {
            snprintf(what, n, "wall %d: %zu triangles, the state's %zu", i, a->meshes[a->wall_index[i]].ntri,
                     b->meshes[b->wall_index[i]].ntri);
            return 1;
        }
    }
    if (a->ninlets != b->ninlets || a->noutlets != b->noutlets) {
        snprintf(what, n, "%d inlets and %d outlets, the state %d and %d", a->ninlets, a->noutlets, b->ninlets,
                 b->noutlets);
        return 1;
    }
    return 0;
}
