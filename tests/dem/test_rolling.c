/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* A sphere rolling on a plane under gravity with rolling friction
 * M_r = mu_r |f_n| decelerates at dv/dt = -(5/7) mu_r g / a (rolling
 * without slip, I = 2/5 m a^2: m dv/dt = F_t, I dw/dt = -a F_t - mu_r m g). */
#include "check.h"

int main(void)
{
    const double a = 1e-3, rho = 2500, E = 1e7, nu = 0.3, g = 9.81, mu_r = 2e-5, v0 = 0.1;
    const double dt = 2e-6;
    double gv[3] = {0, 0, -g};
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, dt, gv, 0.5);
    dem_material mat = test_material(E, nu, 0.5, mu_r, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, p0, nz, mid, NULL, NULL));
    double m = rho * 4.0 / 3.0 * M_PI * a * a * a, estar = E / (2 * (1 - nu * nu));
    double deq = pow(m * g / (4.0 / 3.0 * estar * sqrt(a)), 2.0 / 3.0);
    dem_particle p = test_particle(-0.1, 0, a - deq, v0, 0, 0, a, rho, mid);
    p.omega[1] = v0 / a;
    TRY(w, dem_world_add_particles(w, 1, &p));
    dem_arrays A;
    const double t1 = 0.02, t2 = 0.12;
    TRY(w, dem_world_step(w, (int64_t)(t1 / dt + 0.5)));
    TRY(w, dem_world_arrays(w, &A));
    double va = A.v[0], ta = dem_world_time(w);
    TRY(w, dem_world_step(w, (int64_t)((t2 - t1) / dt + 0.5)));
    TRY(w, dem_world_arrays(w, &A));
    double vb = A.v[0], tb = dem_world_time(w);
    check_rel("rolling friction deceleration [m/s2]", (va - vb) / (tb - ta), 5.0 / 7.0 * mu_r * g / a, 0.02);
    check_rel("rolling without slip a w / v", a * A.omega[1] / A.v[0], 1.0, 1e-3);
    dem_world_destroy(&w);
    return check_exit();
}
