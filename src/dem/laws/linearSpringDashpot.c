/*---------------------------------------------------------------------------*\
  demFoam DEM core - contact law linearSpringDashpot: linear spring-dashpot
  with a Coulomb-limited tangential spring (Silbert et al., Phys. Rev. E
  2001, [S] eqs. 17-26, f = 1); docs/theory.md, "Contact laws".
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "springDashpot.h"

static void contact(const dem_pair *q, double dt, const double n[3], double delta, double d,
                    const double vc[3], double meff, double rstar, double *h,
                    double F[3], double ft[3], double *fel, double *fnout)
{
    (void)d; (void)rstar;
    sd_force(q, dt, n, delta, 1.0, vc, meff, h, F, ft, fel, fnout);
}

static double contact_time(const dem_time_pair *p, double v_imp, int rayleigh, int damped)
{
    (void)v_imp; (void)rayleigh; (void)damped;  /* the damped half period either way */
    return sd_linear_time(p);
}

static void pair_forces(dem_world *w, int periodic, double *max_overlap, size_t *contacts)
{
    dem_pair_loops(w, contact, periodic, max_overlap, contacts);
}

DEM_WALL_FORCES(wall_forces, contact)

const dem_law dem_law_linearSpringDashpot = {
    .name = "linearSpringDashpot",
    .stiffness_name = "stiffness_n",
    .stiffness = sd_stiffness,
    .derived = sd_derived,
    .pair = sd_pair,
    .contact_time = contact_time,
    .pair_forces = pair_forces,
    .wall_forces = wall_forces,
};
