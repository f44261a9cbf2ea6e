/*---------------------------------------------------------------------------*\
  demFoam DEM core - restitution <-> damping mappings of the contact laws
  and the Hertz contact duration.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

  Hertz-Mindlin [Z]: m x'' = -(4/3) E* sqrt(R) x^(3/2) - c sqrt(8 m E* sqrt(R x)) x'.
  With k = (4/3) E* sqrt(R), x = L y, t = T s, T^2 k L^(1/2) / m = 1 and
  L = v0 T (unit impact speed) this becomes, for every m, R, E*, v0,

        y'' = -y^(3/2) - c sqrt(6) y^(1/4) y',   y(0) = 0, y'(0) = 1,

  so e = -y'(s_end) (y(s_end) = 0) depends on c only.  e(c) is found by
  integrating this ODE (classical RK4, h = 1e-4 of a contact time ~3.2) and
  inverted by bisection.
  Linear spring-dashpot [S]: e = exp(-gamma t_c/2), t_c = pi (k/m - gamma^2/4)^(-1/2)
  gives gamma = 2 L sqrt(k/m) / sqrt(pi^2 + L^2), L = -ln e, i.e.
  eta = gamma m = beta sqrt(k m) with beta = 2 L / sqrt(pi^2 + L^2).
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>

static void hm_rhs(double c6, double y, double v, double *a)
{
    double yp = y > 0 ? y : 0.0;
    *a = -yp * sqrt(yp) - c6 * sqrt(sqrt(yp)) * v;
}

/* The dimensionless impact with damping c6 = c_n sqrt(6): e, and in *s_end
 * the dimensionless duration (0: no rebound). */
static double hm_impact(double c6, double *s_end)
{
    const double h = 1e-4;
    *s_end = 0.0;
    double y = 0.0, v = 1.0;
    for (long it = 0; it < 2000000; ++it) {
        double a1, a2, a3, a4;
        hm_rhs(c6, y, v, &a1);
        double y2 = y + 0.5 * h * v, v2 = v + 0.5 * h * a1;
        hm_rhs(c6, y2, v2, &a2);
        double y3 = y + 0.5 * h * v2, v3 = v + 0.5 * h * a2;
        hm_rhs(c6, y3, v3, &a3);
        double y4 = y + h * v3, v4 = v + h * a3;
        hm_rhs(c6, y4, v4, &a4);
        double yn = y + h / 6.0 * (v + 2 * v2 + 2 * v3 + v4);
        double vn = v + h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4);
        if (yn <= 0.0 && it > 0) {
            /* cubic Hermite on [y, yn]: find the root and the slope there */
            double lo = 0.0, hi = 1.0;
            for (int k = 0; k < 60; ++k) {
                double s = 0.5 * (lo + hi);
                double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
                double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
                double ys = h00 * y + h10 * h * v + h01 * yn + h11 * h * vn;
                if (ys > 0) lo = s; else hi = s;
            }
            double s = 0.5 * (lo + hi);
            /* velocity: linear in the (smooth) velocity over the step */
            double vs = v + s * (vn - v);
            *s_end = ((double)it + s) * h;
            return vs < 0 ? -vs : 0.0;
        }
        if (v <= 0 && vn >= 0 && yn > 0 && it > 0) return 0.0; /* stuck: no rebound */
        y = yn; v = vn;
    }
    return 0.0;
}

double dem_hm_restitution(double cn)
{
    if (!(cn > 0)) return 1.0;
    /* e = 0 (no rebound) from c_n ~ 1.3 on; above ~2.5e5 the explicit
       integration returned garbage (e ~ 1e30) */
    if (cn >= 1e3) return 0.0;
    double s;
    return hm_impact(cn * sqrt(6.0), &s);
}

/* Damped / elastic contact duration of the same impact (the scaled ODE
 * above with and without damping; it depends on c_n only). */
double dem_hm_time_ratio(double cn)
{
    if (!(cn > 0)) return 1.0;
    if (cn >= 1e3) return INFINITY;
    double s0, s;
    hm_impact(0.0, &s0);
    hm_impact(cn * sqrt(6.0), &s);
    return s > 0.0 ? s / s0 : INFINITY;
}

double dem_hm_damping(double e)
{
    if (!(e < 1.0)) return 0.0;
    double lo = 0.0, hi = 1.0;
    while (dem_hm_restitution(hi) > e && hi < 1e3) { lo = hi; hi *= 2.0; }
    for (int k = 0; k < 40; ++k) {
        double c = 0.5 * (lo + hi);
        if (dem_hm_restitution(c) > e) lo = c; else hi = c;
    }
    return 0.5 * (lo + hi);
}

double dem_lsd_beta(double e)
{
    if (!(e < 1.0)) return 0.0;
    double L = -log(e);
    return 2.0 * L / sqrt(DEM_PI * DEM_PI + L * L);
}

/* Elastic Hertz contact duration t_c = 2 * (2/5) B(2/5,1/2) * delta_max / v,
 * delta_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5) (Hertz theory; e.g. Johnson,
 * Contact Mechanics, 1985, sec. 11.4). */
double dem_hertz_time(double meff, double rstar, double estar, double v)
{
    double c = 2.0 * 0.4 * tgamma(0.4) * tgamma(0.5) / tgamma(0.9);
    double dm = pow(15.0 * meff * v * v / (16.0 * estar * sqrt(rstar)), 0.4);
    return c * dm / v;
}
