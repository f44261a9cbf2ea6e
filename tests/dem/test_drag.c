/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Semi-implicit drag: with K, u fixed and no other force each half kick
 * solves m (v' - v)/h = K (u - v'), so after n steps
 *   v - u = (v0 - u) / (1 + h K/m)^(2n),  h = dt/2
 * (-> exp(-K t/m) as dt -> 0), stable for any K dt/m, and drag_impulse
 * equals the momentum change m (v - v0) to round-off. */
#include "check.h"

int main(void)
{
    const double a = 1e-3, rho = 2500, dt = 1e-5;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, dt, NULL, 0.5);
    dem_material mat = test_material(1e7, 0.3, 0.3, 0.0, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    dem_particle p[2] = {test_particle(0, 0, 0, 1.0, 0, 0, a, rho, mid),
                         test_particle(0.1, 0, 0, 1.0, 0, 0, a, rho, mid)};
    TRY(w, dem_world_add_particles(w, 2, p));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    double m = A.mass[0];
    A.drag_coeff[0] = 0.01 * m / dt;   /* K dt / m = 0.01 */
    A.drag_coeff[1] = 100.0 * m / dt;  /* stiff: K dt / m = 100 */
    A.fluid_velocity[0] = 0.2;
    A.fluid_velocity[3] = 0.2;
    const int n = 300;
    TRY(w, dem_world_step(w, n));
    TRY(w, dem_world_arrays(w, &A));
    for (int i = 0; i < 2; ++i) {
        double K = A.drag_coeff[i], h = 0.5 * dt;
        double expect = 0.2 + 0.8 / pow(1.0 + h * K / m, 2.0 * n);
        char name[128];
        snprintf(name, sizeof name, "drag K dt/m = %g: velocity", K * dt / m);
        check_rel(name, A.v[3 * i], expect, 1e-12);
        snprintf(name, sizeof name, "drag K dt/m = %g: impulse = m dv", K * dt / m);
        check_rel(name, A.drag_impulse[3 * i], m * (A.v[3 * i] - 1.0), 1e-12);
    }
    check_rel("drag K dt/m = 0.01 vs exp(-K t/m) (first order in K dt/m)", A.v[0], 0.2 + 0.8 * exp(-0.01 * n), 2e-3);
    dem_world_destroy(&w);
    return check_exit();
}
