/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Elastic frictionless gas in a fully periodic box (Hertz, e = 1, mu = 0):
 * total energy (kinetic + Hertz elastic (8/15) E* sqrt(R*) delta^(5/2))
 * drifts by less than 1e-6 relative over 1e5 steps; total momentum stays
 * zero to round-off. */
#include "check.h"

static double energy(dem_world *w, double L, double estar, double *P)
{
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    double ek = 0;
    P[0] = P[1] = P[2] = 0;
    for (size_t i = 0; i < A.n_owned; ++i) {
        const double *v = A.v + 3 * i;
        ek += 0.5 * A.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (int k = 0; k < 3; ++k) P[k] += A.mass[i] * v[k];
    }
    double ep = 0;
    for (size_t i = 0; i < A.n_owned; ++i)
        for (size_t j = i + 1; j < A.n_owned; ++j) {
            double r2 = 0;
            for (int k = 0; k < 3; ++k) {
                double d = A.x[3 * i + k] - A.x[3 * j + k];
                d -= L * nearbyint(d / L);
                r2 += d * d;
            }
            double s = A.radius[i] + A.radius[j];
            if (r2 < s * s) {
                double del = s - sqrt(r2), rs = A.radius[i] * A.radius[j] / s;
                ep += 8.0 / 15.0 * estar * sqrt(rs) * pow(del, 2.5);
            }
        }
    return ek + ep;
}

int main(void)
{
    const double a = 1e-3, rho = 2500, E = 1e7, nu = 0.3, L = 0.025, dt = 5e-7;
    const int nside = 7;
    const long nsteps = QUICK ? 10000 : 100000;
    dem_world *w = NULL;
    TRY(w, dem_world_create(&w));
    dem_config c;
    dem_config_default(&c);
    c.dt = dt;
    c.gravity[2] = 0;
    for (int k = 0; k < 3; ++k) { c.domain_lo[k] = 0; c.domain_hi[k] = L; c.periodic[k] = 1; }
    TRY(w, dem_world_configure(w, &c));
    dem_material mat = test_material(E, nu, 0.0, 0.0, 1.0);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    srand(7);
    int n = nside * nside * nside;
    dem_particle *p = calloc((size_t)n, sizeof *p);
    double vm[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        int ix = i % nside, iy = (i / nside) % nside, iz = i / (nside * nside);
        p[i] = test_particle((ix + 0.5) * L / nside, (iy + 0.5) * L / nside, (iz + 0.5) * L / nside,
                             2.0 * rand() / RAND_MAX - 1.0, 2.0 * rand() / RAND_MAX - 1.0,
                             2.0 * rand() / RAND_MAX - 1.0, a, rho, mid);
        for (int k = 0; k < 3; ++k) vm[k] += p[i].v[k] / n;
    }
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) p[i].v[k] -= vm[k];
    TRY(w, dem_world_add_particles(w, (size_t)n, p));
    free(p);
    double estar = E / (2 * (1 - nu * nu)), P0[3], P[3];
    double e0 = energy(w, L, estar, P0), drift = 0, pmax = 0;
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    double mv = 0;
    for (size_t i = 0; i < A.n_owned; ++i)
        mv += A.mass[i] * sqrt(A.v[3 * i] * A.v[3 * i] + A.v[3 * i + 1] * A.v[3 * i + 1] + A.v[3 * i + 2] * A.v[3 * i + 2]);
    for (int s = 0; s < 10; ++s) {
        TRY(w, dem_world_step(w, nsteps / 10));
        double e1 = energy(w, L, estar, P);
        drift = fmax(drift, fabs(e1 - e0) / e0);
        for (int k = 0; k < 3; ++k) pmax = fmax(pmax, fabs(P[k] - P0[k]) / mv);
    }
    dem_stats st;
    TRY(w, dem_world_stats(w, &st));
    char name[128];
    snprintf(name, sizeof name, "gas relative energy drift over %ld steps", nsteps);
    check_below(name, drift, 1e-6);
    check_below("gas momentum change / sum m|v|", pmax, 1e-12);
    int64_t cnt = dem_world_step_count(w);
    check_abs("gas step count", (double)cnt, (double)nsteps, 0.0);
    dem_world_destroy(&w);
    return check_exit();
}
