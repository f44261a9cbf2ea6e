/*---------------------------------------------------------------------------*\
  demFoam DEM core - random numbers: xoshiro256** and the size/density
  distributions drawn by insertion.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <math.h>

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
