/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Oblique impact of a sphere on a plane wall, Hertz-Mindlin, no gravity.
 * Sliding regime (tan(theta) > 7/2 mu (1+e)): rigid-body Coulomb impact
 * gives v_t'/v_t = 1 - mu (1+e) / tan(theta) and a w' = 5/2 mu (1+e) v_n
 * (solid sphere, no initial spin) - checked within 2 %.
 * Sticking regime (small theta): the rigid body ends rolling,
 * v_t'/v_t = 5/7 and contact-point slip u = v_t - a w = 0.  With Mindlin's
 * tangential compliance (Maw, Barber & Fawcett, Wear 38 (1976) 101) the
 * contact point oscillates tangentially during the impact and leaves with
 * a slip u'/u0 that, for small angles (no micro-slip), follows from
 *   delta'' = -(k/m) delta^(3/2),  u'' = -(7/2) k_t(delta, u) u / m
 * with the [Z] Mindlin force mu f_cn (1 - (1 - |u|/delta_t,max)^(3/2)).
 * The test integrates these equations (RK4, independent of the library)
 * and checks the simulated slip ratio at 2 and 5 degrees (e = 1) within
 * 0.02, and that at 10 and 20 degrees (e = 0.9, micro-slip) v_t'/v_t
 * deviates from the rigid 5/7 in the direction the no-slip solution gives. */
#include "check.h"

static void impact(double theta_deg, double mu, double e, double out[4])
{
    const double a = 1e-3, rho = 2500, V = 1.0, th = theta_deg * M_PI / 180.0;
    const double dt = 2.5e-4 / 2000.0;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, dt, NULL, 0.05);
    dem_material mat = test_material(1e7, 0.3, mu, 0.0, e);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, p0, nz, mid, NULL, NULL));
    double vn = V * cos(th), vt = V * sin(th);
    dem_particle p = test_particle(0, 0, a + 1e-6, vt, 0, -vn, a, rho, mid);
    TRY(w, dem_world_add_particles(w, 1, &p));
    TRY(w, dem_world_step(w, 4000));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    out[0] = A.v[2] / vn;              /* normal restitution */
    out[1] = A.v[0] / vt;              /* tangential velocity ratio */
    out[2] = a * A.omega[1] / vn;      /* rebound spin a w_y / v_n */
    out[3] = (A.v[0] - a * A.omega[1]) / vt; /* contact-point slip ratio */
    dem_world_destroy(&w);
}

/* No-slip Mindlin reference: returns u_end/u0 for a sphere on a wall. */
static double mindlin_slip_ratio(double theta_deg, double mu)
{
    const double a = 1e-3, rho = 2500, E = 1e7, nu = 0.3, V = 1.0, th = theta_deg * M_PI / 180.0;
    const double m = rho * 4.0 / 3.0 * M_PI * a * a * a, es = E / (2 * (1 - nu * nu));
    const double k = 4.0 / 3.0 * es * sqrt(a), mind = (2 - nu) / (2 * (1 - nu));
    double y[4] = {0, V * cos(th), 0, V * sin(th)}; /* delta, delta', u, u' */
    const double h = 1e-8;
    for (long it = 0; it < 10000000; ++it) {
        double kk[4][4], yy[4];
        for (int st = 0; st < 4; ++st) {
            double c = st == 0 ? 0 : (st == 3 ? 1.0 : 0.5);
            for (int q = 0; q < 4; ++q) yy[q] = y[q] + (st ? c * h * kk[st - 1][q] : 0.0);
            double d = yy[0] > 0 ? yy[0] : 0, fcn = k * d * sqrt(d), dtm = mu * mind * d;
            double x = dtm > 0 ? fmin(fabs(yy[2]) / dtm, 1.0) : 1.0;
            double ft = fcn > 0 ? mu * fcn * (1.0 - pow(1.0 - x, 1.5)) * (yy[2] > 0 ? 1 : -1) : 0.0;
            kk[st][0] = yy[1];
            kk[st][1] = -fcn / m;
            kk[st][2] = yy[3];
            kk[st][3] = -3.5 * ft / m;
        }
        for (int q = 0; q < 4; ++q) y[q] += h / 6.0 * (kk[0][q] + 2 * kk[1][q] + 2 * kk[2][q] + kk[3][q]);
        if (y[0] < 0 && it > 10) break;
    }
    return y[3] / (V * sin(th));
}

int main(void)
{
    const double mu = 0.3, e = 0.9;
    const double angles[3] = {70.0, 75.0, 85.0};
    char name[160];
    for (int k = 0; k < 3; ++k) {
        double r[4], tn = tan(angles[k] * M_PI / 180.0);
        impact(angles[k], mu, e, r);
        snprintf(name, sizeof name, "oblique sliding theta=%.0f normal restitution", angles[k]);
        check_rel(name, r[0], e, 0.01);
        snprintf(name, sizeof name, "oblique sliding theta=%.0f v_t'/v_t (Coulomb)", angles[k]);
        check_rel(name, r[1], 1.0 - mu * (1.0 + e) / tn, 0.02);
        snprintf(name, sizeof name, "oblique sliding theta=%.0f a w'/v_n (Coulomb)", angles[k]);
        check_rel(name, r[2], 2.5 * mu * (1.0 + e), 0.02);
    }
    const double small[2] = {2.0, 5.0};
    for (int k = 0; k < 2; ++k) {
        double r[4], ref = mindlin_slip_ratio(small[k], mu);
        impact(small[k], mu, 1.0, r);
        snprintf(name, sizeof name, "oblique sticking theta=%.0f e=1 slip ratio u'/u0 (Mindlin no-slip)", small[k]);
        check_abs(name, r[3], ref, 0.02);
    }
    const double stick[2] = {10.0, 20.0};
    double sgn = mindlin_slip_ratio(1.0, mu) > 0 ? 1.0 : -1.0; /* side of 5/7 Mindlin predicts */
    for (int k = 0; k < 2; ++k) {
        double r[4];
        impact(stick[k], mu, e, r);
        snprintf(name, sizeof name, "oblique sticking theta=%.0f (v_t'/v_t - 5/7) x sign(Mindlin slip) > 0", stick[k]);
        check_below(name, -sgn * (r[1] - 5.0 / 7.0), 0.0);
        snprintf(name, sizeof name, "oblique sticking theta=%.0f v_t'/v_t within 25 %% of rigid 5/7", stick[k]);
        check_rel(name, r[1], 5.0 / 7.0, 0.25);
    }
    return check_exit();
}
