/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Oblique impact of an alumina sphere on a glass anvil: the contact laws
 * against the experiment of Kharaz, Gorham & Salman, "An experimental study
 * of the elastic rebound of spheres", Powder Technol. 120 (2001) 281-291,
 * and against the sticking and sliding limits of rigid-body and Mindlin
 * no-slip theory (Maw, Barber & Fawcett, Wear 38 (1976) 101 and
 * J. Lubr. Technol. 103 (1981) 74).  docs/theory.md section 7.2.1.
 *
 * Set-up (Kharaz et al. 2001; the values used in the model comparison of
 * Di Renzo & Di Maio, Chem. Eng. Sci. 59 (2004) 525): 5 mm sphere,
 * alumina E = 380 GPa, nu = 0.23, rho = 4000 kg/m3, on soda-lime glass
 * E = 70 GPa, nu = 0.25; impact speed 3.9 m/s, no initial spin, no gravity;
 * friction mu = 0.092 (from the gross-sliding rebounds), normal
 * restitution e = 0.98.  Incidence angle theta from the normal.
 *
 * Measured points: as digitised from the paper's figures for the NETL MFiX
 * verification case DEM05 (files tests/dem/DEM05/AUTOTEST/POST_*.dat of
 * MFiX): tangential restitution e_t = v_t'/v_t of the centre of mass,
 * rebound angle atan(v_t'/v_n') and rebound spin w'.
 *
 * Tolerances (what is checked):
 *  - experiment, hertzMindlinNoSlip, incidence >= 9 degrees: e_t within
 *    0.04 absolute, the rebound angle within 1.5 degrees, the spin within
 *    12 %.  The scatter, measured on the data themselves: from 30 to 60
 *    degrees rigid-body Coulomb sliding is exact (both laws reproduce it
 *    within 0.01 %, below) and the measured points lie off it by up to
 *    0.008 in e_t, 0.84 degrees in rebound angle and 7.5 % in spin
 *    (scatter of the measurements, the digitisation and the fitted mu
 *    together).  The tolerances are about 1.6-1.8 times those for angle and
 *    spin; e_t is the rebound angle seen through
 *    d e_t = e d(tan theta')/tan theta, and the 0.84 degree scatter is 0.04
 *    in e_t at 20 degrees (0.08 at 10 degrees).
 *    Below 9 degrees (Psi1 < 0.8) the measured e_t falls to 0.75-0.8 and
 *    the spin stays high: micro-slip at the rim of the contact (Maw et al.
 *    1981), which a no-slip spring does not have; there the law follows the
 *    Mindlin no-slip line (e_t near 1, checked below against its own closed
 *    form) and its deviation from the experiment is printed, not checked.
 *  - hertzMindlin ([Z] Table 2, default law): its deviation from the
 *    experiment is printed (INFO lines), not checked; checked in the sliding
 *    limit (below).
 *  - closed forms, both laws: gross sliding (tan theta > (7/2) mu (1 + e),
 *    theta > 32.5 deg) v_t'/v_t = 1 - mu (1 + e)/tan theta and
 *    a w' = (5/2) mu (1 + e) v_n within 0.5 % (integration at t_c/1000);
 *    in the normalised form Psi1 = kappa v_t/(mu (1 + e) v_n),
 *    Psi2 = kappa u'/(mu (1 + e) v_n) (u' = v_t' - a w' the contact-point
 *    slip at rebound, kappa = 2 (1 - nu)/(2 - nu)), sliding is
 *    Psi2 = Psi1 - (7/2) kappa; in the sticking range (Psi1 < 0.3, elastic
 *    e = 1 as in Maw et al.'s theory) hertzMindlinNoSlip follows the
 *    Mindlin no-slip line Psi2 = r Psi1, r = u'/u0 of an independent
 *    integration (RK4) of
 *        delta'' = -f_n(delta)/m,   u'' = -(7/2) k_t(delta) u / m,
 *    k_t = 8 G* (R delta)^(1/2), within 0.01 in r; the [Z] law's r is
 *    printed. */
#include "check.h"

#define A_RAD 2.5e-3
#define RHO 4000.0
#define V0 3.9
#define MU 0.092
#define EN 0.98
#define E_AL 380e9
#define NU_AL 0.23
#define E_GL 70e9
#define NU_GL 0.25
/* tolerances against the experiment (see the head of the file) */
#define THETA_CHECK 9.0
#define TOL_ET 0.04
#define TOL_ANGLE 1.5
#define TOL_SPIN 0.12

/* Kharaz et al. (2001), digitised (MFiX DEM05): incidence [deg], value */
static const double exp_et[][2] = {
    {2.0275, 0.7938}, {3.9282, 0.7450}, {9.6304, 0.6728}, {20.0845, 0.5964},
    {30.2218, 0.6883}, {39.3031, 0.7719}, {49.5459, 0.8469}, {59.8416, 0.9019}};
static const double exp_angle[][2] = {
    {2.2945, 1.7630}, {4.2922, 2.9577}, {9.9429, 6.6917}, {20.5594, 12.3645},
    {30.3767, 21.7809}, {39.6233, 32.5455}, {49.7831, 45.1051}, {60.0571, 57.3652}};
static const double exp_spin[][2] = {
    {6.0025, 135.5703}, {10.9840, 264.5493}, {21.1931, 577.0096}, {31.0947, 612.6481},
    {39.0283, 595.4843}, {50.2214, 452.9444}, {60.2460, 381.3185}};
#define NPTS(a) ((int)(sizeof(a) / sizeof((a)[0])))

typedef struct { double en, et, angle, spin, slip; } rebound;

static rebound impact(dem_contact_law law, double theta_deg, double en, double dt_frac)
{
    const double th = theta_deg * M_PI / 180.0, vn = V0 * cos(th), vt = V0 * sin(th);
    dem_world *w = test_world(law, 1e-9, NULL, 0.05);
    dem_material al = test_material(E_AL, NU_AL, MU, 0.0, en);
    dem_material gl = test_material(E_GL, NU_GL, MU, 0.0, en);
    int mal, mgl;
    TRY(w, dem_world_add_material(w, &al, &mal));
    TRY(w, dem_world_add_material(w, &gl, &mgl));
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, p0, nz, mgl, NULL, NULL));
    dem_particle p = test_particle(0, 0, A_RAD + 1e-7, vt, 0, -vn, A_RAD, RHO, mal);
    TRY(w, dem_world_add_particles(w, 1, &p));
    double tc;
    TRY(w, dem_world_contact_time(w, vn, &tc));
    dem_config c;
    dem_config_default(&c);
    c.contact_law = law;
    c.dt = tc * dt_frac;
    for (int k = 0; k < 3; ++k) { c.gravity[k] = 0.0; c.domain_lo[k] = -0.05; c.domain_hi[k] = 0.05; }
    TRY(w, dem_world_configure(w, &c));
    /* dem_world_contact_time is the shortest over all material pairs
       (alumina-alumina here); step until the sphere has left the anvil */
    dem_arrays S;
    TRY(w, dem_world_arrays(w, &S));
    for (int it = 0; it < 1000 && !(S.x[2] > A_RAD && S.v[2] > 0.0); ++it) {
        TRY(w, dem_world_step(w, (int64_t)(0.1 * tc / c.dt) + 1));
        TRY(w, dem_world_arrays(w, &S));
    }
    rebound r;
    r.en = S.v[2] / vn;
    r.et = S.v[0] / vt;
    r.angle = atan2(S.v[0], S.v[2]) * 180.0 / M_PI;
    r.spin = S.omega[1];
    r.slip = S.v[0] - A_RAD * S.omega[1];
    dem_world_destroy(&w);
    return r;
}

static double kappa_nu(void) { const double nu = 0.5 * (NU_AL + NU_GL); return 2.0 * (1.0 - nu) / (2.0 - nu); }

/* Mindlin no-slip reference, independent of the library: u'/u0 of
 *   delta'' = -f_n/m,  u'' = -(7/2) k_t u/m  (elastic, no micro-slip). */
static double noslip_ratio(void)
{
    const double m = RHO * 4.0 / 3.0 * M_PI * A_RAD * A_RAD * A_RAD;
    const double ea = E_AL / (1 - NU_AL * NU_AL), eg = E_GL / (1 - NU_GL * NU_GL);
    const double es = 1.0 / (1.0 / ea + 1.0 / eg);
    const double ga = E_AL / (2 * (1 + NU_AL)), gg = E_GL / (2 * (1 + NU_GL));
    const double gs = 1.0 / ((2 - NU_AL) / ga + (2 - NU_GL) / gg);
    const double k = 4.0 / 3.0 * es * sqrt(A_RAD), kt0 = 8.0 * gs * sqrt(A_RAD);
    double y[4] = {0, 1.0, 0, 1.0};  /* delta, delta', u, u' (u linear: scale free) */
    const double h = 1e-9;
    for (long it = 0; it < 100000000; ++it) {
        double kk[4][4], yy[4];
        for (int st = 0; st < 4; ++st) {
            const double cst = st == 0 ? 0 : (st == 3 ? 1.0 : 0.5);
            for (int q = 0; q < 4; ++q) yy[q] = y[q] + (st ? cst * h * kk[st - 1][q] : 0.0);
            const double d = yy[0] > 0 ? yy[0] : 0;
            kk[st][0] = yy[1];
            kk[st][1] = -k * d * sqrt(d) / m;
            kk[st][2] = yy[3];
            kk[st][3] = -3.5 * kt0 * sqrt(d) * yy[2] / m;
        }
        for (int q = 0; q < 4; ++q) y[q] += h / 6.0 * (kk[0][q] + 2 * kk[1][q] + 2 * kk[2][q] + kk[3][q]);
        if (y[0] < 0 && it > 10) break;
    }
    return y[3];
}

int main(void)
{
    const dem_contact_law laws[2] = {DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP, DEM_CONTACT_HERTZ_MINDLIN};
    const char *lname[2] = {"hertzMindlinNoSlip", "hertzMindlin"};
    const double dtf = QUICK ? 1.0 / 200.0 : 1.0 / 1000.0;
    char name[200];

    /* 1. against the experiment */
    for (int l = 0; l < 2; ++l) {
        for (int i = 0; i < NPTS(exp_et); ++i) {
            const int chk = l == 0 && exp_et[i][0] >= THETA_CHECK;
            rebound r = impact(laws[l], exp_et[i][0], EN, dtf);
            snprintf(name, sizeof name, "%s Kharaz theta=%.1f e_t vs experiment", lname[l], exp_et[i][0]);
            if (chk) check_abs(name, r.et, exp_et[i][1], TOL_ET);
            else printf("INFO: %s: %.4f vs %.4f (deviation %+.4f)\n", name, r.et, exp_et[i][1], r.et - exp_et[i][1]);
        }
        for (int i = 0; i < NPTS(exp_angle); ++i) {
            const int chk = l == 0 && exp_angle[i][0] >= THETA_CHECK;
            rebound r = impact(laws[l], exp_angle[i][0], EN, dtf);
            snprintf(name, sizeof name, "%s Kharaz theta=%.1f rebound angle [deg] vs experiment", lname[l],
                     exp_angle[i][0]);
            if (chk) check_abs(name, r.angle, exp_angle[i][1], TOL_ANGLE);
            else printf("INFO: %s: %.3f vs %.3f (deviation %+.3f)\n", name, r.angle, exp_angle[i][1],
                        r.angle - exp_angle[i][1]);
        }
        for (int i = 0; i < NPTS(exp_spin); ++i) {
            const int chk = l == 0 && exp_spin[i][0] >= THETA_CHECK;
            rebound r = impact(laws[l], exp_spin[i][0], EN, dtf);
            snprintf(name, sizeof name, "%s Kharaz theta=%.1f spin [rad/s] vs experiment", lname[l],
                     exp_spin[i][0]);
            if (chk) check_rel(name, r.spin, exp_spin[i][1], TOL_SPIN);
            else printf("INFO: %s: %.1f vs %.1f (deviation %+.1f %%)\n", name, r.spin, exp_spin[i][1],
                        100.0 * (r.spin / exp_spin[i][1] - 1.0));
        }
    }

    /* 2. closed forms: gross sliding (both laws), Mindlin no-slip sticking line */
    const double kap = kappa_nu(), rr = noslip_ratio();
    printf("INFO: kappa = 2 (1 - nu)/(2 - nu) = %.4f, Mindlin no-slip u'/u0 = %.4f\n", kap, rr);
    const double slide[3] = {40.0, 50.0, 60.0};
    for (int l = 0; l < 2; ++l)
        for (int i = 0; i < 3; ++i) {
            const double th = slide[i] * M_PI / 180.0, vn = V0 * cos(th);
            rebound r = impact(laws[l], slide[i], EN, dtf);
            snprintf(name, sizeof name, "%s theta=%.0f sliding v_t'/v_t = 1 - mu (1+e)/tan(theta)", lname[l], slide[i]);
            check_rel(name, r.et, 1.0 - MU * (1.0 + r.en) / tan(th), 0.005);
            snprintf(name, sizeof name, "%s theta=%.0f sliding a w' = 5/2 mu (1+e) v_n", lname[l], slide[i]);
            check_rel(name, A_RAD * r.spin, 2.5 * MU * (1.0 + r.en) * vn, 0.005);
        }
    /* sticking: Psi1 = kappa tan(theta)/(mu (1+e)) < 1 */
    const double stick[3] = {1.0, 2.0, 3.0};
    for (int l = 0; l < 2; ++l)
        for (int i = 0; i < 3; ++i) {
            const double th = stick[i] * M_PI / 180.0, vn = V0 * cos(th), vt = V0 * sin(th);
            rebound r = impact(laws[l], stick[i], 1.0, dtf);
            const double psi1 = kap * vt / (MU * (1.0 + r.en) * vn), psi2 = kap * r.slip / (MU * (1.0 + r.en) * vn);
            snprintf(name, sizeof name, "%s theta=%.0f Psi1=%.3f sticking Psi2/Psi1 vs Mindlin no-slip", lname[l],
                     stick[i], psi1);
            if (l == 0) check_abs(name, psi2 / psi1, rr, 0.01);
            else printf("INFO: %s: %.4f vs %.4f (deviation %+.4f)\n", name, psi2 / psi1, rr, psi2 / psi1 - rr);
        }
    return check_exit();
}
