/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Contact-history bookkeeping and a small conformance suite run against
 * every contact law:
 * - a pressed and sheared pair (external forces and the torques that balance
 *   their couple; tangential load below the Coulomb limit) translating at 0.5 m/s through a periodic box: with a tiny
 *   skin the list is rebuilt (and re-sorted) every few steps, with a large
 *   skin almost never; the tangential history must survive every rebuild and
 *   the periodic wrap, so both runs agree to round-off;
 * - Newton's third law: the contact forces of the pair sum to zero;
 * - zero force at zero overlap (spheres exactly touching). */
#include "check.h"

static void run(dem_contact_law law, double skin, double out[7], int *nbuild_hint)
{
    const double a = 1e-3, rho = 2500, dt = 1e-6, L = 0.02;
    dem_world *w = NULL;
    TRY(w, dem_world_create(&w));
    dem_config c;
    dem_config_default(&c);
    c.contact_law = law;
    c.dt = dt;
    c.gravity[2] = 0;
    c.skin = skin;
    for (int k = 0; k < 3; ++k) { c.domain_lo[k] = 0; c.domain_hi[k] = L; c.periodic[k] = 1; }
    c.max_dt_fraction = 0.5;
    TRY(w, dem_world_configure(w, &c));
    dem_material m = test_material(1e7, 0.3, 0.5, 0.0, 0.3);
    m.stiffness_n = 1000.0;
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    double Fn = 0.01, Ft = 0.3 * 0.5 * Fn;
    /* start slightly overlapped at roughly the static overlap */
    double d0 = law == DEM_CONTACT_LINEAR_SPRING_DASHPOT ? Fn / 1000.0 : 1.5e-5;
    dem_particle p[2] = {test_particle(L - 3e-3, 0.01, 0.01, 0.5, 0, 0, a, rho, mid),
                         test_particle(L - 3e-3, 0.01, 0.01 + 2 * a - d0, 0.5, 0, 0, a, rho, mid)};
    TRY(w, dem_world_add_particles(w, 2, p));
    dem_arrays A;
    dem_stats s0;
    TRY(w, dem_world_stats(w, &s0));
    for (int st = 0; st < 20000; ++st) {
        /* loads follow the line of centres (a dead load along a fixed axis
           would buckle the two-sphere column) */
        TRY(w, dem_world_arrays(w, &A));
        int i0 = A.id[0] == 0 ? 0 : 1, i1 = 1 - i0;
        double e[3], l = 0;
        for (int k = 0; k < 3; ++k) {
            e[k] = A.x[3 * i1 + k] - A.x[3 * i0 + k];
            e[k] -= L * nearbyint(e[k] / L);
            l += e[k] * e[k];
        }
        l = sqrt(l);
        for (int k = 0; k < 3; ++k) e[k] /= l;
        double tv[3] = {e[2], 0.0, -e[0]}; /* in the x-z plane, normal to e */
        for (int k = 0; k < 3; ++k) {
            A.force_ext[3 * i0 + k] = Fn * e[k] + Ft * tv[k];
            A.force_ext[3 * i1 + k] = -Fn * e[k] - Ft * tv[k];
            A.torque_ext[3 * i0 + k] = A.torque_ext[3 * i1 + k] = k == 1 ? a * Ft : 0.0; /* cancels the shear couple */
        }
        TRY(w, dem_world_step(w, 1));
    }
    TRY(w, dem_world_arrays(w, &A));
    double fc[6];
    TRY(w, dem_world_particle_contacts(w, NULL, fc));
    int i0 = A.id[0] == 0 ? 0 : 1, i1 = 1 - i0;
    out[0] = A.x[3 * i0];                                  /* wrapped position */
    out[1] = A.x[3 * i1 + 2] - A.x[3 * i0 + 2];            /* separation */
    out[2] = A.v[3 * i1] - A.v[3 * i0];                     /* relative sliding velocity */
    out[3] = A.omega[3 * i0 + 1];
    out[4] = fc[3 * i0];                                    /* tangential contact force on 0 */
    out[5] = fabs(fc[0] + fc[3]) + fabs(fc[1] + fc[4]) + fabs(fc[2] + fc[5]); /* third law */
    out[6] = fabs(fc[3 * i0 + 2]);
    dem_stats s1;
    TRY(w, dem_world_stats(w, &s1));
    *nbuild_hint = (int)(s1.list_builds - s0.list_builds);
    dem_world_destroy(&w);
}

int main(void)
{
    const dem_contact_law laws[3] = {DEM_CONTACT_HERTZ_MINDLIN, DEM_CONTACT_LINEAR_SPRING_DASHPOT,
                                     DEM_CONTACT_HERTZ_SPRING_DASHPOT};
    char name[200];
    for (int l = 0; l < 3; ++l) {
        const char *ln = dem_contact_law_name(laws[l]);
        double r1[7], r2[7];
        int nb1, nb2;
        run(laws[l], 1e-6, r1, &nb1);
        run(laws[l], 4e-4, r2, &nb2);
        snprintf(name, sizeof name, "%s history across %d list builds vs %d: separation [m]", ln, nb1, nb2);
        check_rel(name, r1[1], r2[1], 1e-9);
        snprintf(name, sizeof name, "%s history across rebuilds: tangential contact force [N]", ln);
        check_rel(name, r1[4], r2[4], 1e-6);
        snprintf(name, sizeof name, "%s history across rebuilds: spin [rad/s]", ln);
        check_abs(name, r1[3], r2[3], 1e-6 * fabs(r2[3]) + 1e-9);
        if (laws[l] != DEM_CONTACT_HERTZ_SPRING_DASHPOT) { /* (weakly damped: still ringing) */
            snprintf(name, sizeof name, "%s static friction holds the shear load (tangential force / F_t)", ln);
            check_rel(name, -r1[4] / (0.3 * 0.5 * 0.01), 1.0, 0.05);
        }
        snprintf(name, sizeof name, "%s pair crossed the periodic boundary (wrapped x < start)", ln);
        check_below(name, r1[0], 0.02 - 3e-3);
        snprintf(name, sizeof name, "%s third law: |F_0 + F_1| / |F_n|", ln);
        check_below(name, r1[5] / r1[6], 1e-12);
    }
    /* zero force at zero overlap, all laws */
    for (int l = 0; l < 3; ++l) {
        dem_world *w = test_world(laws[l], 1e-6, NULL, 0.05);
        dem_material m = test_material(1e7, 0.3, 0.5, 1e-5, 0.5);
        m.stiffness_n = 1000.0;
        int mid;
        TRY(w, dem_world_add_material(w, &m, &mid));
        dem_particle p[2] = {test_particle(0, 0, 0, 0, 0, 0, 1e-3, 2500, mid),
                             test_particle(2e-3, 0, 0, 0, 0, 0, 1e-3, 2500, mid)};
        TRY(w, dem_world_add_particles(w, 2, p));
        TRY(w, dem_world_step(w, 1));
        double fc[6];
        TRY(w, dem_world_particle_contacts(w, NULL, fc));
        snprintf(name, sizeof name, "%s zero force at zero overlap [N]", dem_contact_law_name(laws[l]));
        check_abs(name, fabs(fc[0]) + fabs(fc[1]) + fabs(fc[2]), 0.0, 0.0);
        dem_world_destroy(&w);
    }
    return check_exit();
}
