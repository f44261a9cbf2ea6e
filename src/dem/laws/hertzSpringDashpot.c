/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact law hertzSpringDashpot: the spring-dashpot of
  Silbert et al. (Phys. Rev. E 2001, [S] eqs. 17-26) with the Hertzian
  scale f = sqrt(delta/d); docs/theory.md, "Contact laws".
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "springDashpot.h"

static void contact(const dem_pair *q, double dt, const double n[3], double delta, double d,
                    const double vc[3], double meff, double rstar, double *h,
                    double F[3], double ft[3], double *fel, double *fnout)
{
    (void)rstar;
    sd_force(q, dt, n, delta, sqrt(delta / d), vc, meff, h, F, ft, fel, fnout);
}

/* with an impact speed: Hertz's duration, since k_n delta^(3/2)/sqrt(d)
 * acts as Hertz with (4/3) E* sqrt(R*) = k_n / sqrt(d); else the linear period */
static double contact_time(const dem_time_pair *p, double v_imp, int rayleigh, int damped)
{
    (void)rayleigh; (void)damped;  /* damping not included: Hertz's elastic duration */
    if (!(v_imp > 0)) return sd_linear_time(p);
    double d = 2.0 * p->rstar * (p->wall ? 1.0 : 2.0);
    double es = 0.75 * p->q->kn / sqrt(d * p->rstar);
    return dem_hertz_time(p->meff, p->rstar, es, v_imp);
}

static void pair_forces(dem_world *w, int periodic, double *max_overlap, size_t *contacts)
{
    dem_pair_loops(w, contact, periodic, max_overlap, contacts);
}

DEM_WALL_FORCES(wall_forces, contact)

const dem_law dem_law_hertzSpringDashpot = {
    .name = "hertzSpringDashpot",
    .stiffness_name = "stiffness_n",
    .stiffness = sd_stiffness,
    .derived = sd_derived,
    .pair = sd_pair,
    .contact_time = contact_time,
    .pair_forces = pair_forces,
    .wall_forces = wall_forces,
};
