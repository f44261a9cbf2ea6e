/*---------------------------------------------------------------------------*\
  demFoam DEM core - restitution <-> damping mappings and the random number
  generator.
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

double dem_hm_restitution(double cn)
{
    if (!(cn > 0)) return 1.0;
    /* e = 0 (no rebound) from c_n ~ 1.3 on; above ~2.5e5 the explicit
       integration below is unstable and returned garbage (e ~ 1e30) */
    if (cn >= 1e3) return 0.0;
    const double h = 1e-4, c6 = cn * sqrt(6.0);
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
            return vs < 0 ? -vs : 0.0;
        }
        if (v <= 0 && vn >= 0 && yn > 0 && it > 0) return 0.0; /* stuck: no rebound */
        y = yn; v = vn;
    }
    return 0.0;
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

/*--- xoshiro256** (Blackman & Vigna, 2018), seeded by splitmix64 ----------------*/
static uint64_t splitmix64(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

void dem_rng_seed(dem_world *w, uint64_t seed)
{
    uint64_t s = seed;
    for (int k = 0; k < 4; ++k) w->rng[k] = splitmix64(&s);
}

static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t dem_rng_next(dem_world *w)
{
    uint64_t *s = w->rng;
    uint64_t r = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0]; s[3] ^= s[1]; s[1] ^= s[2]; s[0] ^= s[3];
    s[2] ^= t; s[3] = rotl(s[3], 45);
    return r;
}

double dem_rng_uniform(dem_world *w) { return (double)(dem_rng_next(w) >> 11) * 0x1.0p-53; }

double dem_dist_draw(dem_world *w, const dem_distribution *d)
{
    switch (d->kind) {
    case DEM_DIST_FIXED: return d->a;
    case DEM_DIST_UNIFORM: return d->a + (d->b - d->a) * dem_rng_uniform(w);
    case DEM_DIST_NORMAL:
        for (;;) { /* Box-Muller, truncated at +-3 sigma by rejection */
            double u1 = dem_rng_uniform(w), u2 = dem_rng_uniform(w);
            if (u1 <= 0) continue;
            double z = sqrt(-2.0 * log(u1)) * cos(2.0 * DEM_PI * u2);
            if (fabs(z) <= 3.0) return d->a + d->b * z;
        }
    case DEM_DIST_DISCRETE: {
        double tot = 0;
        for (size_t k = 0; k < d->n; ++k) tot += d->weights[k];
        double u = dem_rng_uniform(w) * tot, acc = 0;
        for (size_t k = 0; k < d->n; ++k) { acc += d->weights[k]; if (u < acc) return d->values[k]; }
        return d->values[d->n - 1];
    }
    }
    return d->a;
}
