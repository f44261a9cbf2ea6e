/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Contact law hertzMindlinNoSlip against the closed forms of rigid-body
 * Coulomb friction (docs/theory.md section 7.2.1):
 *  - oblique impact on a rigid plane in gross sliding (v_t/v_n = 2 and 4,
 *    mu = 0.1, e = 0.9, so v_t > (7/2) mu (1 + e) v_n): impulse-momentum
 *    with Coulomb friction gives v_t' = v_t - mu (1 + e) v_n and
 *    w' = (5/2) mu (1 + e) v_n / a.  The Coulomb limit uses the elastic
 *    normal force, whose impulse is exactly m (1 + e) v_n (the damping
 *    impulse of a complete contact is zero), so the only errors are the
 *    integration (dt = t_c/2000) and the restitution itself: 0.5 %.
 *  - a sphere launched without spin along a rigid plane under gravity
 *    (mu = 0.3): it slides with deceleration mu g until it rolls at
 *    v = (5/7) v_0 after t = 2 v_0 / (7 mu g); 0.5 % on the final speed and
 *    a w / v = 1 at the end (0.5 %): the no-slip spring holds rolling. */
#include "check.h"

static void run_oblique(double ratio)
{
    const double a = 1e-3, rho = 2500, vn = 1.0, vt = ratio * vn, mu = 0.1, e = 0.9;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP, 1e-8, NULL, 0.05);
    dem_material pm = test_material(1e7, 0.3, mu, 0.0, e), wm = pm;
    wm.youngs_modulus = DEM_RIGID;
    int mp, mw;
    TRY(w, dem_world_add_material(w, &pm, &mp));
    TRY(w, dem_world_add_material(w, &wm, &mw));
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, p0, nz, mw, NULL, NULL));
    dem_particle p = test_particle(0, 0, a + 1e-6, vt, 0, -vn, a, rho, mp);
    TRY(w, dem_world_add_particles(w, 1, &p));
    double tc;
    TRY(w, dem_world_contact_time(w, vn, &tc));
    dem_config c;
    dem_config_default(&c);
    c.contact_law = DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP;
    c.dt = tc / 2000.0;
    for (int k = 0; k < 3; ++k) { c.gravity[k] = 0.0; c.domain_lo[k] = -0.05; c.domain_hi[k] = 0.05; }
    TRY(w, dem_world_configure(w, &c));
    TRY(w, dem_world_step(w, (int64_t)(2.0 * tc / c.dt) + 200));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    char name[160];
    snprintf(name, sizeof name, "hertzMindlinNoSlip oblique gross sliding v_t/v_n=%g: v_t' [m/s]", ratio);
    check_rel(name, A.v[0], vt - mu * (1.0 + e) * vn, 0.005);
    snprintf(name, sizeof name, "hertzMindlinNoSlip oblique gross sliding v_t/v_n=%g: spin w_y [1/s]", ratio);
    check_rel(name, A.omega[1], 2.5 * mu * (1.0 + e) * vn / a, 0.005);
    dem_world_destroy(&w);
}

static void run_rolling(void)
{
    const double a = 1e-3, rho = 2500, v0 = 0.1, mu = 0.3, g = 9.81;
    const double grav[3] = {0, 0, -g};
    dem_material pm = test_material(1e7, 0.3, mu, 0.0, 0.5), wm = pm;
    wm.youngs_modulus = DEM_RIGID;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP, 1e-6, grav, 0.5);
    int mp, mw;
    TRY(w, dem_world_add_material(w, &pm, &mp));
    TRY(w, dem_world_add_material(w, &wm, &mw));
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, p0, nz, mw, NULL, NULL));
    /* resting at its static overlap: m g = (4/3) E* sqrt(a) delta^(3/2) */
    const double m = rho * 4.0 / 3.0 * M_PI * a * a * a, es = 1e7 / (1.0 - 0.09);
    const double d0 = pow(m * g / (4.0 / 3.0 * es * sqrt(a)), 2.0 / 3.0);
    dem_particle p = test_particle(0, 0, a - d0, v0, 0, 0, a, rho, mp);
    TRY(w, dem_world_add_particles(w, 1, &p));
    const double tslide = 2.0 * v0 / (7.0 * mu * g);
    TRY(w, dem_world_step(w, (int64_t)(1.5 * tslide / 1e-6)));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    check_rel("hertzMindlinNoSlip sliding to rolling: final speed [m/s]", A.v[0], 5.0 / 7.0 * v0, 0.005);
    check_rel("hertzMindlinNoSlip rolling: a w_y / v_x", a * A.omega[1] / A.v[0], 1.0, 0.005);
    dem_world_destroy(&w);
}

int main(void)
{
    run_oblique(2.0);
    run_oblique(4.0);
    run_rolling();
    return check_exit();
}
