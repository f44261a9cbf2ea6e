/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Hertz elastic normal impact (no damping, no friction, no gravity):
 * sphere-sphere, sphere on a wall of the same material, and sphere on a
 * rigid wall (DEM_RIGID: E* = E/(1 - nu^2) of the sphere alone);
 * peak force, peak overlap and contact duration against Hertz theory
 * (Johnson, Contact Mechanics, 1985, sec. 11.4):
 *   delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5)
 *   F_max     = (4/3) E* sqrt(R*) delta_max^(3/2)
 *   t_c       = 2 (2/5) B(2/5, 1/2) delta_max / v  (= 2.9432 delta_max / v)     */
#include "check.h"

/* the id of the last material added (the rigid wall's in run(2)) */
static int wmid_of(dem_world *w)
{
    dem_material m;
    int id = 0;
    while (dem_world_material_get(w, id + 1, &m) == DEM_OK) ++id;
    return id;
}

/* Linear spring-dashpot, undamped (e = 1), sphere on a rigid wall: the
 * spring is the sphere's k_n alone, contact duration pi sqrt(m / k_n). */
static void linear_rigid(void)
{
    const double a = 1e-3, rho = 2500, kn = 100.0, v0 = 0.5;
    const double m = rho * 4.0 / 3.0 * M_PI * a * a * a;
    const double tc = M_PI * sqrt(m / kn), dt = tc / 2000.0;
    dem_world *w = test_world(DEM_CONTACT_LINEAR_SPRING_DASHPOT, dt, NULL, 0.02);
    dem_material s = test_material(0, 0.3, 0.0, 0.0, 1.0), r = s;
    s.stiffness_n = kn; s.stiffness_t = -1;
    r.stiffness_n = DEM_RIGID; r.stiffness_t = -1;
    int sid, rid;
    TRY(w, dem_world_add_material(w, &s, &sid));
    TRY(w, dem_world_add_material(w, &r, &rid));
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, p0, nz, rid, NULL, NULL));
    const double gap = 0.25 * v0 * tc;
    dem_particle p = test_particle(0, 0, a + gap, 0, 0, -v0, a, rho, sid);
    TRY(w, dem_world_add_particles(w, 1, &p));
    long in_contact = 0, nsteps = (long)(3.0 * tc / dt);
    dem_arrays A;
    for (long k = 0; k < nsteps; ++k) {
        TRY(w, dem_world_step(w, 1));
        TRY(w, dem_world_arrays(w, &A));
        if (A.x[2] < a) in_contact++;
    }
    check_rel("linear sphere-rigid wall contact duration pi sqrt(m/k_n) [s]", in_contact * dt, tc, 0.01);
    TRY(w, dem_world_arrays(w, &A));
    check_rel("linear sphere-rigid wall rebound speed (e = 1) [m/s]", A.v[2], v0, 0.01);
    dem_world_destroy(&w);
}

static void run(int mode)
{
    const int wall = mode > 0, rigid = mode == 2;
    const double a = 1e-3, rho = 2500, E = 1e7, nu = 0.3, v0 = 1.0;
    const double m = rho * 4.0 / 3.0 * M_PI * a * a * a;
    const double estar = rigid ? E / (1.0 - nu * nu) : E / (2.0 * (1.0 - nu * nu));
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
        int wmid = mid;
        if (rigid) {
            dem_material rw = test_material(DEM_RIGID, 0.25, 0.0, 0.0, 1.0);
            TRY(w, dem_world_add_material(w, &rw, &wmid));
        }
        TRY(w, dem_world_add_plane(w, p0, nz, wmid, NULL, NULL));
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
    const char *kind = rigid ? "sphere-rigid wall" : wall ? "sphere-wall" : "sphere-sphere";
    snprintf(name, sizeof name, "hertz %s peak overlap [m]", kind);
    check_rel(name, pk_d, dmax, 0.01);
    snprintf(name, sizeof name, "hertz %s peak force [N]", kind);
    check_rel(name, pk_f, fmax, 0.01);
    snprintf(name, sizeof name, "hertz %s contact duration [s]", kind);
    check_rel(name, in_contact * dt, tc, 0.01);
    double tcw;
    TRY(w, dem_world_contact_time(w, v0, &tcw));
    if (!wall) check_rel("hertz contact_time() at impact speed [s]", tcw, tc, 1e-9);
    if (rigid) check_rel("hertz contact_time() at impact speed, rigid wall [s]", tcw, tc, 1e-9);
    if (rigid) {
        dem_particle bad = test_particle(0.01, 0, 0.01, 0, 0, 0, a, rho, wmid_of(w));
        check_status("rigid material refused for a particle", dem_world_add_particles(w, 1, &bad), DEM_ERR_ARG);
    }
    dem_world_destroy(&w);
}

int main(void)
{
    run(0);
    run(1);
    run(2);
    linear_rigid();
    return check_exit();
}
