/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Hertz elastic normal impact (no damping, no friction, no gravity):
 * peak force, peak overlap and contact duration against Hertz theory
 * (Johnson, Contact Mechanics, 1985, sec. 11.4):
 *   delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5)
 *   F_max     = (4/3) E* sqrt(R*) delta_max^(3/2)
 *   t_c       = 2 (2/5) B(2/5, 1/2) delta_max / v  (= 2.9432 delta_max / v)     */
#include "check.h"

static void run(int wall)
{
    const double a = 1e-3, rho = 2500, E = 1e7, nu = 0.3, v0 = 1.0;
    const double m = rho * 4.0 / 3.0 * M_PI * a * a * a;
    const double estar = E / (2.0 * (1.0 - nu * nu));
    const double ms = wall ? m : 0.5 * m, rs = wall ? a : 0.5 * a;
    const double dmax = pow(15.0 * ms * v0 * v0 / (16.0 * estar * sqrt(rs)), 0.4);
    const double fmax = 4.0 / 3.0 * estar * sqrt(rs) * pow(dmax, 1.5);
    const double tc = 2.0 * 0.4 * tgamma(0.4) * tgamma(0.5) / tgamma(0.9) * dmax / v0;
    const double dt = tc / 4000.0;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, dt, NULL, 0.02);
    dem_material mat = test_material(E, nu, 0.0, 0.0, 1.0);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    const double gap = 0.25 * v0 * tc;
    if (wall) {
        double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
        TRY(w, dem_world_add_plane(w, p0, nz, mid, NULL, NULL));
        dem_particle p = test_particle(0, 0, a + gap, 0, 0, -v0, a, rho, mid);
        TRY(w, dem_world_add_particles(w, 1, &p));
    } else {
        dem_particle p[2] = {test_particle(-a - 0.5 * gap, 0, 0, 0.5 * v0, 0, 0, a, rho, mid),
                             test_particle(a + 0.5 * gap, 0, 0, -0.5 * v0, 0, 0, a, rho, mid)};
        TRY(w, dem_world_add_particles(w, 2, p));
    }
    double pk_d = 0, pk_f = 0, fc[6];
    long in_contact = 0, nsteps = (long)(3.0 * tc / dt);
    dem_arrays A;
    for (long s = 0; s < nsteps; ++s) {
        TRY(w, dem_world_step(w, 1));
        TRY(w, dem_world_arrays(w, &A));
        double d;
        if (wall) d = a - A.x[2];
        else {
            double dx = A.x[3] - A.x[0], dy = A.x[4] - A.x[1], dz = A.x[5] - A.x[2];
            d = 2 * a - sqrt(dx * dx + dy * dy + dz * dz);
        }
        TRY(w, dem_world_particle_contacts(w, NULL, fc));
        double f = sqrt(fc[0] * fc[0] + fc[1] * fc[1] + fc[2] * fc[2]);
        if (d > pk_d) pk_d = d;
        if (f > pk_f) pk_f = f;
        if (f > 0) in_contact++;
    }
    char name[128];
    snprintf(name, sizeof name, "hertz %s peak overlap [m]", wall ? "sphere-wall" : "sphere-sphere");
    check_rel(name, pk_d, dmax, 0.01);
    snprintf(name, sizeof name, "hertz %s peak force [N]", wall ? "sphere-wall" : "sphere-sphere");
    check_rel(name, pk_f, fmax, 0.01);
    snprintf(name, sizeof name, "hertz %s contact duration [s]", wall ? "sphere-wall" : "sphere-sphere");
    check_rel(name, in_contact * dt, tc, 0.01);
    double tcw;
    TRY(w, dem_world_contact_time(w, v0, &tcw));
    if (!wall) check_rel("hertz contact_time() at impact speed [s]", tcw, tc, 1e-9);
    dem_world_destroy(&w);
}

int main(void)
{
    run(0);
    run(1);
    return check_exit();
}
