/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Randomised robustness test of the public C API (docs/demCore.md, Tests).
 *
 * Two twin worlds A and B receive the same sequence of valid calls; A also
 * receives malformed and extreme calls in between (NULL pointers, NaN,
 * +-Inf, denormals, zero/negative/huge sizes and counts, out-of-range ids,
 * indices and enum values, degenerate geometry, bad configurations and
 * materials, calls in a wrong order, garbage pack buffers, garbage,
 * truncated and missing state files).  Every rejected call must return a
 * status other than DEM_OK with a fresh, non-empty dem_world_last_error
 * (file:line: ...), and must leave A exactly as B: after each one the
 * counters and statistics are compared, and regularly every particle
 * (packed with its contact history) byte for byte.  Garbage that happens
 * to be acceptable (a corrupted state file or pack buffer that passes all
 * checks) is then applied to both.  Crashes, hangs, leaks and sanitizer
 * reports fail the test by themselves (check-sanitize).
 *
 * Reproducible: fixed seed, DEM_FUZZ_SEED=<n> overrides it and
 * DEM_FUZZ_ROUNDS=<n> the number of rounds; DEM_FUZZ_VERBOSE=1 prints
 * every distinct error message.  A failure prints the seed, the round and
 * the last calls. */
#define _POSIX_C_SOURCE 200809L
#include "check.h"

/* laws whose stiffness is youngs_modulus and whose damping is dimensionless */
static int hertz_law(int law)
{
    return law == DEM_CONTACT_HERTZ_MINDLIN || law == DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP;
}
#include <float.h>
#include <limits.h>
#include <stdint.h>
#include <unistd.h>

/*--- random numbers (splitmix64) -------------------------------------------*/
static uint64_t rs;
static uint64_t rnd(void)
{
    uint64_t z = (rs += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static size_t rn(size_t n) { return n ? (size_t)(rnd() % n) : 0; }
static double ru(void) { return (double)(rnd() >> 11) * 0x1.0p-53; }
static double rr(double a, double b) { return a + (b - a) * ru(); }
static int coin(int one_in) { return rn((size_t)one_in) == 0; }

/* malformed / extreme doubles */
static double bad_double(void)
{
    static const double v[] = {NAN, -NAN, INFINITY, -INFINITY, DBL_MAX, -DBL_MAX, 1e308, -1e308,
                               DBL_MIN, -DBL_MIN, 4.9e-324, -4.9e-324, 1e-310, 0.0, -0.0, -1.0,
                               1e200, -1e200, 1e-200, 1e30, -1e30};
    return v[rn(sizeof v / sizeof v[0])];
}
static double bad_positive(void) /* not a usable positive size */
{
    static const double v[] = {NAN, INFINITY, -INFINITY, 0.0, -0.0, -1.0, -1e-3, -DBL_MAX, 4.9e-324};
    return v[rn(sizeof v / sizeof v[0])];
}
static double bad_nonpositive(void) /* not > 0 and finite (denormals are valid here) */
{
    static const double v[] = {NAN, INFINITY, -INFINITY, 0.0, -0.0, -1.0, -1e-3, -DBL_MAX, -4.9e-324};
    return v[rn(sizeof v / sizeof v[0])];
}
static int bad_int(int n) /* out of [0, n) */
{
    static const int v[] = {-1, -2, INT_MIN, INT_MAX, INT_MIN + 1, 1000000};
    if (coin(3)) return n + (int)rn(3);
    return v[rn(sizeof v / sizeof v[0])];
}
static size_t huge_count(void) /* more particles/vertices than a world can hold */
{
    static const size_t v[] = {SIZE_MAX, SIZE_MAX / 2, SIZE_MAX / 3 + 1, SIZE_MAX / 24 + 1,
                               (size_t)INT_MAX + 1, (size_t)1 << 40, (size_t)1 << 62};
    return v[rn(sizeof v / sizeof v[0])];
}

/*--- bookkeeping ---------------------------------------------------------------*/
#define NCAT 160
static struct { const char *name; long calls, fails; } cat[NCAT];
static int ncat;
static long round_no;
static uint64_t seed;
static char last_ops[8][160];
static int nlast;
static int verbose;
static char seen[400][200];
static int nseen;

static int cat_id(const char *name)
{
    for (int i = 0; i < ncat; ++i) if (!strcmp(cat[i].name, name)) return i;
    if (ncat == NCAT) return NCAT - 1;
    cat[ncat].name = name;
    return ncat++;
}

static void note_op(const char *fmt, const char *what)
{
    snprintf(last_ops[nlast++ % 8], sizeof last_ops[0], fmt, what);
}

static void failure(const char *catname, const char *fmt, const char *a, const char *b)
{
    int c = cat_id(catname);
    cat[c].fails++;
    if (cat[c].fails > 3) return; /* details of the first few only */
    printf("# fuzz failure (seed %llu, round %ld) in %s: ", (unsigned long long)seed, round_no, catname);
    printf(fmt, a, b);
    printf("\n#   last calls:");
    for (int k = nlast > 8 ? nlast - 8 : 0; k < nlast; ++k) printf("\n#     %s", last_ops[k % 8]);
    printf("\n");
}

static void show_message(const char *e)
{
    if (!verbose || nseen >= 400) return;
    char key[200];
    snprintf(key, sizeof key, "%s", e);
    for (int k = 0; k < nseen; ++k) if (!strcmp(seen[k], key)) return;
    snprintf(seen[nseen++], sizeof seen[0], "%s", key);
    printf("# message: %s\n", e);
}

/*--- the twin worlds ----------------------------------------------------------*/
typedef struct {
    dem_world *a, *b;
    int law, nmat, nwalls, noutlets, ninlets, configured;
    double H;           /* domain [-H, H]^3 */
    int periodic[3];
    double dt;
    char dir[256];
    int nfile;
    int diverged;       /* A no longer equals B: start again with fresh worlds */
} fz;

static unsigned marker;
/* Put a unique message into A's error text (a rejected material look-up),
 * so that a rejected call that leaves the text unchanged is noticed. */
static void mark(dem_world *w)
{
    dem_material m;
    dem_world_material_get(w, -1 - (int)(++marker % 1000000000u), &m);
}

static int particle_total(dem_world *w) /* owned + ghosts, through pack */
{
    size_t sz;
    int n = (int)dem_world_count(w);
    while (dem_world_pack_particle(w, (size_t)n, NULL, &sz) == DEM_OK) ++n;
    return n;
}

/* Quick comparison: counters and statistics. */
static int same_quick(fz *F, const char *catname, const char *call)
{
    dem_stats sa, sb;
    memset(&sa, 0, sizeof sa); memset(&sb, 0, sizeof sb);
    dem_status s1 = dem_world_stats(F->a, &sa), s2 = dem_world_stats(F->b, &sb);
    int ok = s1 == DEM_OK && s2 == DEM_OK && dem_world_count(F->a) == dem_world_count(F->b) &&
             dem_world_step_count(F->a) == dem_world_step_count(F->b) &&
             memcmp(&(double){dem_world_time(F->a)}, &(double){dem_world_time(F->b)}, sizeof(double)) == 0 &&
             dem_world_reorder_count(F->a) == dem_world_reorder_count(F->b) &&
             memcmp(&sa, &sb, sizeof sa) == 0;
    if (!ok) {
        char d[300];
        snprintf(d, sizeof d, " [A: n %zu step %lld t %g reorders %lld ke %g ins %lld rem %lld pc %zu wc %zu ov %g;"
                 " B: n %zu step %lld t %g reorders %lld ke %g ins %lld rem %lld pc %zu wc %zu ov %g]",
                 dem_world_count(F->a), (long long)dem_world_step_count(F->a), dem_world_time(F->a),
                 (long long)dem_world_reorder_count(F->a), sa.kinetic_energy, (long long)sa.inserted,
                 (long long)sa.removed, sa.pair_contacts, sa.wall_contacts, sa.max_overlap_ratio,
                 dem_world_count(F->b), (long long)dem_world_step_count(F->b), dem_world_time(F->b),
                 (long long)dem_world_reorder_count(F->b), sb.kinetic_energy, (long long)sb.inserted,
                 (long long)sb.removed, sb.pair_contacts, sb.wall_contacts, sb.max_overlap_ratio);
        failure(catname, "world changed by %s%s (count/step/time/stats differ from the twin)", call, d);
               F->diverged = 1; }
    return ok;
}

/* Full comparison: every particle packed with its contacts, byte for byte. */
static int same_full(fz *F, const char *catname, const char *call)
{
    if (!same_quick(F, catname, call)) return 0;
    int na = particle_total(F->a), nb = particle_total(F->b);
    if (na != nb) { failure(catname, "particle totals differ after %s%s", call, ""); F->diverged = 1; return 0; }
    for (int i = 0; i < na; ++i) {
        size_t za = 0, zb = 0;
        dem_world_pack_particle(F->a, (size_t)i, NULL, &za);
        dem_world_pack_particle(F->b, (size_t)i, NULL, &zb);
        if (za != zb) { failure(catname, "pack size differs after %s%s", call, ""); F->diverged = 1; return 0; }
        char *ba = calloc(1, za), *bb = calloc(1, zb);
        dem_status s1 = dem_world_pack_particle(F->a, (size_t)i, ba, &za);
        dem_status s2 = dem_world_pack_particle(F->b, (size_t)i, bb, &zb);
        int ok = s1 == DEM_OK && s2 == DEM_OK && memcmp(ba, bb, za) == 0;
        free(ba); free(bb);
        if (!ok) { failure(catname, "particle state differs from the twin after %s%s", call, ""); F->diverged = 1; return 0; }
    }
    return 1;
}

/* A rejected call: status, fresh message with file:line, world unchanged. */
static void rejected(fz *F, const char *catname, const char *call, dem_status s, int world_given)
{
    int c = cat_id(catname);
    cat[c].calls++;
    note_op("bad: %s", call);
    if (s == DEM_OK) { failure(catname, "%s was accepted%s", call, ""); F->diverged = 1; return; }
    if ((int)s <= 0 || (int)s >= DEM_STATUS_COUNT) { failure(catname, "%s returned an unknown status%s", call, ""); return; }
    if (world_given) {
        const char *e = dem_world_last_error(F->a);
        char mk[64];
        snprintf(mk, sizeof mk, "material %d;", -1 - (int)(marker % 1000000000u));
        if (!e[0] || strstr(e, mk) || !strstr(e, ".c:")) {
            failure(catname, "%s: no fresh error message (\"%s\")", call, e);
            return;
        }
        show_message(e);
    }
    same_quick(F, catname, call);
}

#define BAD(catname, call) do { mark(F->a); dem_world *W = F->a; (void)W; \
    dem_status s_ = (call); rejected(F, catname, #call, s_, 1); } while (0)
/* NULL handle: status only (there is no handle to carry a message) */
#define BADNULL(catname, call) do { dem_world *W = NULL; (void)W; dem_status s_ = (call); \
    cat[cat_id(catname)].calls++; if (s_ == DEM_OK) failure(catname, "%s accepted a NULL handle%s", #call, ""); } while (0)

/* A valid call, made on both twins: same status; an error has a message. */
static void valid_result(fz *F, const char *catname, const char *call, dem_status sa, dem_status sb, int must_ok)
{
    int c = cat_id(catname);
    cat[c].calls++;
    note_op("ok:  %s", call);
    if (sa != sb) { failure(catname, "%s: twins returned different statuses (%s)", call, dem_status_string(sa));
                    F->diverged = 1; return; }
    if (must_ok && sa != DEM_OK) { failure(catname, "%s failed: %s", call, dem_world_last_error(F->a)); return; }
    if (sa != DEM_OK) {
        const char *e = dem_world_last_error(F->a);
        if (!e[0] || !strstr(e, ".c:")) failure(catname, "%s: error without message (%s)", call, e);
        else show_message(e);
    }
}
#define BOTH(catname, must_ok, call) do { dem_world *W = F->a; dem_status sa_ = (call); W = F->b; \
    dem_status sb_ = (call); valid_result(F, catname, #call, sa_, sb_, must_ok); } while (0)

/*--- valid building blocks --------------------------------------------------------*/
static dem_material good_material(int law)
{
    dem_material m;
    memset(&m, 0, sizeof m);
    m.youngs_modulus = rr(5e6, 5e7);
    m.poisson_ratio = rr(0.0, 0.45);
    m.stiffness_n = rr(200, 2000);
    m.stiffness_t = coin(2) ? 0.0 : rr(50, 500);
    m.friction = rr(0, 0.6);
    m.rolling_friction = coin(2) ? 0.0 : rr(0, 3e-5);
    /* Hertz-Mindlin: mostly a damping; a restitution is mapped to a damping
       by bisection over ODE solutions (~0.1 s, again after each restore) */
    if (!hertz_law(law) || coin(40)) { m.restitution = rr(0.3, 1.0); m.damping = -1; }
    else { m.restitution = -1; m.damping = rr(0.0, 0.4); }
    if (!hertz_law(law) && coin(4)) { m.restitution = -1; m.damping = rr(0, 1e-3); }
    return m;
}

static dem_distribution good_dist(double lo, double hi, double *store)
{
    dem_distribution d;
    memset(&d, 0, sizeof d);
    switch (rn(4)) {
    case 0: d.kind = DEM_DIST_FIXED; d.a = rr(lo, hi); break;
    case 1: d.kind = DEM_DIST_UNIFORM; d.a = lo; d.b = rr(lo, hi); break;
    case 2: d.kind = DEM_DIST_NORMAL; d.a = 0.5 * (lo + hi); d.b = (hi - lo) / 8; break;
    default:
        d.kind = DEM_DIST_DISCRETE; d.n = 1 + rn(3);
        for (size_t k = 0; k < d.n; ++k) { store[k] = rr(lo, hi); store[4 + k] = rr(0.1, 1); }
        d.values = store; d.weights = store + 4;
    }
    return d;
}

static dem_particle_template good_template(fz *F, double *store)
{
    dem_particle_template t;
    memset(&t, 0, sizeof t);
    t.diameter = good_dist(1e-3, 2e-3, store);
    t.density = good_dist(1500, 3000, store + 8);
    t.material = (int)rn((size_t)F->nmat);
    for (int k = 0; k < 3; ++k) t.velocity[k] = coin(2) ? 0 : rr(-0.2, 0.2);
    return t;
}

static dem_particle good_particle(fz *F)
{
    dem_particle p;
    memset(&p, 0, sizeof p);
    p.id = coin(4) ? (int64_t)(1000000 + rn(1000000)) : -1;
    for (int k = 0; k < 3; ++k) { p.x[k] = rr(-0.8, 0.8) * F->H; p.v[k] = rr(-0.1, 0.1); p.omega[k] = rr(-10, 10); }
    p.radius = rr(5e-4, 1e-3);
    p.density = rr(1500, 3000);
    p.material = (int)rn((size_t)F->nmat);
    return p;
}

static dem_config good_config(fz *F, int may_change_geometry)
{
    dem_config c;
    dem_config_default(&c);
    if (!F->configured && !may_change_geometry) { /* keep the default geometry and law */
        F->dt = rr(2e-7, 1e-6);
        c.dt = F->dt;
        c.gravity[0] = rr(-1, 1);
        return c;
    }
    if (may_change_geometry) {
        F->law = (int)rn(DEM_CONTACT_LAW_COUNT);
        F->H = rr(0.01, 0.03);
        for (int k = 0; k < 3; ++k) F->periodic[k] = coin(4);
    }
    c.contact_law = (dem_contact_law)F->law;
    F->dt = rr(2e-7, 1e-6);
    c.dt = F->dt;
    for (int k = 0; k < 3; ++k) {
        c.gravity[k] = k == 2 ? -9.81 : rr(-1, 1);
        c.domain_lo[k] = -F->H; c.domain_hi[k] = F->H;
        c.periodic[k] = F->periodic[k];
    }
    c.seed = 7;
    c.spatial_sort = coin(4) ? 0 : 1;
    if (F->law == DEM_CONTACT_LINEAR_SPRING_DASHPOT) c.max_dt_fraction = 0.2;
    return c;
}

/*--- world (re)creation ---------------------------------------------------------*/
static void log_sink(dem_log_level l, const char *msg, void *user) { (void)l; (void)msg; ++*(long *)user; }
static long nlog;

static void fresh(fz *F)
{
    dem_world_destroy(&F->a);
    dem_world_destroy(&F->b);
    if (dem_world_create(&F->a) || dem_world_create(&F->b)) { printf("FAIL: fuzz: create (tol exact)\n"); exit(1); }
    dem_world_set_logger(F->a, log_sink, &nlog);
    dem_world_set_logger(F->b, log_sink, &nlog);
    F->law = DEM_CONTACT_HERTZ_MINDLIN; /* the defaults of dem_config_default */
    F->H = 0.5; F->dt = 1e-6;
    F->periodic[0] = F->periodic[1] = F->periodic[2] = 0;
    F->nmat = F->nwalls = F->noutlets = F->ninlets = 0;
    F->configured = 0;
    F->diverged = 0;
    note_op("%s", "fresh worlds");
}

/*--- malformed inputs -------------------------------------------------------------*/
static void bad_config(fz *F)
{
    dem_config c = good_config(F, 0);
    switch (rn(12)) {
    case 0: c.contact_law = (dem_contact_law)bad_int(DEM_CONTACT_LAW_COUNT); break;
    case 1: c.dt = bad_nonpositive(); break;
    case 2: c.gravity[rn(3)] = coin(2) ? NAN : (coin(2) ? INFINITY : -INFINITY); break;
    case 3: { int k = (int)rn(3); double t = c.domain_lo[k]; c.domain_lo[k] = c.domain_hi[k]; c.domain_hi[k] = t; break; }
    case 4: c.domain_lo[rn(3)] = coin(2) ? NAN : -INFINITY; break;
    case 5: c.domain_hi[rn(3)] = coin(2) ? NAN : INFINITY; break;
    case 6: { int k = (int)rn(3); c.domain_lo[k] = -DBL_MAX; c.domain_hi[k] = DBL_MAX; break; }
    case 7: c.skin = coin(2) ? NAN : INFINITY; break;
    case 8: c.max_dt_fraction = coin(2) ? NAN : -1.0 * rn(2); break;
    case 9: c.max_overlap_ratio = coin(2) ? NAN : -1.0 * rn(2); break;
    case 10: c.impact_speed = coin(2) ? NAN : (coin(2) ? INFINITY : -1.0); break;
    default: { int k = (int)rn(3); c.domain_hi[k] = c.domain_lo[k]; break; }
    }
    BAD("configure: bad field", dem_world_configure(W, &c));
}

static void bad_material(fz *F)
{
    dem_material m = good_material(F->law);
    switch (rn(10)) {
    case 0: m.poisson_ratio = coin(2) ? bad_double() : (coin(2) ? 0.5 : -1e-9);
            if (m.poisson_ratio >= 0 && m.poisson_ratio < 0.5) m.poisson_ratio = NAN;
            break;
    case 1: m.friction = coin(2) ? NAN : (coin(2) ? INFINITY : -1e-3); break;
    case 2: m.rolling_friction = coin(2) ? NAN : (coin(2) ? INFINITY : -1e-6); break;
    case 3: m.restitution = coin(2) ? NAN : (coin(2) ? 1.0000001 : 0.0); m.damping = -1; break;
    case 4: m.restitution = 0.5; m.damping = 0.1; break;                /* both given */
    case 5: m.restitution = -1; m.damping = coin(2) ? -1 : (coin(2) ? NAN : INFINITY); break; /* neither */
    case 6: { double b = bad_nonpositive();
              if (b == INFINITY) b = -INFINITY;   /* DEM_RIGID is valid */
              if (hertz_law(F->law)) m.youngs_modulus = b;
              else m.stiffness_n = b;
            } break;
    /* (+INFINITY is DEM_RIGID, a valid wall material) */
    case 7: m.youngs_modulus = coin(2) ? NAN : -INFINITY; break;
    case 8: m.stiffness_t = coin(2) ? NAN : -INFINITY; break;
    default: m.stiffness_n = coin(2) ? NAN : -INFINITY; break;
    }
    int id = -7;
    if (coin(3)) BAD("set_pair: bad material", dem_world_set_pair(W, (int)rn((size_t)F->nmat + 1), (int)rn((size_t)F->nmat + 1), &m));
    else BAD("add_material: bad field", dem_world_add_material(W, &m, coin(2) ? &id : NULL));
    if (id != -7) failure("add_material: bad field", "material id written by a rejected call%s%s", "", "");
}

static void bad_particles(fz *F)
{
    size_t n = 1 + rn(4);
    dem_particle p[4];
    for (size_t i = 0; i < n; ++i) p[i] = good_particle(F);
    dem_particle *q = &p[rn(n)];
    switch (F->nmat == 0 ? 9 : rn(9)) {
    case 0: q->radius = bad_positive(); break;
    case 1: q->density = bad_positive(); break;
    case 2: q->material = bad_int(F->nmat); break;
    case 3: q->x[rn(3)] = coin(2) ? NAN : (coin(2) ? INFINITY : -INFINITY); break;
    case 4: q->v[rn(3)] = coin(2) ? NAN : INFINITY; break;
    case 5: q->omega[rn(3)] = coin(2) ? NAN : -INFINITY; break;
    case 6: /* mass or moment of inertia not representable */
        if (coin(2)) { q->radius = 1e-200; } else { q->radius = 1e200; q->density = coin(2) ? 1e100 : 1.0; }
        break;
    case 7: q->id = INT64_MAX; break;
    case 8: /* huge count with a short buffer, or NULL */
        if (coin(2)) { BAD("add_particles: huge n", dem_world_add_particles(W, huge_count(), p)); return; }
        BAD("add_particles: NULL", dem_world_add_particles(W, n, NULL));
        return;
    default: break; /* no materials yet: wrong call order */
    }
    BAD(F->nmat ? "add_particles: bad particle" : "add_particles: before materials", dem_world_add_particles(W, n, p));
}

static dem_distribution bad_dist(double *store)
{
    dem_distribution d;
    memset(&d, 0, sizeof d);
    switch (rn(9)) {
    case 0: d.kind = (dem_dist_kind)bad_int(4); d.a = 1e-3; d.b = 2e-3; break;
    case 1: d.kind = DEM_DIST_FIXED; d.a = bad_positive(); break;
    case 2: d.kind = DEM_DIST_FIXED; d.a = coin(2) ? INFINITY : NAN; break;
    case 3: d.kind = DEM_DIST_UNIFORM; d.a = 2e-3; d.b = coin(2) ? 1e-3 : (coin(2) ? NAN : INFINITY); break;
    case 4: d.kind = DEM_DIST_NORMAL; d.a = 1e-3; d.b = coin(2) ? 1e-3 : (coin(2) ? NAN : -1e-4); break;
    case 5: d.kind = DEM_DIST_DISCRETE; d.n = coin(2) ? 0 : 2; d.values = coin(2) ? NULL : store; d.weights = NULL; break;
    case 6: d.kind = DEM_DIST_DISCRETE; d.n = 2; store[0] = 1e-3; store[1] = bad_positive();
            store[4] = 1; store[5] = 1; d.values = store; d.weights = store + 4; break;
    case 7: d.kind = DEM_DIST_DISCRETE; d.n = 2; store[0] = 1e-3; store[1] = 2e-3;
            store[4] = coin(2) ? 0.0 : -1.0; store[5] = coin(2) ? 0.0 : NAN; d.values = store; d.weights = store + 4; break;
    default: d.kind = DEM_DIST_DISCRETE; d.n = 2; store[0] = 1e-3; store[1] = 2e-3;
             store[4] = DBL_MAX; store[5] = coin(2) ? DBL_MAX : INFINITY; d.values = store; d.weights = store + 4; break;
    }
    return d;
}

static void bad_template(fz *F, dem_particle_template *t, double *store)
{
    switch (F->nmat == 0 ? 0 : rn(5)) {
    case 0: t->material = bad_int(F->nmat); break;
    case 1: t->velocity[rn(3)] = coin(2) ? NAN : INFINITY; break;
    case 2: t->diameter = bad_dist(store); break;
    case 3: t->density = bad_dist(store); break;
    default: /* diameter and density that give no representable mass */
        t->diameter.kind = DEM_DIST_FIXED; t->density.kind = DEM_DIST_FIXED;
        if (coin(2)) { t->diameter.a = 1e-120; t->density.a = 1e-300; }
        else { t->diameter.a = 1e120; t->density.a = 1e100; }
    }
}

static void bad_fill(fz *F)
{
    double store[16];
    dem_particle_template t = F->nmat ? good_template(F, store) : (dem_particle_template){0};
    double lo[3], hi[3], base[3] = {0, 0, -F->H / 2}, axis[3] = {0, 0, 1}, R = F->H / 2, L = F->H;
    for (int k = 0; k < 3; ++k) { lo[k] = -F->H / 2; hi[k] = F->H / 2; }
    size_t n = 1 + rn(5), got = 12345;
    int cyl = coin(3), what = (int)rn(6);
    switch (what) {
    case 0: bad_template(F, &t, store); break;
    case 1: if (cyl) { axis[0] = axis[1] = axis[2] = coin(2) ? 0.0 : (coin(2) ? NAN : 1e-320); }
            else { int k = (int)rn(3); double s = lo[k]; lo[k] = hi[k]; hi[k] = s; } break;
    case 2: if (cyl) { if (coin(2)) R = bad_positive(); else L = bad_positive(); }
            else { lo[rn(3)] = coin(2) ? NAN : -INFINITY; } break;
    case 3: if (cyl) { base[rn(3)] = coin(2) ? NAN : INFINITY; }
            else { lo[0] = -DBL_MAX; hi[0] = DBL_MAX; } break;
    case 4: n = huge_count(); break;
    default: if (cyl) { R = coin(2) ? DBL_MAX : 1e300; L = coin(2) ? 1e300 : INFINITY; }
             else { hi[rn(3)] = coin(2) ? NAN : INFINITY; } break;
    }
    if (F->nmat == 0 && what != 0) bad_template(F, &t, store);
    if (coin(12)) {
        int k = 1 + (int)rn(3);
        if (cyl) BAD("fill_cylinder: NULL", dem_world_fill_cylinder(W, k & 1 ? NULL : base, k & 2 ? NULL : axis, R, L, n, NULL, &got));
        else BAD("fill_box: NULL", dem_world_fill_box(W, k & 1 ? NULL : lo, k & 2 ? NULL : hi, NULL, NULL, n, coin(2) ? NULL : &t, &got));
        return;
    }
    /* huge but finite regions are valid; a fill may also end with DEM_ERR_FULL
       after placing some: then the twin gets the same call */
    size_t *gp = coin(2) ? &got : NULL, got_b = 12345, *gpb = gp ? &got_b : NULL;
    mark(F->a);
    dem_status sa = cyl ? dem_world_fill_cylinder(F->a, base, axis, R, L, n, &t, gp)
                        : dem_world_fill_box(F->a, lo, hi, NULL, NULL, n, &t, gp);
    if (sa == DEM_OK || sa == DEM_ERR_FULL) {
        dem_status sb = cyl ? dem_world_fill_cylinder(F->b, base, axis, R, L, n, &t, gpb)
                            : dem_world_fill_box(F->b, lo, hi, NULL, NULL, n, &t, gpb);
        valid_result(F, "fill: extreme but valid", "dem_world_fill_*(extreme)", sa, sb, 0);
        if (gp && got != got_b) failure("fill: extreme but valid", "twins placed different numbers%s%s", "", "");
        return;
    }
    rejected(F, cyl ? "fill_cylinder: bad input" : "fill_box: bad input", "dem_world_fill_*(bad)", sa, 1);
    if (got != 12345 && got != 0) failure("fill: bad input", "rejected fill reports %s%s placed particles", "", "");
}

static void bad_walls(fz *F)
{
    double p[3] = {0, 0, -F->H}, nrm[3] = {0, 0, 1}, vel[3] = {0, 0, 0};
    int mat = (int)rn((size_t)F->nmat), id = -7, what = (int)rn(12);
    switch (what) {
    case 0: mat = bad_int(F->nmat); break;
    case 1: nrm[0] = nrm[1] = nrm[2] = coin(2) ? 0.0 : 4.9e-324; break;
    case 2: nrm[rn(3)] = coin(2) ? NAN : INFINITY; break;
    case 3: nrm[rn(3)] = coin(2) ? 1e200 : DBL_MAX; break;
    case 4: p[rn(3)] = coin(2) ? NAN : -INFINITY; break;
    case 5: vel[rn(3)] = coin(2) ? NAN : INFINITY; break;
    case 6: { int k = 1 + (int)rn(3);
              BAD("add_plane: NULL", dem_world_add_plane(W, k & 1 ? NULL : p, k & 2 ? NULL : nrm, mat, vel, &id));

              return; }
    case 7: BAD("set_wall_velocity: bad id", dem_world_set_wall_velocity(W, bad_int(F->nwalls), vel)); return;
    case 8: if (F->nwalls) { vel[rn(3)] = coin(2) ? NAN : -INFINITY;
                BAD("set_wall_velocity: bad velocity", dem_world_set_wall_velocity(W, (int)rn((size_t)F->nwalls), vel)); return; }
            mat = bad_int(F->nmat); break;
    default: { /* triangle meshes */
        double v[12] = {-F->H, -F->H, -F->H / 2, F->H, -F->H, -F->H / 2, F->H, F->H, -F->H / 2, -F->H, F->H, -F->H / 2};
        int tri[6] = {0, 1, 2, 0, 2, 3};
        size_t nv = 4, nt = 2;
        const double *vp = v; const int *tp = tri;
        switch (rn(10)) {
        case 0: tri[rn(6)] = coin(2) ? -1 : (coin(2) ? 4 : INT_MAX); break;
        case 1: tri[1] = tri[0]; break;                                   /* repeated vertex */
        case 2: v[3] = v[0]; v[4] = v[1]; v[5] = v[2]; break;             /* coincident vertices */
        case 3: v[6] = 0.5 * (v[0] + v[3]); v[7] = 0.5 * (v[1] + v[4]); v[8] = 0.5 * (v[2] + v[5]); break; /* collinear */
        case 4: v[rn(12)] = coin(2) ? NAN : INFINITY; break;
        case 5: for (int k = 0; k < 12; ++k) v[k] *= 1e200; break;       /* normal not representable */
        case 6: if (coin(2)) nv = huge_count(); else nt = huge_count(); break;
        case 7: if (coin(2)) { nt = 0; } else { vp = coin(2) ? NULL : v; tp = vp ? NULL : tri; } break;
        case 8: nv = 0; break;
        default: mat = bad_int(F->nmat); break;
        }
        BAD("add_trimesh: bad input", dem_world_add_trimesh(W, nv, vp, nt, tp, mat, vel, coin(2) ? &id : NULL));
        if (id != -7) failure("add_trimesh: bad input", "wall id written by a rejected call%s%s", "", "");
        return;
    }
    }
    if (F->nmat == 0) mat = bad_int(0);
    BAD("add_plane: bad input", dem_world_add_plane(W, p, nrm, mat, coin(2) || what == 5 ? vel : NULL, &id));
    if (id != -7) failure("add_plane: bad input", "wall id written by a rejected call%s%s", "", "");
}

static void bad_inlet_outlet(fz *F)
{
    double store[16];
    dem_particle_template t = F->nmat ? good_template(F, store) : (dem_particle_template){0};
    double h = F->H / 4, z = F->H / 2;
    double poly[15] = {-h, -h, z, h, -h, z, h, h, z, -h, h, z, 0, 0, z};
    size_t nv = 4;
    dem_rate_kind kind = DEM_RATE_NUMBER;
    double rate = 1000, t0 = 0, t1 = 1;
    int id = -7;
    switch (F->nmat == 0 ? 0 : rn(16)) {
    case 0: bad_template(F, &t, store); break;
    case 1: nv = rn(3); break;
    case 2: kind = (dem_rate_kind)bad_int(2); break;
    case 3: rate = coin(2) ? NAN : (coin(2) ? INFINITY : -1.0); break;
    case 4: t0 = 1; t1 = coin(2) ? 0 : NAN; break;
    case 5: poly[rn(12)] = coin(2) ? NAN : INFINITY; break;
    case 6: for (int k = 0; k < 12; k += 3) { poly[k] = 0; } break;      /* zero area (a line) */
    case 7: for (int k = 0; k < 15; ++k) poly[k] *= 1e200; break;        /* area not representable */
    case 8: nv = huge_count(); break;
    case 9: t.diameter.kind = DEM_DIST_DISCRETE; t.diameter.n = 33; {
                static double v[40], wt[40];
                for (int k = 0; k < 40; ++k) { v[k] = 1e-3; wt[k] = 1; }
                t.diameter.values = v; t.diameter.weights = wt; } break;
    case 10: BAD("add_inlet: NULL", dem_world_add_inlet(W, nv, NULL, kind, rate, t0, t1, coin(2) ? &t : NULL, &id)); return;
    case 11: { double pt[3] = {0, 0, 0}, nn[3] = {0, 0, 0};
               if (coin(2)) nn[rn(3)] = coin(2) ? NAN : INFINITY; else if (coin(2)) { nn[2] = 1; pt[rn(3)] = NAN; }
               if (coin(6)) BAD("add_outlet_plane: NULL", dem_world_add_outlet_plane(W, coin(2) ? NULL : pt, NULL, &id));
               else BAD("add_outlet_plane: bad input", dem_world_add_outlet_plane(W, pt, nn, &id));
               return; }
    case 12: { double lo[3] = {-h, -h, -h}, hi[3] = {h, h, h};
               int k = (int)rn(3);
               if (coin(2)) { lo[k] = hi[k]; } else if (coin(2)) lo[k] = NAN; else hi[k] = NAN;
               if (coin(6)) BAD("add_outlet_box: NULL", dem_world_add_outlet_box(W, NULL, coin(2) ? NULL : hi, &id));
               else BAD("add_outlet_box: bad input", dem_world_add_outlet_box(W, lo, hi, &id));
               return; }
    case 13: { int64_t cnt; double mass;
               BAD("outlet_totals: bad id", dem_world_outlet_totals(W, bad_int(F->noutlets), &cnt, &mass)); return; }
    case 14: { const dem_removed_record *r;
               BAD("removed_records: NULL", dem_world_removed_records(W, coin(2) ? NULL : &r, NULL));
               return; }
    default: rate = coin(2) ? 1e300 : DBL_MAX; t.diameter.kind = DEM_DIST_FIXED; t.diameter.a = 1e-150;
             t.density.kind = DEM_DIST_FIXED; t.density.a = 1e-100; break; /* mass 0: infinitely many per kg */
    }
    BAD("add_inlet: bad input", dem_world_add_inlet(W, nv, poly, kind, rate, t0, t1, &t, &id));
    if (id != -7) failure("add_inlet: bad input", "inlet id written by a rejected call%s%s", "", "");
}

static void bad_misc(fz *F)
{
    size_t n = dem_world_count(F->a);
    switch (rn(14)) {
    case 0: BAD("step: nsteps < 0", dem_world_step(W, coin(2) ? -1 : (coin(2) ? INT64_MIN : -(int64_t)rn(1000) - 1))); break;
    case 1: if (dem_world_step_count(F->a) > 0) BAD("step: step counter overflow", dem_world_step(W, INT64_MAX));
            else BAD("step: nsteps < 0", dem_world_step(W, -2));
            break;
    case 2: BAD("remove_particle: bad index", dem_world_remove_particle(W, coin(2) ? n + rn(3) : SIZE_MAX - rn(3), -1)); break;
    case 3: if (n) BAD("remove_particle: bad outlet", dem_world_remove_particle(W, rn(n), bad_int(F->noutlets) < -1 ? INT_MIN : -2 - (int)rn(5)));
            else BAD("remove_particle: bad index", dem_world_remove_particle(W, 0, -1));
            break;
    case 4: { dem_material m; BAD("material_get: bad id", dem_world_material_get(W, bad_int(F->nmat), &m)); break; }
    case 5: BAD("material_get: NULL", dem_world_material_get(W, 0, NULL)); break;
    case 6: BAD("stats: NULL", dem_world_stats(W, NULL)); break;
    case 7: BAD("arrays: NULL", dem_world_arrays(W, NULL)); break;
    case 8: BAD("contact_time: NULL", dem_world_contact_time(W, 1.0, NULL)); break;
    case 9: { size_t sz = 0; char buf[8];
              if (coin(2)) BAD("pack: bad index", dem_world_pack_particle(W, n + 50 + rn(3), coin(2) ? NULL : buf, &sz));
              else BAD("pack: NULL size", dem_world_pack_particle(W, 0, NULL, NULL));
              break; }
    case 10: if (n) { size_t sz = 0; dem_world_pack_particle(F->a, 0, NULL, &sz);
                      char *buf = malloc(sz); size_t small = sz - 1 - rn(sz - 1);
                      BAD("pack: buffer too small", dem_world_pack_particle(W, 0, buf, &small)); free(buf); }
             else BAD("pack: bad index", dem_world_pack_particle(W, (size_t)particle_total(F->a), NULL, &(size_t){0}));
             break;
    case 11: BAD("save: NULL or bad path", dem_world_save(W, coin(3) ? NULL : (coin(2) ? "/nonexistent-dir/x/state" : F->dir)));
             break;
    case 12: { dem_contact_law law = DEM_CONTACT_LAW_COUNT;
               const char *names[] = {NULL, "", "hooke", "HertzMindlin", "hertzMindlin ", "linearSpringDashpotX"};
               dem_status s = dem_contact_law_from_name(names[rn(6)], coin(4) ? NULL : &law);
               int c = cat_id("contact_law_from_name: bad name"); cat[c].calls++;
               if (s == DEM_OK || law != DEM_CONTACT_LAW_COUNT) failure("contact_law_from_name: bad name", "accepted%s%s", "", "");
               const char *nm = dem_contact_law_name((dem_contact_law)bad_int(DEM_CONTACT_LAW_COUNT));
               const char *ss = dem_status_string((dem_status)bad_int(DEM_STATUS_COUNT));
               if (nm != NULL || !ss || strcmp(ss, "unknown status"))
                   failure("contact_law_from_name: bad name", "law name/status string of an invalid value%s%s", "", "");
               break; }
    default: { /* configure changes that need an empty world */
        if (n == 0) { BAD("configure: NULL", dem_world_configure(W, NULL)); break; }
        dem_config c = good_config(F, 0);
        switch (rn(4)) {
        case 0: c.contact_law = (dem_contact_law)((F->law + 1) % DEM_CONTACT_LAW_COUNT); break;
        case 1: c.domain_hi[rn(3)] *= 2; break;
        case 2: c.periodic[rn(3)] ^= 1; break;
        default: c.skin = 1e-3 + 1e-4 * (double)rn(10); break;
        }
        BAD("configure: state change with particles", dem_world_configure(W, &c));
    }
    }
}

static void null_handle_calls(void)
{
    dem_config c; dem_config_default(&c);
    dem_material m; memset(&m, 0, sizeof m);
    dem_particle p; memset(&p, 0, sizeof p);
    double x[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    int id; size_t sz;
    BADNULL("NULL handle", dem_world_create(NULL));
    BADNULL("NULL handle", dem_world_configure(W, &c));
    BADNULL("NULL handle", dem_world_add_material(W, &m, &id));
    BADNULL("NULL handle", dem_world_set_pair(W, 0, 0, &m));
    BADNULL("NULL handle", dem_world_material_get(W, 0, &m));
    BADNULL("NULL handle", dem_world_add_particles(W, 1, &p));
    BADNULL("NULL handle", dem_world_remove_particle(W, 0, -1));
    BADNULL("NULL handle", dem_world_arrays(W, &(dem_arrays){0}));
    BADNULL("NULL handle", dem_world_step(W, 1));
    BADNULL("NULL handle", dem_world_contact_time(W, 1.0, &(double){0}));
    BADNULL("NULL handle", dem_world_add_plane(W, x, nz, 0, NULL, &id));
    BADNULL("NULL handle", dem_world_add_trimesh(W, 0, NULL, 0, NULL, 0, NULL, &id));
    BADNULL("NULL handle", dem_world_set_wall_velocity(W, 0, x));
    BADNULL("NULL handle", dem_world_fill_box(W, x, nz, NULL, NULL, 1, NULL, &sz));
    BADNULL("NULL handle", dem_world_fill_cylinder(W, x, nz, 1, 1, 1, NULL, &sz));
    BADNULL("NULL handle", dem_world_add_inlet(W, 3, x, DEM_RATE_NUMBER, 1, 0, 1, NULL, &id));
    BADNULL("NULL handle", dem_world_add_outlet_plane(W, x, nz, &id));
    BADNULL("NULL handle", dem_world_add_outlet_box(W, x, nz, &id));
    BADNULL("NULL handle", dem_world_add_outlet(W, &id));
    BADNULL("NULL handle", dem_world_outlet_totals(W, 0, NULL, NULL));
    BADNULL("NULL handle", dem_world_removed_records(W, &(const dem_removed_record *){0}, &sz));
    BADNULL("NULL handle", dem_world_stats(W, &(dem_stats){0}));
    BADNULL("NULL handle", dem_world_memory(W, &sz, &sz));
    BADNULL("NULL handle", dem_world_particle_contacts(W, NULL, NULL));
    BADNULL("NULL handle", dem_world_save(W, "x"));
    BADNULL("NULL handle", dem_world_restore(W, "x"));
    BADNULL("NULL handle", dem_world_pack_particle(W, 0, NULL, &sz));
    BADNULL("NULL handle", dem_world_unpack_particle(W, x, sizeof x, 0));
    BADNULL("NULL handle", dem_world_clear_ghosts(W));
    /* the void and query functions accept NULL */
    dem_world *nw = NULL;
    dem_world_destroy(NULL); dem_world_destroy(&nw);
    dem_world_set_logger(NULL, NULL, NULL);
    dem_world_clear_removed_records(NULL);
    dem_config_default(NULL);
    int ok = dem_world_count(NULL) == 0 && dem_world_time(NULL) == 0 && dem_world_step_count(NULL) == 0 &&
             dem_world_reorder_count(NULL) == 0 && !strcmp(dem_world_last_error(NULL), "");
    if (!ok) failure("NULL handle", "query functions on a NULL handle%s%s", "", "");
}

/*--- garbage pack buffers and state files -------------------------------------------*/
static void corrupt(unsigned char *b, size_t n)
{
    if (n == 0) return;
    int times = 1 + (int)rn(3);
    for (int t = 0; t < times; ++t) {
        switch (rn(4)) {
        case 0: b[rn(n)] ^= (unsigned char)(1u << rn(8)); break;
        case 1: if (n >= 8) { double d = bad_double(); memcpy(b + 8 * rn(n / 8), &d, 8); } break;
        case 2: if (n >= 4) { static const int32_t v[] = {-1, INT32_MIN, INT32_MAX, 1 << 30, 27, 3, 2};
                               memcpy(b + 4 * rn(n / 4), &v[rn(7)], 4); } break;
        default: if (n >= 8) { static const uint64_t v[] = {UINT64_MAX, (uint64_t)1 << 40, (uint64_t)1 << 32,
                                                            (uint64_t)INT64_MAX, 1000000007u};
                               memcpy(b + 8 * rn(n / 8), &v[rn(5)], 8); } break;
        }
    }
}

static void garbage_unpack(fz *F)
{
    int ghost = (int)rn(2);
    size_t n = dem_world_count(F->a), sz = 0;
    unsigned char *buf = NULL;
    const char *kind;
    if (n && coin(2)) { /* a real packed particle, corrupted */
        size_t i = rn(n);
        dem_world_pack_particle(F->a, i, NULL, &sz);
        buf = malloc(sz);
        dem_world_pack_particle(F->a, i, buf, &sz);
        if (coin(3)) { sz = rn(sz); kind = "unpack: truncated buffer"; }
        else { corrupt(buf, sz); kind = "unpack: corrupted buffer (may be valid)"; }
    } else {
        sz = rn(400);
        buf = malloc(sz + 1);
        for (size_t k = 0; k < sz; ++k) buf[k] = (unsigned char)rnd();
        if (sz >= 4 && coin(2)) { uint32_t mg = 0x444d5032u; memcpy(buf, &mg, 4); }
        kind = "unpack: random bytes";
    }
    if (coin(10)) { BAD("unpack: NULL buffer", dem_world_unpack_particle(W, NULL, sz, ghost)); free(buf); return; }
    if (strstr(kind, "may be valid")) {
        mark(F->a);
        dem_status s = dem_world_unpack_particle(F->a, buf, sz, ghost);
        if (s == DEM_OK) { /* acceptable after all: the twin gets it too */
            dem_status s2 = dem_world_unpack_particle(F->b, buf, sz, ghost);
            valid_result(F, "unpack: corrupted buffer accepted", "dem_world_unpack_particle(garbage)", s, s2, 1);
        } else rejected(F, kind, "dem_world_unpack_particle(corrupted)", s, 1);
    } else {
        BAD(kind, dem_world_unpack_particle(W, buf, sz, ghost));
    }
    free(buf);
}

static unsigned char *read_all(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, len = 0;
    unsigned char *b = malloc(cap);
    size_t k;
    while ((k = fread(b + len, 1, cap - len, f)) > 0) {
        len += k;
        if (len == cap) { cap *= 2; b = realloc(b, cap); }
    }
    fclose(f);
    *n = len;
    return b;
}

static void write_all(const char *path, const unsigned char *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) return;
    if (n) fwrite(b, 1, n, f);
    fclose(f);
}

/* A few calls on a world the fuzzer knows little about (restored from a
 * corrupted file, or after a garbage unpack): same results on both. */
static void exercise(fz *F)
{
    size_t n = dem_world_count(F->a);
    int64_t k = 1 + (int64_t)rn(5);
    BOTH("exercise", 0, dem_world_step(W, k));
    dem_stats s;
    BOTH("exercise", 1, dem_world_stats(W, &s));
    double tc;
    double v = rr(0, 2);
    BOTH("exercise", 0, dem_world_contact_time(W, v, &tc));
    n = dem_world_count(F->a) > n ? dem_world_count(F->a) : n;
    int *c = calloc(n + 1, sizeof(int));
    double *f = calloc(3 * n + 3, sizeof(double));
    BOTH("exercise", 0, dem_world_particle_contacts(W, c, f));
    free(c); free(f);
    if (dem_world_count(F->a)) BOTH("exercise", 1, dem_world_remove_particle(W, 0, -1));
    BOTH("exercise", 0, dem_world_step(W, 1));
    BOTH("exercise", 1, dem_world_clear_ghosts(W));
    same_full(F, "twin comparison", "exercise");
}

static void garbage_restore(fz *F)
{
    char good[300], badp[300];
    snprintf(good, sizeof good, "%s/good.state", F->dir);
    snprintf(badp, sizeof badp, "%s/bad-%d.state", F->dir, F->nfile++ % 4);
    int mode = (int)rn(8);
    if (mode == 0) { BAD("restore: missing file", dem_world_restore(W, coin(4) ? NULL : "/nonexistent-dir/none.state")); return; }
    if (mode == 1) { BAD("restore: directory or empty file", dem_world_restore(W, coin(2) ? F->dir : "/dev/null")); return; }
    if (mode == 2) { /* random bytes, with or without the magic */
        size_t n = rn(600);
        unsigned char *b = malloc(n + 32);
        for (size_t k = 0; k < n + 32; ++k) b[k] = (unsigned char)rnd();
        if (coin(2)) { memcpy(b, "DEMSTATE", 8); uint32_t v[3] = {3, 0x01020304u, 8}; memcpy(b + 8, v, 12); n += 20; }
        write_all(badp, b, n);
        free(b);
        BAD("restore: random bytes", dem_world_restore(W, badp));
        return;
    }
    if (dem_world_save(F->a, good) != DEM_OK) { failure("restore: save", "save of the world failed: %s%s", dem_world_last_error(F->a), ""); return; }
    size_t n = 0;
    unsigned char *b = read_all(good, &n);
    if (!b) return;
    if (mode == 3) { /* truncated */
        write_all(badp, b, rn(n));
        BAD("restore: truncated file", dem_world_restore(W, badp));
    } else if (mode == 4) { /* trailing data */
        b = realloc(b, n + 8);
        memset(b + n, 0xab, 8);
        write_all(badp, b, n + 1 + rn(8));
        BAD("restore: trailing data", dem_world_restore(W, badp));
    } else { /* corrupted: must be rejected or, if it passes all checks, be usable */
        corrupt(b, n);
        write_all(badp, b, n);
        mark(F->a);
        dem_status s = dem_world_restore(F->a, badp);
        if (s == DEM_OK) {
            dem_status s2 = dem_world_restore(F->b, badp);
            valid_result(F, "restore: corrupted file accepted", "dem_world_restore(corrupted)", s, s2, 1);
            /* what the fuzzer knows about the world is stale now: use it a
               little on both (same results), then start again */
            exercise(F);
            F->diverged = 1;
        } else rejected(F, "restore: corrupted file", "dem_world_restore(corrupted)", s, 1);
    }
    free(b);
}

/* Many corruptions of one state file (mostly of counts, indices and flags):
 * each is refused, or accepted and then usable. */
static void restore_storm(fz *F, int tries)
{
    char good[300], badp[300];
    snprintf(good, sizeof good, "%s/good.state", F->dir);
    snprintf(badp, sizeof badp, "%s/bad-0.state", F->dir);
    if (dem_world_save(F->a, good) != DEM_OK) return;
    size_t n = 0;
    unsigned char *orig = read_all(good, &n);
    if (!orig) return;
    unsigned char *b = malloc(n);
    for (int k = 0; k < tries; ++k) {
        memcpy(b, orig, n);
        if (n >= 8 && coin(2)) { /* an int32 or uint64 field to an extreme */
            static const int32_t v[] = {-1, -2, INT32_MIN, INT32_MAX, 0, 1, 2, 27, 64, 1000};
            if (coin(2)) memcpy(b + 4 * rn(n / 4), &v[rn(10)], 4);
            else { uint64_t u = coin(2) ? UINT64_MAX : (uint64_t)rn(300); memcpy(b + 8 * rn(n / 8), &u, 8); }
        } else corrupt(b, n);
        write_all(badp, b, n);
        mark(F->a);
        dem_status s = dem_world_restore(F->a, badp);
        if (s == DEM_OK) {
            dem_status s2 = dem_world_restore(F->b, badp);
            valid_result(F, "restore: corrupted file accepted", "dem_world_restore(corrupted)", s, s2, 1);
            exercise(F);
            F->diverged = 1;
        } else rejected(F, "restore: corrupted file", "dem_world_restore(corrupted)", s, 1);
    }
    free(b);
    free(orig);
}

/*--- valid operations (both twins) -------------------------------------------------*/
static int cyl_inside(const double x[3], void *user) { (void)user; return x[0] * x[0] + x[1] * x[1] < 1e-4; }

static void valid_op(fz *F)
{
    size_t n = dem_world_count(F->a);
    int op = (int)rn(22);
    if (!F->configured && coin(2)) op = 0;
    if (F->nmat == 0 && coin(2)) op = 1;
    switch (op) {
    case 0: { /* configure (geometry/law only while empty) */
        int geo = n == 0 && particle_total(F->a) == 0;
        dem_config c = good_config(F, geo);
        BOTH("configure", 1, dem_world_configure(W, &c));
        if (geo) F->configured = 1;
        break; }
    case 1: if (F->nmat < 4) {
        dem_material m = good_material(F->law);
        int id = -1, id2 = -1;
        dem_world *W = F->a; dem_status sa = dem_world_add_material(W, &m, &id);
        W = F->b; dem_status sb = dem_world_add_material(W, &m, &id2);
        valid_result(F, "add_material", "dem_world_add_material", sa, sb, 1);
        if (sa == DEM_OK) { if (id != F->nmat || id2 != id) failure("add_material", "material id%s%s", "", ""); F->nmat++; }
        } break;
    case 2: if (F->nmat > 1) { dem_material m = good_material(F->law);
        int a = (int)rn((size_t)F->nmat), b = (int)rn((size_t)F->nmat);
        BOTH("set_pair", 1, dem_world_set_pair(W, a, b, &m)); } break;
    case 3: case 4: if (F->nmat) { /* fill */
        double store[16];
        dem_particle_template t = good_template(F, store);
        size_t nn = rn(QUICK ? 12 : 25), ga = 0, gb = 0;
        if (coin(3)) {
            double base[3] = {rr(-0.3, 0.3) * F->H, rr(-0.3, 0.3) * F->H, -0.5 * F->H}, ax[3] = {rr(-0.2, 0.2), rr(-0.2, 0.2), 1};
            dem_world *W = F->a; dem_status sa = dem_world_fill_cylinder(W, base, ax, 0.3 * F->H, 0.8 * F->H, nn, &t, &ga);
            W = F->b; dem_status sb = dem_world_fill_cylinder(W, base, ax, 0.3 * F->H, 0.8 * F->H, nn, &t, &gb);
            valid_result(F, "fill_cylinder", "dem_world_fill_cylinder", sa, sb, 0);
        } else {
            double lo[3], hi[3];
            for (int k = 0; k < 3; ++k) { lo[k] = rr(-0.9, -0.1) * F->H; hi[k] = lo[k] + rr(0.2, 0.9) * F->H; }
            dem_inside_fn in = coin(3) ? cyl_inside : NULL;
            dem_world *W = F->a; dem_status sa = dem_world_fill_box(W, lo, hi, in, NULL, nn, &t, &ga);
            W = F->b; dem_status sb = dem_world_fill_box(W, lo, hi, in, NULL, nn, &t, &gb);
            valid_result(F, "fill_box", "dem_world_fill_box", sa, sb, 0);
        }
        if (ga != gb) failure("fill", "twins placed different numbers%s%s", "", "");
        } break;
    case 5: if (F->nmat) { dem_particle p[2] = {good_particle(F), good_particle(F)};
        size_t k = 1 + rn(2);
        BOTH("add_particles", 1, dem_world_add_particles(W, k, p)); } break;
    case 6: if (n) { size_t i = rn(n); int o = F->noutlets ? (int)rn((size_t)F->noutlets + 1) - 1 : -1;
        BOTH("remove_particle", 1, dem_world_remove_particle(W, i, o)); } break;
    case 7: case 8: case 9: { int64_t k = 1 + (int64_t)rn(QUICK ? 6 : 20);
        BOTH("step", 0, dem_world_step(W, k)); } break;
    case 10: if (F->nmat) { /* plane on a face of the box, normal inwards */
        int k = (int)rn(3), s = coin(2) ? 1 : -1;
        double p[3] = {0, 0, 0}, nn[3] = {0, 0, 0}, v[3] = {0, 0, 0};
        p[k] = -s * F->H * 0.95; nn[k] = s; nn[(k + 1) % 3] = rr(-0.1, 0.1);
        if (coin(4)) v[k] = rr(-0.01, 0.01);
        int ia = -1, ib = -2; int mat = (int)rn((size_t)F->nmat);
        const double *vp = coin(2) ? v : NULL;
        dem_world *W = F->a; dem_status sa = dem_world_add_plane(W, p, nn, mat, vp, &ia);
        W = F->b; dem_status sb = dem_world_add_plane(W, p, nn, mat, vp, &ib);
        valid_result(F, "add_plane", "dem_world_add_plane", sa, sb, 1);
        if (ia != ib || ia != F->nwalls) failure("add_plane", "wall id%s%s", "", "");
        F->nwalls++; } break;
    case 11: if (F->nmat) {
        double z = -0.9 * F->H, L = F->H;
        double v[15] = {-L, -L, z, L, -L, z, L, L, z + rr(0, 0.1) * L, -L, L, z, 0, 0, z + rr(-0.05, 0.05) * L};
        int tri[12] = {4, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0};
        int mat = (int)rn((size_t)F->nmat);
        BOTH("add_trimesh", 1, dem_world_add_trimesh(W, 5, v, 4, tri, mat, NULL, NULL));
        F->nwalls++; } break;
    case 12: if (F->nwalls) { double v[3] = {rr(-0.01, 0.01), 0, 0}; int id = (int)rn((size_t)F->nwalls);
        const double *vp = coin(3) ? NULL : v;
        /* may fail after an extreme wall velocity: wall out of the range of doubles */
        BOTH("set_wall_velocity", 0, dem_world_set_wall_velocity(W, id, vp)); } break;
    case 13: if (F->nmat && F->ninlets < 2) {
        double store[16];
        dem_particle_template t = good_template(F, store);
        double h = F->H / 3, z = 0.7 * F->H;
        double poly[12] = {-h, -h, z, h, -h, z, h, h, z, -h, h, z};
        dem_rate_kind kind = coin(2) ? DEM_RATE_NUMBER : DEM_RATE_MASS;
        double rate = kind == DEM_RATE_NUMBER ? rr(1e3, 2e4) : rr(1e-3, 2e-2);
        double t0 = dem_world_time(F->a), t1 = t0 + rr(0, 1e-3);
        size_t nv = 3 + rn(2);
        BOTH("add_inlet", 1, dem_world_add_inlet(W, nv, poly, kind, rate, t0, t1, &t, NULL));
        F->ninlets++; } break;
    case 14: { double p[3] = {0, 0, 0.9 * F->H}, nn[3] = {0, 0, 1}, lo[3] = {-F->H, -F->H, 0.85 * F->H}, hi[3] = {F->H, F->H, F->H};
        switch (rn(3)) {
        case 0: BOTH("add_outlet", 1, dem_world_add_outlet_plane(W, p, nn, NULL)); break;
        case 1: BOTH("add_outlet", 1, dem_world_add_outlet_box(W, lo, hi, NULL)); break;
        default: BOTH("add_outlet", 1, dem_world_add_outlet(W, NULL));
        }
        F->noutlets++; } break;
    case 15: { /* coupling arrays: same inputs on both */
        dem_arrays A, B;
        dem_world *W = F->a; dem_status sa = dem_world_arrays(W, &A);
        W = F->b; dem_status sb = dem_world_arrays(W, &B);
        valid_result(F, "arrays", "dem_world_arrays", sa, sb, 1);
        if (sa || sb || A.n_owned != B.n_owned) break;
        for (size_t i = 0; i < A.n_owned; ++i) {
            if (!coin(3)) continue;
            double K = rr(0, 1e-5), u = rr(-0.1, 0.1), fe = rr(-1e-5, 1e-5), ma = coin(3) ? rr(0, 1e-6) : 0.0;
            A.drag_coeff[i] = B.drag_coeff[i] = K;
            A.fluid_velocity[3 * i + 2] = B.fluid_velocity[3 * i + 2] = u;
            A.force_ext[3 * i] = B.force_ext[3 * i] = fe;
            A.added_mass[i] = B.added_mass[i] = ma;
        }
        break; }
    case 16: { /* queries: same answers */
        double ta = 0, tb = 0, v = coin(2) ? 0.0 : rr(0.1, 2);
        dem_world *W = F->a; dem_status sa = dem_world_contact_time(W, v, &ta);
        W = F->b; dem_status sb = dem_world_contact_time(W, v, &tb);
        valid_result(F, "contact_time", "dem_world_contact_time", sa, sb, 0);
        if (memcmp(&ta, &tb, sizeof ta)) failure("contact_time", "twins differ%s%s", "", "");
        size_t pa, la;
        size_t *ppa = coin(2) ? &pa : NULL, *pla = coin(2) ? &la : NULL;
        BOTH("memory", 1, dem_world_memory(W, ppa, pla));
        int *ca = calloc(n + 1, sizeof(int)), *cb = calloc(n + 1, sizeof(int));
        double *fa = calloc(3 * n + 3, sizeof(double)), *fb = calloc(3 * n + 3, sizeof(double));
        sa = dem_world_particle_contacts(F->a, ca, fa);
        sb = dem_world_particle_contacts(F->b, cb, fb);
        valid_result(F, "particle_contacts", "dem_world_particle_contacts", sa, sb, 0);
        if (sa != DEM_OK && sa != DEM_ERR_STATE) failure("particle_contacts", "unexpected status %s%s", dem_status_string(sa), "");
        if (memcmp(ca, cb, n * sizeof(int)) || memcmp(fa, fb, 3 * n * sizeof(double)))
            failure("particle_contacts", "twins differ%s%s", "", "");
        free(ca); free(cb); free(fa); free(fb);
        if (F->nmat) { dem_material ma, mb; int id = (int)rn((size_t)F->nmat);
            sa = dem_world_material_get(F->a, id, &ma); sb = dem_world_material_get(F->b, id, &mb);
            valid_result(F, "material_get", "dem_world_material_get", sa, sb, 1); }
        if (F->noutlets) { int64_t c1, c2; double m1, m2; int id = (int)rn((size_t)F->noutlets);
            sa = dem_world_outlet_totals(F->a, id, &c1, &m1); sb = dem_world_outlet_totals(F->b, id, &c2, &m2);
            valid_result(F, "outlet_totals", "dem_world_outlet_totals", sa, sb, 1);
            if (c1 != c2 || memcmp(&m1, &m2, sizeof m1)) failure("outlet_totals", "twins differ%s%s", "", ""); }
        const dem_removed_record *r; size_t nr;
        BOTH("removed_records", 1, dem_world_removed_records(W, &r, &nr));
        if (coin(3)) { dem_world_clear_removed_records(F->a); dem_world_clear_removed_records(F->b); }
        break; }
    case 17: if (n) { /* migration round trip: pack, remove, unpack as owned (or as a ghost) */
        size_t i = rn(n), sa = 0, sb = 0;
        dem_world_pack_particle(F->a, i, NULL, &sa);
        dem_world_pack_particle(F->b, i, NULL, &sb);
        unsigned char *ba = malloc(sa + 8), *bb = malloc(sb + 8);
        size_t za = sa + 8, zb = sb + 8; /* larger buffers are fine */
        BOTH("pack", 1, dem_world_pack_particle(W, i, W == F->a ? (void *)ba : (void *)bb, W == F->a ? &za : &zb));
        int ghost = coin(3);
        BOTH("remove_particle", 1, dem_world_remove_particle(W, i, -1));
        /* may fail: a particle of a world that went non-finite is refused */
        BOTH(ghost ? "unpack (ghost)" : "unpack", 0,
             dem_world_unpack_particle(W, W == F->a ? (void *)ba : (void *)bb, W == F->a ? za : zb, ghost));
        free(ba); free(bb);
        } break;
    case 18: BOTH("clear_ghosts", 1, dem_world_clear_ghosts(W)); break;
    case 19: if (coin(3)) { /* save and restore both */
        char pa[300], pb[300];
        snprintf(pa, sizeof pa, "%s/a.state", F->dir);
        snprintf(pb, sizeof pb, "%s/b.state", F->dir);
        BOTH("save", 1, dem_world_save(W, W == F->a ? pa : pb));
        BOTH("restore", 1, dem_world_restore(W, W == F->a ? pa : pb));
        } break;
    case 20: { dem_stats s; BOTH("stats", 1, dem_world_stats(W, &s)); } break;
    default: break;
    }
}

/* Extreme values that are valid (finite, representable): both twins get
 * them, then a few steps; any error must be the same on both, with a
 * message.  The world may end up non-finite (reported by the next step). */
static void extreme_valid(fz *F)
{
    static const double big[] = {1e300, -1e300, DBL_MAX, -DBL_MAX, 1e200, 1e-300, 4.9e-324, 1e30};
    size_t n = dem_world_count(F->a);
    switch (rn(8)) {
    case 0: if (F->nmat) {
        dem_particle p = good_particle(F);
        static const double rr_[][2] = {{1e-100, 1e200}, {1e50, 1e-100}, {1e-150, 1e300}, {5e-4, 1e300}, {1e3, 1e-300}};
        int k = (int)rn(5);
        if (coin(2)) { p.radius = rr_[k][0]; p.density = rr_[k][1]; }
        if (coin(2)) p.x[rn(3)] = big[rn(8)];
        if (coin(2)) p.v[rn(3)] = big[rn(8)];
        if (coin(2)) p.omega[rn(3)] = big[rn(8)];
        if (coin(3)) { p.id = INT64_MAX - 1 - (int64_t)rn(2); F->diverged = 1; } /* auto ids may run out: start again */
        BOTH("extreme: add_particles", 0, dem_world_add_particles(W, 1, &p));
        } break;
    case 1: if (F->nwalls) { double v[3] = {0, 0, 0}; v[rn(3)] = big[rn(8)]; int id = (int)rn((size_t)F->nwalls);
        BOTH("extreme: set_wall_velocity", 0, dem_world_set_wall_velocity(W, id, v)); } break;
    case 2: { dem_config c = good_config(F, 0);
        switch (rn(6)) {
        case 0: c.dt = coin(2) ? 1e-300 : (coin(2) ? 1e300 : 4.9e-324); break;
        case 1: c.gravity[rn(3)] = big[rn(8)]; break;
        case 2: c.max_dt_fraction = coin(2) ? INFINITY : 1e-300; break;
        case 3: c.max_overlap_ratio = coin(2) ? INFINITY : 4.9e-324; break;
        case 4: c.impact_speed = coin(2) ? 1e300 : 4.9e-324; break;
        default: if (n == 0 && particle_total(F->a) == 0 && F->configured) {
                     int k = (int)rn(3);
                     if (coin(2)) { c.domain_lo[k] = -1e307; c.domain_hi[k] = 1e307; }
                     else { c.domain_lo[k] = 0; c.domain_hi[k] = 1e-300; c.periodic[k] = 0; }
                     if (coin(2)) c.skin = coin(2) ? 1e300 : 1e-300;
                     F->diverged = 1; /* the fuzzer's notion of the geometry is stale */
                 }
        }
        BOTH("extreme: configure", 0, dem_world_configure(W, &c));
        break; }
    case 3: { double t1 = 0, t2 = 0, v = big[rn(8)];
        if (coin(3)) v = coin(2) ? INFINITY : NAN;
        dem_status sa = dem_world_contact_time(F->a, v, &t1), sb = dem_world_contact_time(F->b, v, &t2);
        valid_result(F, "extreme: contact_time", "dem_world_contact_time(extreme)", sa, sb, 0);
        if (memcmp(&t1, &t2, sizeof t1)) failure("extreme: contact_time", "twins differ%s%s", "", "");
        break; }
    case 4: if (F->nmat) { double store[16];
        dem_particle_template t = good_template(F, store);
        double lo[3] = {-1e300, -1e300, -1e300}, hi[3] = {1e300, 1e300, 1e300};
        size_t ga = 0, gb = 0, k = 1 + rn(3);
        dem_status sa = dem_world_fill_box(F->a, lo, hi, NULL, NULL, k, &t, &ga);
        dem_status sb = dem_world_fill_box(F->b, lo, hi, NULL, NULL, k, &t, &gb);
        valid_result(F, "extreme: fill_box", "dem_world_fill_box(huge box)", sa, sb, 0);
        if (ga != gb) failure("extreme: fill_box", "twins placed different numbers%s%s", "", "");
        } break;
    case 5: if (F->nmat) { double p[3] = {big[rn(8)], 0, 0}, nn[3] = {coin(2) ? 1e-150 : 1e150, 0, 0};
        int mat = (int)rn((size_t)F->nmat);
        dem_status sa = dem_world_add_plane(F->a, p, nn, mat, NULL, NULL), sb = dem_world_add_plane(F->b, p, nn, mat, NULL, NULL);
        valid_result(F, "extreme: add_plane", "dem_world_add_plane(extreme)", sa, sb, 0);
        if (sa == DEM_OK) F->nwalls++; } break;
    case 6: if (F->nmat) { double s = coin(2) ? 1e150 : 1e-150;
        double v[9] = {0, 0, 0, s, 0, 0, 0, s, 0};
        int tri[3] = {0, 1, 2}, mat = (int)rn((size_t)F->nmat);
        dem_status sa = dem_world_add_trimesh(F->a, 3, v, 1, tri, mat, NULL, NULL);
        dem_status sb = dem_world_add_trimesh(F->b, 3, v, 1, tri, mat, NULL, NULL);
        valid_result(F, "extreme: add_trimesh", "dem_world_add_trimesh(extreme)", sa, sb, 0);
        if (sa == DEM_OK) F->nwalls++; } break;
    default: if (n) { dem_arrays A, B;
        dem_status sa = dem_world_arrays(F->a, &A), sb = dem_world_arrays(F->b, &B);
        valid_result(F, "extreme: arrays", "dem_world_arrays", sa, sb, 1);
        if (sa || sb) break;
        size_t i = rn(n);
        double v = fabs(big[rn(8)]);
        switch (rn(4)) {
        case 0: A.force_ext[3 * i] = B.force_ext[3 * i] = v; break;
        case 1: A.drag_coeff[i] = B.drag_coeff[i] = v; A.fluid_velocity[3 * i] = B.fluid_velocity[3 * i] = 1.0; break;
        case 2: A.added_mass[i] = B.added_mass[i] = v; break;
        default: A.torque_ext[3 * i + 1] = B.torque_ext[3 * i + 1] = v; break;
        } }
    }
    int64_t k = 1 + (int64_t)rn(3);
    BOTH("extreme: step", 0, dem_world_step(W, k));
    same_full(F, "twin comparison", "extreme values");
}

static void step_both(fz *F)
{
    BOTH("step after rejected calls", 0, dem_world_step(W, 1));
    same_full(F, "twin comparison", "step");
}

int main(void)
{
    const char *e = getenv("DEM_FUZZ_SEED");
    seed = e && *e ? strtoull(e, NULL, 0) : 20260611ull;
    e = getenv("DEM_FUZZ_ROUNDS");
    long rounds = e && *e ? strtol(e, NULL, 0) : (QUICK ? 5000 : 3000);
    e = getenv("DEM_FUZZ_VERBOSE");
    verbose = e && *e && *e != '0';
    rs = seed;
    printf("# fuzz seed %llu, %ld rounds (reproduce: DEM_FUZZ_SEED=%llu)\n", (unsigned long long)seed, rounds,
           (unsigned long long)seed);

    fz F;
    memset(&F, 0, sizeof F);
    const char *tmp = getenv("TMPDIR");
    snprintf(F.dir, sizeof F.dir, "%s/demfuzz-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(F.dir)) { printf("FAIL: fuzz: mkdtemp %s (tol exact)\n", F.dir); return 1; }

    null_handle_calls();
    fresh(&F);
    long since_fresh = 0;
    for (round_no = 0; round_no < rounds; ++round_no) {
        if (F.diverged || since_fresh++ > 150 + (long)rn(150)) {
            same_full(&F, "twin comparison", "(end of a world)");
            if (!F.diverged) restore_storm(&F, QUICK ? 5 : 10);
            fresh(&F);
            since_fresh = 0;
        }
        if (coin(2)) { valid_op(&F); if (coin(4)) same_full(&F, "twin comparison", last_ops[(nlast - 1) % 8]); continue; }
        switch (rn(11)) {
        case 10: extreme_valid(&F); break;
        case 0: bad_config(&F); break;
        case 1: bad_material(&F); break;
        case 2: bad_particles(&F); break;
        case 3: bad_fill(&F); break;
        case 4: bad_walls(&F); break;
        case 5: bad_inlet_outlet(&F); break;
        case 6: case 7: bad_misc(&F); break;
        case 8: garbage_unpack(&F); break;
        default: if (coin(QUICK ? 3 : 2)) garbage_restore(&F); else bad_misc(&F); break;
        }
        if (coin(8)) same_full(&F, "twin comparison", last_ops[(nlast - 1) % 8]);
        /* the world stays usable: a small valid step behaves the same on both */
        if (coin(10)) step_both(&F);
    }
    same_full(&F, "twin comparison", "(end)");
    dem_world_destroy(&F.a);
    dem_world_destroy(&F.b);

    /* remove the temporary directory */
    const char *names[] = {"good.state", "a.state", "b.state", "bad-0.state", "bad-1.state", "bad-2.state", "bad-3.state"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) {
        char p[300];
        snprintf(p, sizeof p, "%s/%s", F.dir, names[k]);
        remove(p);
    }
    if (rmdir(F.dir) != 0) printf("# could not remove %s\n", F.dir);

    long total = 0;
    for (int c = 0; c < ncat; ++c) {
        printf("%s: fuzz %s: %ld failures in %ld calls vs 0 (tol exact)\n", cat[c].fails ? "FAIL" : "PASS",
               cat[c].name, cat[c].fails, cat[c].calls);
        if (cat[c].fails) check_failures++;
        total += cat[c].calls;
    }
    printf("# fuzz: %ld calls in %d categories, %ld log messages, seed %llu\n", total, ncat, nlog,
           (unsigned long long)seed);
    return check_exit();
}
