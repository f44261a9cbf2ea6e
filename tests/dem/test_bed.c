/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* A poured bed: 2000 spheres (d = 2 mm, E = 1e7 Pa, mu = 0.3, e = 0.5)
 * placed at random by fill_box in a tall region, falling under gravity
 * onto a floor, periodic sideways.  After settling, the packing fraction
 * in the interior (2 d away from the floor and the free surface; exact
 * sphere-slab volumes) lies in 0.58-0.64 (random loose to random close
 * packing of frictional spheres) and the largest overlap is below 1 % of d. */
#include "check.h"

static double slab_volume(double zc, double a, double z1, double z2)
{
    double lo = fmax(z1, zc - a), hi = fmin(z2, zc + a);
    if (hi <= lo) return 0.0;
    /* pi * int (a^2 - (z - zc)^2) dz */
    double u1 = lo - zc, u2 = hi - zc;
    return M_PI * (a * a * (u2 - u1) - (u2 * u2 * u2 - u1 * u1 * u1) / 3.0);
}

int main(void)
{
    const double d = 2e-3, a = 0.5 * d, rho = 2500;
    const size_t n = QUICK ? 600 : 2000;
    const double L = QUICK ? 8 * d : 12 * d;
    const double dt = 1.5e-5; /* < 0.2 x Rayleigh time 8.7e-5 s */
    dem_world *w = NULL;
    TRY(w, dem_world_create(&w));
    dem_config c;
    dem_config_default(&c);
    c.dt = dt;
    c.domain_lo[0] = c.domain_lo[1] = 0; c.domain_hi[0] = c.domain_hi[1] = L;
    c.periodic[0] = c.periodic[1] = 1;
    c.domain_lo[2] = 0; c.domain_hi[2] = 0.1;
    c.seed = 2024;
    TRY(w, dem_world_configure(w, &c));
    dem_material m = test_material(1e7, 0.3, 0.3, 0.0, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, p0, nz, mid, NULL, NULL));
    dem_particle_template t;
    memset(&t, 0, sizeof t);
    t.diameter.kind = DEM_DIST_FIXED; t.diameter.a = d;
    t.density.kind = DEM_DIST_FIXED; t.density.a = rho;
    t.material = mid;
    double lo[3] = {0, 0, a}, hi[3] = {L, L, 0.06};
    size_t got = 0;
    TRY(w, dem_world_fill_box(w, lo, hi, NULL, NULL, n, &t, &got));
    check_abs("bed fill_box inserted", (double)got, (double)n, 0.0);
    const double T = 0.4;
    TRY(w, dem_world_step(w, (int64_t)(T / dt)));
    dem_stats st;
    TRY(w, dem_world_stats(w, &st));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    double ztop = 0;
    for (size_t i = 0; i < A.n_owned; ++i) ztop = fmax(ztop, A.x[3 * i + 2] + A.radius[i]);
    double z1 = 2 * d, z2 = ztop - 2 * d, vs = 0;
    for (size_t i = 0; i < A.n_owned; ++i) vs += slab_volume(A.x[3 * i + 2], A.radius[i], z1, z2);
    double phi = vs / (L * L * (z2 - z1));
    double m1 = rho * M_PI / 6 * d * d * d;
    char name[128];
    snprintf(name, sizeof name, "bed of %zu: packing fraction (interior slab)", n);
    check_range(name, phi, 0.58, 0.64);
    snprintf(name, sizeof name, "bed of %zu: max overlap / d", n);
    check_below(name, st.max_overlap_ratio, 0.01);
    snprintf(name, sizeof name, "bed of %zu: settled (kinetic energy / (N m g d))", n);
    check_below(name, st.kinetic_energy / ((double)n * m1 * 9.81 * d), 1e-3);
    int *coord = malloc(n * sizeof(int));
    TRY(w, dem_world_particle_contacts(w, coord, NULL));
    double zsum = 0;
    for (size_t i = 0; i < n; ++i) zsum += coord[i];
    free(coord);
    snprintf(name, sizeof name, "bed of %zu: mean coordination (frictional, settled)", n);
    check_range(name, zsum / n, 4.0, 7.0);
    dem_world_destroy(&w);
    return check_exit();
}
