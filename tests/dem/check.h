/*---------------------------------------------------------------------------*\
  demFoam DEM core tests - shared helpers.  Output protocol of
  docs/developers.md: one line per check,
      PASS: <name>: <measured> vs <expected> (tol <tolerance>)
  and a non-zero exit status if any check failed (check_exit()).

  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#ifndef DEM_TEST_CHECK_H
#define DEM_TEST_CHECK_H

#include "dem.h"
#include <math.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Sanitizer builds (-DDEM_TEST_QUICK) run shorter versions of the long tests. */
#ifdef DEM_TEST_QUICK
#define QUICK 1
#else
#define QUICK 0
#endif

static int check_failures = 0;

/* relative tolerance check (|m - e| <= tol |e|) */
static inline int check_rel(const char *name, double measured, double expected, double tol)
{
    int ok = isfinite(measured) && fabs(measured - expected) <= tol * fabs(expected);
    printf("%s: %s: %.10g vs %.10g (tol %g relative)\n", ok ? "PASS" : "FAIL", name, measured, expected, tol);
    if (!ok) check_failures++;
    return ok;
}

/* absolute tolerance check */
static inline int check_abs(const char *name, double measured, double expected, double tol)
{
    int ok = isfinite(measured) && fabs(measured - expected) <= tol;
    printf("%s: %s: %.10g vs %.10g (tol %g absolute)\n", ok ? "PASS" : "FAIL", name, measured, expected, tol);
    if (!ok) check_failures++;
    return ok;
}

/* measured in [lo, hi] */
static inline int check_range(const char *name, double measured, double lo, double hi)
{
    int ok = measured >= lo && measured <= hi;
    printf("%s: %s: %.10g vs [%g, %g] (tol range)\n", ok ? "PASS" : "FAIL", name, measured, lo, hi);
    if (!ok) check_failures++;
    return ok;
}

/* measured < bound */
static inline int check_below(const char *name, double measured, double bound)
{
    int ok = measured < bound;
    printf("%s: %s: %.10g vs < %g (tol bound)\n", ok ? "PASS" : "FAIL", name, measured, bound);
    if (!ok) check_failures++;
    return ok;
}

static inline int check_status(const char *name, dem_status got, dem_status want)
{
    int ok = got == want;
    printf("%s: %s: %s vs %s (tol exact)\n", ok ? "PASS" : "FAIL", name, dem_status_string(got),
           dem_status_string(want));
    if (!ok) check_failures++;
    return ok;
}

static inline int check_exit(void) { return check_failures ? 1 : 0; }

/* Abort the test program (not the library) on an unexpected error. */
#define TRY(w, call) do { dem_status s_ = (call); if (s_ != DEM_OK) { \
    printf("FAIL: %s:%d: %s: %s vs success (tol exact) [%s]\n", __FILE__, __LINE__, #call, \
           dem_status_string(s_), (w) ? dem_world_last_error(w) : ""); exit(1); } } while (0)

static inline dem_material test_material(double E, double nu, double mu, double mu_r, double e)
{
    dem_material m;
    memset(&m, 0, sizeof m);
    m.youngs_modulus = E; m.poisson_ratio = nu; m.friction = mu; m.rolling_friction = mu_r;
    m.restitution = e; m.damping = -1.0;
    return m;
}

static inline dem_world *test_world(dem_contact_law law, double dt, const double g[3], double half)
{
    dem_world *w = NULL;
    TRY(w, dem_world_create(&w));
    dem_config c;
    dem_config_default(&c);
    c.contact_law = law;
    c.dt = dt;
    for (int k = 0; k < 3; ++k) {
        c.gravity[k] = g ? g[k] : 0.0;
        c.domain_lo[k] = -half;
        c.domain_hi[k] = half;
    }
    TRY(w, dem_world_configure(w, &c));
    return w;
}

static inline dem_particle test_particle(double x, double y, double z, double vx, double vy, double vz,
                                  double a, double rho, int mat)
{
    dem_particle p;
    memset(&p, 0, sizeof p);
    p.id = -1;
    p.x[0] = x; p.x[1] = y; p.x[2] = z;
    p.v[0] = vx; p.v[1] = vy; p.v[2] = vz;
    p.radius = a; p.density = rho; p.material = mat;
    return p;
}

/* the fill tests' particles: diameter uniform in 1.6-2.4 mm, density
   normal about 2500 kg/m3 (sd 100) */
static inline dem_particle_template test_fill_template(int mid)
{
    dem_particle_template t;
    memset(&t, 0, sizeof t);
    t.diameter.kind = DEM_DIST_UNIFORM; t.diameter.a = 1.6e-3; t.diameter.b = 2.4e-3;
    t.density.kind = DEM_DIST_NORMAL; t.density.a = 2500; t.density.b = 100;
    t.material = mid;
    return t;
}

/* the fill tests' world: Hertz-Mindlin, dt 1e-6 s, one material (mid) */
static inline dem_world *test_fill_world(int *mid)
{
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-6, NULL, 0.2);
    dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
    TRY(w, dem_world_add_material(w, &m, mid));
    return w;
}

/* pairs of owned particles that overlap (all pairs: small sets only) */
static inline int test_overlapping_pairs(const dem_arrays *a)
{
    int bad = 0;
    for (size_t i = 0; i < a->n_owned; ++i)
        for (size_t j = i + 1; j < a->n_owned; ++j) {
            double d2 = 0;
            for (int k = 0; k < 3; ++k) { double d = a->x[3 * i + k] - a->x[3 * j + k]; d2 += d * d; }
            double s = a->radius[i] + a->radius[j];
            bad += d2 < s * s;
        }
    return bad;
}

/* keep filter of the fill tests: a processor of a decomposed set-up that
   keeps the slab s of the x-cuts cut[0..ncut-1] (s = 0: x < cut[0]; s:
   cut[s-1] <= x < cut[s]; s = ncut: x >= cut[ncut-1]) */
typedef struct { const double *cut; int ncut, slab; } test_slab;

static inline int test_keep_slab(const double x[3], void *user)
{
    const test_slab *s = (const test_slab *)user;
    int at = 0;
    while (at < s->ncut && x[0] >= s->cut[at]) ++at;
    return at == s->slab;
}

/* the slab's keep filter and its keep box (lo, hi: the rest of the box) */
static inline void test_set_keep_slab(dem_world *w, test_slab *s)
{
    TRY(w, dem_world_set_keep_filter(w, test_keep_slab, s));
    double lo[3] = {s->slab == 0 ? -1 : s->cut[s->slab - 1], -1, -1};
    double hi[3] = {s->slab == s->ncut ? 1 : s->cut[s->slab], 1, 1};
    TRY(w, dem_world_set_keep_box(w, lo, hi));
}

/* the worlds make(slab) of every slab of cut (keep-filtered fills) hold
   together exactly the unfiltered particles A (ids 0..n-1), bit for bit,
   each only its own slab's, and each counts all n inserted */
static inline void test_keep_slabs(const char *what, dem_world *(*make)(test_slab *), const double *cut,
                                   int ncut, const dem_arrays *A)
{
    size_t *at = (size_t *)malloc((A->n_owned + 1) * sizeof *at);
    for (size_t i = 0; i < A->n_owned; ++i)
        if (A->id[i] >= 0 && (size_t)A->id[i] < A->n_owned) at[A->id[i]] = i;
    size_t total = 0;
    int differ = 0, wrongSlab = 0;
    char name[200];
    for (int s = 0; s <= ncut; ++s) {
        test_slab slab = {cut, ncut, s};
        dem_world *w = make(&slab);
        dem_arrays B;
        TRY(w, dem_world_arrays(w, &B));
        total += B.n_owned;
        for (size_t i = 0; i < B.n_owned; ++i) {
            const int64_t id = B.id[i];
            if (id < 0 || id >= (int64_t)A->n_owned) { differ++; continue; }
            const size_t k = at[id];
            wrongSlab += !test_keep_slab(B.x + 3 * i, &slab);
            differ += memcmp(B.x + 3 * i, A->x + 3 * k, 3 * sizeof(double)) != 0
                      || B.radius[i] != A->radius[k] || B.density[i] != A->density[k];
        }
        dem_stats st;
        TRY(w, dem_world_stats(w, &st));
        snprintf(name, sizeof name, "%s keep filter: inserted count of a filtered world", what);
        check_abs(name, (double)st.inserted, (double)A->n_owned, 0);
        dem_world_destroy(&w);
    }
    free(at);
    snprintf(name, sizeof name, "%s keep filter: particles of the %d filtered worlds", what, ncut + 1);
    check_abs(name, (double)total, (double)A->n_owned, 0);
    snprintf(name, sizeof name, "%s keep filter: particles differing from the unfiltered ones (bit for bit)", what);
    check_abs(name, (double)differ, 0, 0);
    snprintf(name, sizeof name, "%s keep filter: particles in another world's slab", what);
    check_abs(name, (double)wrongSlab, 0, 0);
}

/* the world's own random stream is untouched by the fills in p (before
   particles): a random fill of 50 in [lo, hi] after them equals the same
   fill in the fresh world q (material mid) */
static inline void test_stream_untouched(const char *name, dem_world *p, dem_world *q, int mid, size_t before,
                                         const double lo[3], const double hi[3])
{
    dem_particle_template t = test_fill_template(mid);
    size_t got;
    TRY(p, dem_world_fill_box(p, lo, hi, NULL, NULL, 50, &t, &got));
    TRY(q, dem_world_fill_box(q, lo, hi, NULL, NULL, 50, &t, &got));
    dem_arrays P, Q;
    TRY(p, dem_world_arrays(p, &P));
    TRY(q, dem_world_arrays(q, &Q));
    int same = Q.n_owned == 50 && P.n_owned == before + 50
               && !memcmp(P.x + 3 * before, Q.x, 3 * 50 * sizeof(double));
    check_abs(name, (double)same, 1, 0);
}

#endif
