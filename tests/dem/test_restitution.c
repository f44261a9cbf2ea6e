/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Requested restitution reproduced by Hertz-Mindlin (c_n from the exact
 * dimensionless-ODE mapping) and by the linear spring-dashpot
 * (e = exp(-gamma t_c / 2) of [S]), sphere-sphere and sphere-wall, 1 %. */
#include "check.h"

static double impact(dem_contact_law law, double e, int wall, double v0)
{
    const double a = 1e-3, rho = 2500;
    dem_material mat = test_material(1e7, 0.3, 0.0, 0.0, e);
    mat.stiffness_n = 1000.0;
    double m = rho * 4.0 / 3.0 * M_PI * a * a * a;
    double tc = law == DEM_CONTACT_HERTZ_MINDLIN ? 2.5e-4 : M_PI * sqrt(0.5 * m / 1000.0);
    double dt = tc / 2000.0;
    dem_world *w = test_world(law, dt, NULL, 0.02);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    double gap = 0.1 * v0 * tc;
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
    TRY(w, dem_world_step(w, (int64_t)(3.0 * tc / dt)));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    double vr = wall ? A.v[2] : A.v[3] - A.v[0];
    dem_world_destroy(&w);
    return vr / v0;
}

int main(void)
{
    const double es[3] = {0.1, 0.5, 0.9};
    char name[160];
    for (int k = 0; k < 3; ++k) {
        for (int wall = 0; wall < 2; ++wall) {
            snprintf(name, sizeof name, "restitution hertzMindlin %s e=%.1f (v=1 m/s)",
                     wall ? "sphere-wall" : "sphere-sphere", es[k]);
            check_rel(name, impact(DEM_CONTACT_HERTZ_MINDLIN, es[k], wall, 1.0), es[k], 0.01);
            snprintf(name, sizeof name, "restitution linearSpringDashpot %s e=%.1f",
                     wall ? "sphere-wall" : "sphere-sphere", es[k]);
            check_rel(name, impact(DEM_CONTACT_LINEAR_SPRING_DASHPOT, es[k], wall, 1.0), es[k], 0.01);
        }
        /* Hertz-Mindlin restitution does not depend on the impact speed */
        snprintf(name, sizeof name, "restitution hertzMindlin sphere-wall e=%.1f (v=0.1 m/s)", es[k]);
        check_rel(name, impact(DEM_CONTACT_HERTZ_MINDLIN, es[k], 1, 0.1), es[k], 0.01);
    }
    /* pair override (dem_world_set_pair): particle-wall pair with its own
       stiffness and restitution, linear law: rebound e and contact time
       t_c = pi (k/m - gamma^2/4)^(-1/2) of the override, not of the materials */
    {
        const double a = 1e-3, rho = 2500, kw = 1200.0, ew = 0.9;
        const double m = rho * 4.0 / 3.0 * M_PI * a * a * a;
        const double L = -log(ew), gam = 2.0 * L * sqrt(kw / m) / sqrt(M_PI * M_PI + L * L);
        const double tc = M_PI / sqrt(kw / m - 0.25 * gam * gam), dt = tc / 2000.0;
        dem_world *w = test_world(DEM_CONTACT_LINEAR_SPRING_DASHPOT, dt, NULL, 0.02);
        dem_material pm = test_material(1e7, 0.3, 0.0, 0.0, 0.5), wmat = pm;
        pm.stiffness_n = 800.0;
        wmat.stiffness_n = 800.0;
        int ip, iw;
        TRY(w, dem_world_add_material(w, &pm, &ip));
        TRY(w, dem_world_add_material(w, &wmat, &iw));
        dem_material pair = pm;
        pair.stiffness_n = kw;
        pair.restitution = ew;
        TRY(w, dem_world_set_pair(w, iw, ip, &pair));
        double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
        TRY(w, dem_world_add_plane(w, p0, nz, iw, NULL, NULL));
        dem_particle p = test_particle(0, 0, a + 1e-5, 0, 0, -0.1, a, rho, ip);
        TRY(w, dem_world_add_particles(w, 1, &p));
        long in_contact = 0;
        double fc[3];
        dem_arrays A;
        for (long k = 0; k < (long)(4.0 * tc / dt); ++k) {
            TRY(w, dem_world_step(w, 1));
            TRY(w, dem_world_particle_contacts(w, NULL, fc));
            if (fc[0] != 0 || fc[1] != 0 || fc[2] != 0) in_contact++;
        }
        TRY(w, dem_world_arrays(w, &A));
        check_rel("set_pair: particle-wall restitution of the override", A.v[2] / 0.1, ew, 0.01);
        check_rel("set_pair: particle-wall contact time of the override [s]", in_contact * dt, tc, 0.01);
        dem_world_destroy(&w);
    }
    /* round trip of the mapping through dem_world_material_get */
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-6, NULL, 0.02);
    dem_material m = test_material(1e7, 0.3, 0.3, 0.0, 0.5), got, got2;
    int id, id2;
    TRY(w, dem_world_add_material(w, &m, &id));
    TRY(w, dem_world_material_get(w, id, &got));
    m.restitution = -1.0;
    m.damping = got.damping;
    TRY(w, dem_world_add_material(w, &m, &id2));
    TRY(w, dem_world_material_get(w, id2, &got2));
    check_rel("hertzMindlin damping -> restitution round trip", got2.restitution, 0.5, 1e-6);
    dem_world_destroy(&w);
    return check_exit();
}
