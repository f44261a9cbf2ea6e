/*---------------------------------------------------------------------------*\
  demFoam DEM core - what a contact law is: one table entry (name, material
  checks, pair constants, contact time, kernels) defined in its own file
  under laws/ and registered once in laws.c (docs/demCore.md, "Adding a
  contact law").
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#ifndef DEM_LAW_H
#define DEM_LAW_H
#include "dem_private.h"

/* One contact, force on i (convention of contactKernel.h): n unit normal,
 * delta overlap, d = a_i + a_j (pair) or 2 a_i (wall), vc contact-point
 * velocity, meff and rstar the effective mass and radius, h the tangential
 * history (updated); F total force = *fn n + ft (computed as fn * n[k] +
 * ft[k]), ft tangential force, *fel elastic normal force (rolling friction
 * uses it), *fn the normal force along n (contact record). */
typedef void (*dem_contact_fn)(const dem_pair *q, double dt, const double n[3], double delta, double d,
                               const double vc[3], double meff, double rstar, double *h,
                               double F[3], double ft[3], double *fel, double *fn);

/* What the contact-time estimate knows of one pair (contactTime.c). */
typedef struct {
    const dem_pair *q;          /* pair constants */
    const dem_material *a;      /* the particle's material */
    double meff, rstar;         /* smallest particles of the two materials (wall: the particle's) */
    double rmin, rhomax;        /* smallest radius, largest density of material a */
    int wall;                   /* 1: particle-wall */
} dem_time_pair;

typedef struct {
    const char *name;           /* contactLaw keyword and dem_contact_law_name() */
    const char *stiffness_name; /* the material field the law needs > 0 ("youngs_modulus") */
    double (*stiffness)(const dem_material *m);           /* that field; +inf: DEM_RIGID */
    /* restitution <-> damping of a material under this law (e < 0: not known
       without the pair, e.g. a damping in N s/m) */
    void (*derived)(const dem_material *m, double *e, double *c);
    /* the law's constants of a pair; mu, mu_r, nu and mindlin are set
       already; ra/rb: a/b rigid (not both); like: a and b the same material */
    void (*pair)(dem_pair *q, const dem_material *a, double ea, double ca, const dem_material *b,
                 double eb, double cb, int like, int ra, int rb);
    /* contact duration of a pair at impact speed v_imp (<= 0: none given);
       rayleigh: also bound by the Rayleigh time where the law has one;
       damped: the duration with the pair's damping where the law knows it */
    double (*contact_time)(const dem_time_pair *p, double v_imp, int rayleigh, int damped);
    /* all pairs of the neighbour list (one call per force evaluation); when
       w->crec_now, also appends each touching pair to w->crec (the same arithmetic) */
    void (*pair_forces)(dem_world *w, int periodic, double *max_overlap, size_t *contacts);
    /* all wall contacts (one call per force evaluation): DEM_WALL_FORCES
       of wallLoop.h with the law's one-contact kernel */
    void (*wall_forces)(dem_world *w);
} dem_law;

/* The registry (laws.c), indexed by dem_contact_law. */
extern const dem_law *const dem_laws[DEM_CONTACT_LAW_COUNT];
static inline const dem_law *dem_law_of(const dem_world *w) { return dem_laws[w->cfg.contact_law]; }

/* The laws (laws/) */
extern const dem_law dem_law_hertzMindlin;
extern const dem_law dem_law_linearSpringDashpot;
extern const dem_law dem_law_hertzSpringDashpot;
extern const dem_law dem_law_hertzMindlinNoSlip;

/* The Hertz normal part shared by hertzMindlin and hertzMindlinNoSlip
 * (laws/hertzMindlin.c): stiffness E, the e <-> c_n mapping, and the pair's
 * E*, e, c_n = c_t, k43 and cn8. */
double dem_hm_stiffness(const dem_material *m);
void dem_hm_derived(const dem_material *m, double *e, double *c);
void dem_hm_pair_normal(dem_pair *q, const dem_material *a, double ea, double ca,
                        const dem_material *b, double eb, double cb);

#endif
