/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Split step and decomposition support (docs/demCore.md, "State,
 * decomposition support"; docs/parallel.md).
 * (a) n x (dem_world_step_drift + dem_world_step_forces) is bit-identical to
 *     dem_world_step(w, n): a bed on plane walls, the same with coupling
 *     arrays (force_ext, torque_ext, drag_coeff, fluid_velocity, added_mass),
 *     a periodic box with an inlet and an outlet.
 * (b) Two ranks emulated in one process: worlds A (x < 0) and B (x >= 0)
 *     each own the particles on their side; every step: drift on both,
 *     migration (dem_world_pack_particle, dem_world_remove_particle(-1),
 *     dem_world_unpack_particle(0) on the other side), clear_ghosts and
 *     ghosts (owned particles within 2 a_max + margin of x = 0, packed with
 *     dem_world_pack_ghost, unpacked ghost = 1), forces on both.  Compared by
 *     id with a reference world owning everything: head-on and oblique
 *     (tangential history, migration during the contact) collisions across
 *     x = 0 with rotation, and a settling bed of 216 Hertz-Mindlin particles.
 * (b') The same with the Verlet scheme of dem.h: the ghost set is chosen
 *     only at steps where a list rebuild is due on either rank (OR of
 *     dem_world_list_stale; then migration, clear_ghosts, ghosts within
 *     r_i + r_max + skin of x = 0, dem_world_invalidate_list on both), in
 *     between only the ghost states go over (dem_world_set_ghost_states, in
 *     the order the ghosts were sent): same comparisons, ghost order checked
 *     every step, list builds far fewer than steps.
 * (c) Call order (DEM_ERR_STATE), dem_world_pack_ghost sizes, and the
 *     bookkeeping of migration (no inserted/removed counts).
 * (d) Ghost order kept by insertion (inlet during step_drift), owned unpack
 *     and removal; set_ghost_states errors and that it keeps the list;
 *     dem_world_skin, dem_world_list_stale, dem_world_invalidate_list. */
#include "check.h"

/*--- helpers ------------------------------------------------------------------*/
static uint64_t lcg = 12345;
static double rnd(void) /* [0, 1) */
{
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg >> 11) / 9007199254740992.0;
}

/* nx x ny x nz spheres at spacing s from (x0, y0, s/2), odd layers shifted
 * by s/8 in x; radii in [amin, amin + 0.2 mm], random v (0.05 m/s) and omega */
static size_t lattice(dem_particle *p, int nx, int ny, int nz, double x0, double y0, double s, double amin,
                      double omega_amp, uint64_t seed)
{
    lcg = seed;
    size_t n = 0;
    for (int iz = 0; iz < nz; ++iz)
        for (int iy = 0; iy < ny; ++iy)
            for (int ix = 0; ix < nx; ++ix) {
                double a = amin + 0.2e-3 * rnd();
                p[n] = test_particle(x0 + s * ix + 0.125 * s * (iz % 2), y0 + s * iy, 0.5 * s + s * iz,
                                     0.1 * (rnd() - 0.5), 0.1 * (rnd() - 0.5), 0.1 * (rnd() - 0.5), a, 2500, 0);
                for (int k = 0; k < 3; ++k) p[n].omega[k] = omega_amp * (rnd() - 0.5);
                n++;
            }
    return n;
}

/* storage index of id among the owned particles ((size_t)-1: none) */
static size_t index_of(const dem_arrays *A, int64_t id)
{
    for (size_t i = 0; i < A->n_owned; ++i) if (A->id[i] == id) return i;
    return (size_t)-1;
}

/*--- (a) bit identity ---------------------------------------------------------------*/
enum { BED_WALLS, BED_COUPLED, PERIODIC_IO };

static dem_world *make_a(int kind)
{
    const double g[3] = {0, 0, -9.81};
    dem_world *w = NULL;
    TRY(w, dem_world_create(&w));
    dem_config c;
    dem_config_default(&c);
    c.dt = 5e-6;
    for (int k = 0; k < 3; ++k) { c.gravity[k] = g[k]; c.domain_lo[k] = -0.01; c.domain_hi[k] = 0.01; }
    c.domain_lo[2] = 0; c.domain_hi[2] = 0.03;
    if (kind == PERIODIC_IO) c.periodic[0] = c.periodic[1] = 1;
    TRY(w, dem_world_configure(w, &c));
    dem_material m = test_material(1e7, 0.3, 0.4, 1e-5, 0.6);
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    const double o[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, o, nz, mid, NULL, NULL));
    if (kind != PERIODIC_IO) {
        const double px[3] = {-0.0075, 0, 0}, nx[3] = {1, 0, 0}, qx[3] = {0.0075, 0, 0}, mx[3] = {-1, 0, 0};
        const double vel[3] = {0, 0.01, 0};
        TRY(w, dem_world_add_plane(w, px, nx, mid, vel, NULL));
        TRY(w, dem_world_add_plane(w, qx, mx, mid, NULL, NULL));
    }
    dem_particle p[120];
    size_t n = lattice(p, 6, 4, 5, -0.005, -0.004, 2.1e-3, 0.8e-3, 20, 777);
    TRY(w, dem_world_add_particles(w, n, p));
    if (kind == BED_COUPLED) {
        dem_arrays A;
        TRY(w, dem_world_arrays(w, &A));
        for (size_t i = 0; i < A.n_owned; ++i) {
            A.drag_coeff[i] = (i % 3) ? 1e-4 * (1 + 0.1 * (double)(i % 7)) : 0.0;
            A.added_mass[i] = (i % 4) ? 0.5 * 1000 * 4.0 / 3.0 * M_PI * A.radius[i] * A.radius[i] * A.radius[i] : 0.0;
            A.fluid_velocity[3 * i] = 0.05; A.fluid_velocity[3 * i + 2] = 0.1 * (double)(i % 5) / 5;
            A.force_ext[3 * i + 1] = 1e-6; A.torque_ext[3 * i + 2] = 1e-11;
        }
    }
    if (kind == PERIODIC_IO) {
        dem_particle_template t;
        memset(&t, 0, sizeof t);
        t.diameter.kind = DEM_DIST_UNIFORM; t.diameter.a = 1.6e-3; t.diameter.b = 2e-3;
        t.density.kind = DEM_DIST_FIXED; t.density.a = 2500;
        t.velocity[2] = -0.5;
        t.material = mid;
        double sq[12] = {-0.009, -0.009, 0.028, 0.009, -0.009, 0.028, 0.009, 0.009, 0.028, -0.009, 0.009, 0.028};
        TRY(w, dem_world_add_inlet(w, 4, sq, DEM_RATE_NUMBER, 4e4, 0.0, 1.0, &t, NULL));
        const double lo[3] = {-0.01, -0.01, -0.01}, hi[3] = {-0.004, 0.01, 0.003};
        TRY(w, dem_world_add_outlet_box(w, lo, hi, NULL));
    }
    return w;
}

static void bit_identity(int kind, const char *name, int64_t nsteps)
{
    dem_world *w1 = make_a(kind), *w2 = make_a(kind), *w3 = make_a(kind);
    TRY(w1, dem_world_step(w1, nsteps));
    for (int64_t s = 0; s < nsteps; ++s) {
        TRY(w2, dem_world_step_drift(w2));
        TRY(w2, dem_world_step_forces(w2));
        /* the checks once, as dem_world_step: dem_world_step_drift_next */
        TRY(w3, s ? dem_world_step_drift_next(w3) : dem_world_step_drift(w3));
        TRY(w3, dem_world_step_forces(w3));
    }
    {
        dem_arrays a3, b3;
        TRY(w2, dem_world_arrays(w2, &a3));
        TRY(w3, dem_world_arrays(w3, &b3));
        double d3 = a3.n_owned == b3.n_owned ? 0.0 : 1.0;
        for (size_t i = 0; i < a3.n_owned && a3.n_owned == b3.n_owned; ++i)
            for (int k = 0; k < 3; ++k) {
                d3 = fmax(d3, fabs(a3.x[3 * i + k] - b3.x[3 * i + k]));
                d3 = fmax(d3, fabs(a3.v[3 * i + k] - b3.v[3 * i + k]));
                d3 = fmax(d3, fabs(a3.omega[3 * i + k] - b3.omega[3 * i + k]));
            }
        char nm3[200];
        snprintf(nm3, sizeof nm3, "%s: step_drift_next vs step_drift: max |difference| of x, v, omega", name);
        check_abs(nm3, d3, 0.0, 0.0);
    }
    dem_arrays a, b;
    TRY(w1, dem_world_arrays(w1, &a));
    TRY(w2, dem_world_arrays(w2, &b));
    char nm[200];
    snprintf(nm, sizeof nm, "%s: particle count (drift+forces vs step(%lld))", name, (long long)nsteps);
    check_abs(nm, (double)b.n_owned, (double)a.n_owned, 0.0);
    double d = 0, dJ = 0;
    size_t nid = 0;
    if (a.n_owned == b.n_owned)
        for (size_t i = 0; i < a.n_owned; ++i) {
            nid += a.id[i] != b.id[i];
            for (int k = 0; k < 3; ++k) {
                d = fmax(d, fabs(a.x[3 * i + k] - b.x[3 * i + k]));
                d = fmax(d, fabs(a.v[3 * i + k] - b.v[3 * i + k]));
                d = fmax(d, fabs(a.omega[3 * i + k] - b.omega[3 * i + k]));
                dJ = fmax(dJ, fabs(a.drag_impulse[3 * i + k] - b.drag_impulse[3 * i + k]));
            }
        }
    snprintf(nm, sizeof nm, "%s: ids in storage order differing", name);
    check_abs(nm, (double)nid, 0.0, 0.0);
    snprintf(nm, sizeof nm, "%s: max |difference| of x, v, omega", name);
    check_abs(nm, d, 0.0, 0.0);
    snprintf(nm, sizeof nm, "%s: max |difference| of drag_impulse", name);
    check_abs(nm, dJ, 0.0, 0.0);
    snprintf(nm, sizeof nm, "%s: time", name);
    check_abs(nm, dem_world_time(w2), dem_world_time(w1), 0.0);
    dem_stats s1, s2;
    TRY(w1, dem_world_stats(w1, &s1));
    TRY(w2, dem_world_stats(w2, &s2));
    snprintf(nm, sizeof nm, "%s: pair contacts", name);
    check_abs(nm, (double)s2.pair_contacts, (double)s1.pair_contacts, 0.0);
    snprintf(nm, sizeof nm, "%s: neighbour-list builds", name);
    check_abs(nm, (double)s2.list_builds, (double)s1.list_builds, 0.0);
    if (kind == BED_WALLS || kind == PERIODIC_IO) {
        snprintf(nm, sizeof nm, "%s: contacts present (test not vacuous): pairs >= %d", name, QUICK ? 3 : 10);
        check_range(nm, (double)s1.pair_contacts, QUICK ? 3 : 10, 1e9);
    }
    if (kind == PERIODIC_IO) {
        snprintf(nm, sizeof nm, "%s: inserted", name);
        check_abs(nm, (double)s2.inserted, (double)s1.inserted, 0.0);
        snprintf(nm, sizeof nm, "%s: removed (outlet)", name);
        check_abs(nm, (double)s2.removed, (double)s1.removed, 0.0);
        snprintf(nm, sizeof nm, "%s: outlet removed some particles (test not vacuous)", name);
        check_range(nm, (double)s1.removed, 1, 1e9);
    }
    dem_world_destroy(&w1);
    dem_world_destroy(&w2);
    dem_world_destroy(&w3);
}

/*--- (b) two ranks in one process ------------------------------------------------------*/
typedef struct {
    dem_world *R, *W[2]; double halo; int nid; int64_t split_steps; double pair_sum[2];
    /* Verlet scheme (b') */
    int verlet;              /* 1: ghosts chosen at rebuilds only */
    double rmax, skin;       /* global largest radius, skin in use */
    int64_t *sent[2];        /* ids W[s] sent as ghosts to W[1-s], in order */
    size_t nsent[2];
    int64_t rebuilds;        /* steps with a (global) rebuild */
    int order_bad;           /* steps where a receiver's ghost order differs from sent[] */
    int skin_bad;            /* dem_world_skin differing from the configured skin */
} ranks;

static double cfg_skin = 0; /* dem_config.skin of the worlds of make_b (0: auto) */

static dem_world *make_b(double dt, const double g[3], int wall, double E)
{
    dem_world *w = NULL;
    TRY(w, dem_world_create(&w));
    dem_config c;
    dem_config_default(&c);
    c.dt = dt;
    c.skin = cfg_skin;
    for (int k = 0; k < 3; ++k) { c.gravity[k] = g[k]; c.domain_lo[k] = -0.02; c.domain_hi[k] = 0.02; }
    if (wall) { c.domain_lo[2] = 0; c.domain_hi[2] = 0.04; }
    TRY(w, dem_world_configure(w, &c));
    dem_material m = test_material(E, 0.3, 0.4, 2e-5, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    if (wall) {
        const double o[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
        TRY(w, dem_world_add_plane(w, o, nz, mid, NULL, NULL));
        const double px[3] = {-0.0105, 0, 0}, nx[3] = {1, 0, 0}, qx[3] = {0.0105, 0, 0}, mx[3] = {-1, 0, 0};
        const double py[3] = {0, -0.004, 0}, ny[3] = {0, 1, 0}, qy[3] = {0, 0.004, 0}, my[3] = {0, -1, 0};
        TRY(w, dem_world_add_plane(w, px, nx, mid, NULL, NULL));
        TRY(w, dem_world_add_plane(w, qx, mx, mid, NULL, NULL));
        TRY(w, dem_world_add_plane(w, py, ny, mid, NULL, NULL));
        TRY(w, dem_world_add_plane(w, qy, my, mid, NULL, NULL));
    }
    return w;
}

static void send(dem_world *from, size_t i, dem_world *to, int ghost)
{
    size_t sz = 0;
    if (ghost) TRY(from, dem_world_pack_ghost(from, i, NULL, &sz));
    else TRY(from, dem_world_pack_particle(from, i, NULL, &sz));
    void *buf = malloc(sz);
    if (ghost) TRY(from, dem_world_pack_ghost(from, i, buf, &sz));
    else TRY(from, dem_world_pack_particle(from, i, buf, &sz));
    TRY(to, dem_world_unpack_particle(to, buf, sz, ghost));
    free(buf);
}

static void exchange_ghosts(ranks *r)
{
    for (int s = 0; s < 2; ++s) TRY(r->W[s], dem_world_clear_ghosts(r->W[s]));
    for (int s = 0; s < 2; ++s) {
        dem_arrays A;
        TRY(r->W[s], dem_world_arrays(r->W[s], &A));
        size_t n = A.n_owned;
        for (size_t i = 0; i < n; ++i)
            if (fabs(A.x[3 * i]) < r->halo) send(r->W[s], i, r->W[1 - s], 1);
    }
}

static void migrate(ranks *r)
{
    /* pack everything leaving first (both sides), then unpack: no ping-pong */
    void *bufs[2][512]; size_t sizes[2][512]; int nb[2] = {0, 0};
    for (int s = 0; s < 2; ++s) {
        dem_arrays A;
        TRY(r->W[s], dem_world_arrays(r->W[s], &A));
        for (size_t i = A.n_owned; i-- > 0;) {
            TRY(r->W[s], dem_world_arrays(r->W[s], &A));
            int side = A.x[3 * i] >= 0;
            if (side == s) continue;
            size_t sz = 0;
            TRY(r->W[s], dem_world_pack_particle(r->W[s], i, NULL, &sz));
            bufs[s][nb[s]] = malloc(sz);
            TRY(r->W[s], dem_world_pack_particle(r->W[s], i, bufs[s][nb[s]], &sz));
            sizes[s][nb[s]++] = sz;
            TRY(r->W[s], dem_world_remove_particle(r->W[s], i, -1));
        }
    }
    for (int s = 0; s < 2; ++s)
        for (int k = 0; k < nb[s]; ++k) {
            TRY(r->W[1 - s], dem_world_unpack_particle(r->W[1 - s], bufs[s][k], sizes[s][k], 0));
            free(bufs[s][k]);
        }
}

/* Verlet scheme: after migration, the ghosts of the new list (owned
 * particles within r_i + r_max + skin of x = 0), their ids kept in order */
static void choose_ghosts(ranks *r)
{
    for (int s = 0; s < 2; ++s) TRY(r->W[s], dem_world_clear_ghosts(r->W[s]));
    for (int s = 0; s < 2; ++s) {
        dem_arrays A;
        TRY(r->W[s], dem_world_arrays(r->W[s], &A));
        size_t n = A.n_owned;
        double skin = dem_world_skin(r->W[s]);
        r->skin_bad += skin != r->skin;
        free(r->sent[s]);
        r->sent[s] = malloc((n + 1) * sizeof(int64_t));
        r->nsent[s] = 0;
        for (size_t i = 0; i < n; ++i) {
            TRY(r->W[s], dem_world_arrays(r->W[s], &A));
            if (fabs(A.x[3 * i]) < A.radius[i] + r->rmax + skin) {
                r->sent[s][r->nsent[s]++] = A.id[i];
                send(r->W[s], i, r->W[1 - s], 1);
            }
        }
    }
}

/* Verlet scheme between rebuilds: the states of the particles sent at the
 * last rebuild, in the same order (looked up by id: re-sorted storage) */
static void send_states(ranks *r)
{
    for (int s = 0; s < 2; ++s) {
        dem_arrays A;
        TRY(r->W[s], dem_world_arrays(r->W[s], &A));
        size_t *idx = malloc((size_t)r->nid * sizeof(size_t));
        for (int k = 0; k < r->nid; ++k) idx[k] = (size_t)-1;
        for (size_t i = 0; i < A.n_owned; ++i) idx[A.id[i]] = i;
        double *buf = malloc((9 * r->nsent[s] + 1) * sizeof(double));
        for (size_t k = 0; k < r->nsent[s]; ++k) {
            size_t i = idx[r->sent[s][k]];
            if (i == (size_t)-1) { r->order_bad++; i = 0; } /* cannot happen: no migration in between */
            memcpy(buf + 9 * k, A.x + 3 * i, 3 * sizeof(double));
            memcpy(buf + 9 * k + 3, A.v + 3 * i, 3 * sizeof(double));
            memcpy(buf + 9 * k + 6, A.omega + 3 * i, 3 * sizeof(double));
        }
        TRY(r->W[1 - s], dem_world_set_ghost_states(r->W[1 - s], 0, r->nsent[s], buf));
        free(buf);
        free(idx);
    }
}

/* the receivers hold the ghosts in the order they were sent */
static void check_ghost_order(ranks *r)
{
    for (int s = 0; s < 2; ++s) {
        dem_arrays A;
        TRY(r->W[1 - s], dem_world_arrays(r->W[1 - s], &A));
        int bad = A.n_ghost != r->nsent[s];
        for (size_t k = 0; k < r->nsent[s] && !bad; ++k) bad = A.id[A.n_owned + k] != r->sent[s][k];
        r->order_bad += bad;
    }
}

static void setup_ranks(ranks *r, double dt, const double g[3], int wall, double E, size_t n, dem_particle *p)
{
    memset(r, 0, sizeof *r);
    r->verlet = cfg_skin > 0;
    r->R = make_b(dt, g, wall, E);
    r->W[0] = make_b(dt, g, wall, E);
    r->W[1] = make_b(dt, g, wall, E);
    double amax = 0;
    for (size_t i = 0; i < n; ++i) { p[i].id = (int64_t)i; amax = fmax(amax, p[i].radius); }
    r->halo = 2 * amax + 0.1 * amax;
    r->nid = (int)n;
    r->rmax = amax;
    r->skin = cfg_skin;
    TRY(r->R, dem_world_add_particles(r->R, n, p));
    for (size_t i = 0; i < n; ++i) {
        int s = p[i].x[0] >= 0;
        TRY(r->W[s], dem_world_add_particles(r->W[s], 1, &p[i]));
    }
    /* before the first force evaluation */
    if (r->verlet) choose_ghosts(r);
    else exchange_ghosts(r);
}

static int ghost_moved; /* ghosts changed by a drift or force half (must stay 0) */

/* one step of the Verlet scheme (b') */
static void step_ranks_verlet(ranks *r)
{
    TRY(r->R, dem_world_step_drift(r->R));
    for (int s = 0; s < 2; ++s) TRY(r->W[s], dem_world_step_drift(r->W[s]));
    int stale = dem_world_list_stale(r->W[0]) || dem_world_list_stale(r->W[1]); /* MPI: allreduce(LOR) */
    if (stale) {
        migrate(r);
        choose_ghosts(r);
        for (int s = 0; s < 2; ++s) TRY(r->W[s], dem_world_invalidate_list(r->W[s]));
        r->rebuilds++;
    } else {
        send_states(r);
    }
    check_ghost_order(r);
    TRY(r->R, dem_world_step_forces(r->R));
    for (int s = 0; s < 2; ++s) {
        TRY(r->W[s], dem_world_step_forces(r->W[s]));
        dem_stats st;
        TRY(r->W[s], dem_world_stats(r->W[s], &st));
        r->pair_sum[s] += (double)st.pair_contacts;
    }
}

static void step_ranks(ranks *r)
{
    if (r->verlet) { step_ranks_verlet(r); return; }
    TRY(r->R, dem_world_step_drift(r->R));
    for (int s = 0; s < 2; ++s) {
        dem_arrays A;
        TRY(r->W[s], dem_world_arrays(r->W[s], &A));
        size_t ng = A.n_ghost, n0 = A.n_owned;
        double *gx = malloc((3 * ng + 1) * sizeof(double));
        memcpy(gx, A.x + 3 * n0, 3 * ng * sizeof(double));
        TRY(r->W[s], dem_world_step_drift(r->W[s]));
        TRY(r->W[s], dem_world_arrays(r->W[s], &A));
        if (A.n_ghost != ng || memcmp(gx, A.x + 3 * A.n_owned, 3 * ng * sizeof(double))) ghost_moved++;
        free(gx);
    }
    migrate(r);
    exchange_ghosts(r);
    TRY(r->R, dem_world_step_forces(r->R));
    for (int s = 0; s < 2; ++s) {
        dem_arrays A;
        TRY(r->W[s], dem_world_arrays(r->W[s], &A));
        size_t ng = A.n_ghost;
        double *gx = malloc((3 * ng + 1) * sizeof(double));
        memcpy(gx, A.x + 3 * A.n_owned, 3 * ng * sizeof(double));
        TRY(r->W[s], dem_world_step_forces(r->W[s]));
        TRY(r->W[s], dem_world_arrays(r->W[s], &A));
        if (memcmp(gx, A.x + 3 * A.n_owned, 3 * ng * sizeof(double))) ghost_moved++;
        free(gx);
        dem_stats st;
        TRY(r->W[s], dem_world_stats(r->W[s], &st));
        r->pair_sum[s] += (double)st.pair_contacts;
    }
}

/* compare with the reference: max differences of x (/ scale_x), v (/ scale_v), omega (/ scale_w) */
static void compare_ranks(ranks *r, const char *name, double tol_x, double tol_v, double tol_w,
                          double scale_x, double scale_v, double scale_w)
{
    dem_arrays R, A[2];
    TRY(r->R, dem_world_arrays(r->R, &R));
    TRY(r->W[0], dem_world_arrays(r->W[0], &A[0]));
    TRY(r->W[1], dem_world_arrays(r->W[1], &A[1]));
    char nm[200];
    snprintf(nm, sizeof nm, "%s: owned particles A + B vs reference", name);
    check_abs(nm, (double)(A[0].n_owned + A[1].n_owned), (double)R.n_owned, 0.0);
    double dx = 0, dv = 0, dw = 0, P[3] = {0, 0, 0}, PR[3] = {0, 0, 0}, mtot = 0;
    int missing = 0, twice = 0, wrong_side = 0;
    for (size_t i = 0; i < R.n_owned; ++i) {
        int found = 0;
        for (int s = 0; s < 2; ++s) {
            size_t j = index_of(&A[s], R.id[i]);
            if (j == (size_t)-1) continue;
            found++;
            /* Verlet scheme: migration at rebuilds only, a particle strays
               less than skin/2 (else a rebuild is due) */
            double slack = r->verlet ? 0.5 * r->skin : 0.0;
            if (s ? A[s].x[3 * j] < -slack : A[s].x[3 * j] >= slack) wrong_side++;
            for (int k = 0; k < 3; ++k) {
                dx = fmax(dx, fabs(A[s].x[3 * j + k] - R.x[3 * i + k]));
                dv = fmax(dv, fabs(A[s].v[3 * j + k] - R.v[3 * i + k]));
                dw = fmax(dw, fabs(A[s].omega[3 * j + k] - R.omega[3 * i + k]));
            }
        }
        missing += found == 0;
        twice += found > 1;
        for (int k = 0; k < 3; ++k) PR[k] += R.mass[i] * R.v[3 * i + k];
        mtot += R.mass[i];
    }
    for (int s = 0; s < 2; ++s)
        for (size_t j = 0; j < A[s].n_owned; ++j)
            for (int k = 0; k < 3; ++k) P[k] += A[s].mass[j] * A[s].v[3 * j + k];
    snprintf(nm, sizeof nm, "%s: reference ids owned by no rank", name);
    check_abs(nm, missing, 0, 0);
    snprintf(nm, sizeof nm, "%s: reference ids owned by both ranks", name);
    check_abs(nm, twice, 0, 0);
    if (r->verlet) snprintf(nm, sizeof nm, "%s: owned particles more than skin/2 on the wrong side of x = 0", name);
    else snprintf(nm, sizeof nm, "%s: owned particles on the wrong side of x = 0", name);
    check_abs(nm, wrong_side, 0, 0);
    snprintf(nm, sizeof nm, "%s: max |x - x_ref| / %g m", name, scale_x);
    check_abs(nm, dx / scale_x, 0.0, tol_x);
    snprintf(nm, sizeof nm, "%s: max |v - v_ref| / %g m/s", name, scale_v);
    check_abs(nm, dv / scale_v, 0.0, tol_v);
    snprintf(nm, sizeof nm, "%s: max |omega - omega_ref| / %g 1/s", name, scale_w);
    check_abs(nm, dw / scale_w, 0.0, tol_w);
    double dP = 0;
    for (int k = 0; k < 3; ++k) dP = fmax(dP, fabs(P[k] - PR[k]));
    snprintf(nm, sizeof nm, "%s: |momentum A + B - reference| / (total mass x %g m/s)", name, scale_v);
    check_abs(nm, dP / (mtot * scale_v), 0.0, tol_v);
}

/* checks of the Verlet scheme after a run of nsteps */
static void verlet_checks(ranks *r, const char *name, int64_t nsteps, double max_build_fraction, int min_rebuilds)
{
    char nm[200];
    if (!r->verlet) return;
    snprintf(nm, sizeof nm, "%s: steps with a receiver's ghost order differing from the send order", name);
    check_abs(nm, r->order_bad, 0, 0);
    snprintf(nm, sizeof nm, "%s: dem_world_skin differing from dem_config.skin (calls)", name);
    check_abs(nm, r->skin_bad, 0, 0);
    for (int s = 0; s < 2; ++s) {
        dem_stats st;
        TRY(r->W[s], dem_world_stats(r->W[s], &st));
        /* one build at the first drift, then one per global rebuild */
        snprintf(nm, sizeof nm, "%s: list builds of rank %c = 1 + steps with a global rebuild", name, "AB"[s]);
        check_abs(nm, (double)st.list_builds, 1.0 + (double)r->rebuilds, 0.0);
        snprintf(nm, sizeof nm, "%s: list builds of rank %c / steps (%lld steps)", name, "AB"[s], (long long)nsteps);
        check_below(nm, (double)st.list_builds / (double)nsteps, max_build_fraction);
    }
    snprintf(nm, sizeof nm, "%s: global rebuilds (ghost set re-chosen; >= %d: not vacuous)", name, min_rebuilds);
    check_range(nm, (double)r->rebuilds, min_rebuilds, 1e9);
}

static void free_ranks(ranks *r)
{
    free(r->sent[0]);
    free(r->sent[1]);
    dem_world_destroy(&r->R);
    dem_world_destroy(&r->W[0]);
    dem_world_destroy(&r->W[1]);
}

/* two particles, relative speed vrel along x, common velocity U along x,
 * impact parameter b along y; the contact starts with particle 0's centre at
 * x = xc0 (< 0) after time t0 */
static void two_particles(const char *name, double b, double U, double xc0)
{
    const double a = 1e-3, rho = 2500, vrel = 1.0, t0 = 2e-4, dt = 1e-6, g[3] = {0, 0, 0};
    const double dxc = sqrt(4 * a * a - b * b);
    double x0 = xc0 - (U + 0.5 * vrel) * t0, x1 = x0 + dxc + vrel * t0;
    dem_particle p[2] = {test_particle(x0, 0, 0, U + 0.5 * vrel, 0, 0, a, rho, 0),
                         test_particle(x1, b, 0, U - 0.5 * vrel, 0, 0, a, rho, 0)};
    p[0].omega[0] = 30; p[0].omega[2] = 80; p[1].omega[1] = -50; p[1].omega[2] = 20;
    ranks r;
    setup_ranks(&r, dt, g, 0, 1e7, 2, p);
    const int nsteps = 800;
    int contact_steps = 0;
    for (int s = 0; s < nsteps; ++s) {
        step_ranks(&r);
        dem_stats st;
        TRY(r.R, dem_world_stats(r.R, &st));
        contact_steps += (int)st.pair_contacts;
        if ((dem_world_count(r.W[0]) == 1) && st.pair_contacts) r.split_steps++;
    }
    char nm[200];
    snprintf(nm, sizeof nm, "%s: steps in contact (reference; test not vacuous)", name);
    check_range(nm, contact_steps, 50, nsteps - 100);
    snprintf(nm, sizeof nm, "%s: pair contacts summed over steps, A + B vs reference + steps split across ranks",
             name);
    check_abs(nm, r.pair_sum[0] + r.pair_sum[1], (double)contact_steps + (double)r.split_steps, 0.0);
    /* round-off only (a different force summation order) over a few hundred steps */
    compare_ranks(&r, name, 1e-9, 1e-9, 1e-9, 2 * a, vrel, vrel / a);
    verlet_checks(&r, name, nsteps, 0.2, U > 0 ? 1 : 0); /* head-on: < skin/2 of travel */
    if (U > 0) {
        dem_arrays A;
        TRY(r.W[1], dem_world_arrays(r.W[1], &A));
        snprintf(nm, sizeof nm, "%s: particle 0 migrated to B (owned count of B)", name);
        check_abs(nm, (double)A.n_owned, 2.0, 0.0);
    }
    free_ranks(&r);
}

static void bed(int64_t nsteps)
{
    const double g[3] = {0, 0, -9.81}, dt = 2e-5;
    dem_particle p[216];
    size_t n = lattice(p, 8, 3, 9, -0.0084, -0.0024, 2.4e-3, 0.9e-3, 50, 4242);
    ranks r;
    setup_ranks(&r, dt, g, 1, 1e6, n, p);
    int64_t migrations = 0;
    for (int64_t s = 0; s < nsteps; ++s) {
        size_t nb = dem_world_count(r.W[1]);
        step_ranks(&r);
        migrations += (int64_t)(dem_world_count(r.W[1]) != nb);
    }
    dem_stats st[3];
    TRY(r.R, dem_world_stats(r.R, &st[0]));
    TRY(r.W[0], dem_world_stats(r.W[0], &st[1]));
    TRY(r.W[1], dem_world_stats(r.W[1], &st[2]));
    char nm[200];
    const char *pre = r.verlet ? "Verlet scheme: " : "";
    snprintf(nm, sizeof nm, "%sbed %lld steps: pair contacts of the reference (settled bed; not vacuous)", pre, (long long)nsteps);
    check_range(nm, (double)st[0].pair_contacts, QUICK ? 5 : 100, 2000);
    snprintf(nm, sizeof nm, "%sbed %lld steps: wall contacts A + B vs reference (ghosts have none)", pre, (long long)nsteps);
    check_abs(nm, (double)(st[1].wall_contacts + st[2].wall_contacts), (double)st[0].wall_contacts, 2.0);
    snprintf(nm, sizeof nm, "%sbed %lld steps: removed and inserted counts of A and B (migration counts neither)",
             pre, (long long)nsteps);
    check_abs(nm, (double)(st[1].removed + st[2].removed + st[1].inserted + st[2].inserted),
              (double)n, 0.0);
    snprintf(nm, sizeof nm, "%sbed %lld steps: steps with a migration (not vacuous)", pre, (long long)nsteps);
    check_range(nm, (double)migrations, QUICK ? 0 : 1, 1e9);
    /* A dense bed is chaotic: the round-off of a different force summation
       order (rebuilt lists, owned-ghost pairs evaluated from the other side)
       grows over the settling.  Measured after 2000 steps (x86-64, gcc -O2):
       x 1.3e-13 x 2 mm, v 2.8e-12 x 0.1 m/s, omega 3.7e-12 x 100 1/s,
       momentum 3e-14 (docs/demCore.md); the bounds are ~300x those. */
    snprintf(nm, sizeof nm, "%sbed %lld steps", pre, (long long)nsteps);
    compare_ranks(&r, nm, 5e-11, 1e-9, 1e-9, 2e-3, 0.1, 0.1 / 1e-3);
    verlet_checks(&r, nm, nsteps, 0.2, QUICK ? 1 : 5);
    free_ranks(&r);
}

/*--- (c) call order, pack_ghost, bookkeeping ---------------------------------------------*/
static void order_and_bookkeeping(void)
{
    dem_world *w = make_a(BED_WALLS);
    check_status("step_forces without step_drift: DEM_ERR_STATE", dem_world_step_forces(w), DEM_ERR_STATE);
    printf("# message: %s\n", dem_world_last_error(w));
    TRY(w, dem_world_step(w, 3000)); /* contacts with history by then */
    check_status("step_forces after dem_world_step: DEM_ERR_STATE", dem_world_step_forces(w), DEM_ERR_STATE);
    TRY(w, dem_world_step_drift(w));
    check_status("step_drift while a drift is pending: DEM_ERR_STATE", dem_world_step_drift(w), DEM_ERR_STATE);
    check_status("dem_world_step while a drift is pending: DEM_ERR_STATE", dem_world_step(w, 1), DEM_ERR_STATE);
    printf("# message: %s\n", dem_world_last_error(w));
    check_status("dem_world_step(w, 0) while a drift is pending: DEM_ERR_STATE", dem_world_step(w, 0), DEM_ERR_STATE);
    void *buf = NULL; size_t cap = 0, sz = 0;
    check_status("save_memory while a drift is pending: DEM_ERR_STATE", dem_world_save_memory(w, &buf, &cap, &sz),
                 DEM_ERR_STATE);
    dem_config c;
    dem_config_default(&c);
    check_status("configure while a drift is pending: DEM_ERR_STATE", dem_world_configure(w, &c), DEM_ERR_STATE);
    check_abs("step count after a drift", (double)dem_world_step_count(w), 3001.0, 0.0);
    check_status("step_forces after step_drift", dem_world_step_forces(w), DEM_OK);
    check_status("dem_world_step after the force half", dem_world_step(w, 1), DEM_OK);
    check_status("save_memory between steps", dem_world_save_memory(w, &buf, &cap, &sz), DEM_OK);
    free(buf);

    /* pack_ghost: header only; pack_particle of a particle in contact carries history */
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    int *coord = malloc(A.n_owned * sizeof(int));
    TRY(w, dem_world_particle_contacts(w, coord, NULL));
    size_t ic = 0;
    for (size_t i = 0; i < A.n_owned; ++i) if (coord[i] > coord[ic]) ic = i;
    free(coord);
    size_t sg = 0, sp = 0, s0 = 0;
    TRY(w, dem_world_pack_ghost(w, ic, NULL, &sg));
    TRY(w, dem_world_pack_particle(w, ic, NULL, &sp));
    dem_world *e = make_a(BED_WALLS);
    TRY(e, dem_world_arrays(e, &A));
    TRY(e, dem_world_pack_particle(e, 0, NULL, &s0)); /* no list yet: no history */
    check_abs("pack_ghost size = pack_particle size without history (bytes)", (double)sg, (double)s0, 0.0);
    check_range("pack_particle of a particle in contact carries history (extra bytes)", (double)(sp - sg), 1, 1e9);
    size_t small = sg - 1;
    char *gb = malloc(sg);
    check_status("pack_ghost into a too small buffer: DEM_ERR_RANGE", dem_world_pack_ghost(w, ic, gb, &small),
                 DEM_ERR_RANGE);
    check_status("pack_ghost index out of range: DEM_ERR_RANGE", dem_world_pack_ghost(w, 100000, gb, &sg),
                 DEM_ERR_RANGE);
    free(gb);

    /* bookkeeping: migration counts neither as removed nor as inserted */
    dem_stats s1, s2;
    TRY(w, dem_world_stats(w, &s1));
    char *pb = malloc(sp);
    TRY(w, dem_world_pack_particle(w, ic, pb, &sp));
    TRY(w, dem_world_remove_particle(w, ic, -1));
    TRY(w, dem_world_stats(w, &s2));
    check_abs("remove_particle(-1): stats.removed unchanged", (double)s2.removed, (double)s1.removed, 0.0);
    check_abs("remove_particle(-1): stats.inserted unchanged", (double)s2.inserted, (double)s1.inserted, 0.0);
    TRY(w, dem_world_unpack_particle(w, pb, sp, 0));
    free(pb);
    TRY(w, dem_world_stats(w, &s2));
    check_abs("unpack owned: stats.inserted unchanged", (double)s2.inserted, (double)s1.inserted, 0.0);
    check_abs("unpack owned: count restored", (double)dem_world_count(w), (double)A.n_owned, 0.0);
    int oid;
    TRY(w, dem_world_add_outlet(w, &oid));
    TRY(w, dem_world_remove_particle(w, 0, oid));
    TRY(w, dem_world_stats(w, &s2));
    check_abs("remove_particle(outlet): stats.removed + 1", (double)s2.removed, (double)s1.removed + 1, 0.0);
    int64_t cnt; double mass;
    TRY(w, dem_world_outlet_totals(w, oid, &cnt, &mass));
    check_abs("remove_particle(outlet): outlet count", (double)cnt, 1.0, 0.0);
    dem_world_destroy(&e);
    dem_world_destroy(&w);
}

/*--- (c') pack_particles: m particles in one call -------------------------------------------*/
/* the records equal dem_world_pack_particle's one by one, byte for byte, with
   a valid list and after it is invalidated (the row map path of a migration) */
static void pack_many_case(dem_world *w, const char *when)
{
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    size_t idx[120], m = 0, sg = 0;
    for (size_t i = A.n_owned; i-- > 0 && m < 120;) /* reverse order: records follow index[], not storage */
        if (i % 3) idx[m++] = i;
    size_t *sizes = malloc(m * sizeof *sizes), bytes = 0;
    TRY(w, dem_world_pack_particles(w, idx, m, NULL, &bytes, sizes));
    char *many = malloc(bytes), *one = malloc(bytes + 1);
    size_t got = bytes, at = 0, differ = 0, with_history = 0;
    TRY(w, dem_world_pack_particles(w, idx, m, many, &got, NULL));
    TRY(w, dem_world_pack_ghost(w, 0, NULL, &sg));
    for (size_t q = 0; q < m; ++q) {
        size_t sz = 0;
        TRY(w, dem_world_pack_particle(w, idx[q], NULL, &sz));
        differ += sz != sizes[q];
        with_history += sz > sg;
        if (at + sz <= bytes) TRY(w, dem_world_pack_particle(w, idx[q], one + at, &sz));
        at += sz;
    }
    char nm[160];
    snprintf(nm, sizeof nm, "pack_particles %s: %zu particles: bytes = sum of pack_particle sizes", when, m);
    check_abs(nm, (double)got, (double)at, 0.0);
    snprintf(nm, sizeof nm, "pack_particles %s: records whose size differs from pack_particle's", when);
    check_abs(nm, (double)differ, 0, 0);
    snprintf(nm, sizeof nm, "pack_particles %s: records with contact history (not vacuous)", when);
    check_range(nm, (double)with_history, 10, (double)m);
    snprintf(nm, sizeof nm, "pack_particles %s: bytes differing from the one-by-one packing", when);
    check_abs(nm, at == got ? (double)(memcmp(many, one, got) != 0) : 1.0, 0, 0);
    free(many);
    free(one);
    free(sizes);
}

static void pack_many(void)
{
    dem_world *w = make_a(BED_WALLS);
    TRY(w, dem_world_step(w, 3000)); /* contacts with history by then */
    pack_many_case(w, "valid list");
    size_t idx[3] = {3, 5, 3}, bytes = 0, small;
    char buf[64];
    check_status("pack_particles with an index given twice: DEM_ERR_ARG",
                 dem_world_pack_particles(w, idx, 3, NULL, &bytes, NULL), DEM_ERR_ARG);
    printf("# message: %s\n", dem_world_last_error(w));
    idx[2] = 100000;
    check_status("pack_particles with an index out of range: DEM_ERR_RANGE",
                 dem_world_pack_particles(w, idx, 3, NULL, &bytes, NULL), DEM_ERR_RANGE);
    printf("# message: %s\n", dem_world_last_error(w));
    TRY(w, dem_world_pack_particles(w, idx, 2, NULL, &bytes, NULL));
    small = bytes - 1;
    char *b = malloc(bytes);
    check_status("pack_particles into a buffer one byte too small: DEM_ERR_RANGE",
                 dem_world_pack_particles(w, idx, 2, b, &small, NULL), DEM_ERR_RANGE);
    free(b);
    bytes = 7;
    check_status("pack_particles of no particle", dem_world_pack_particles(w, NULL, 0, buf, &bytes, NULL), DEM_OK);
    check_abs("pack_particles of no particle: bytes", (double)bytes, 0, 0);
    TRY(w, dem_world_invalidate_list(w));
    pack_many_case(w, "invalidated list");
    dem_world_destroy(&w);
}

/*--- (d) ghost order, set_ghost_states, list control ----------------------------------------*/
/* ghost ids at positions 0..ng-1 equal ref[] (count of differences; ng mismatch counts 1000) */
static int ghost_order_diff(dem_world *w, const int64_t *ref, size_t ng)
{
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    if (A.n_ghost != ng) return 1000;
    int d = 0;
    for (size_t k = 0; k < ng; ++k) d += A.id[A.n_owned + k] != ref[k];
    return d;
}

/* dem_world_drift_displacement: after each drift the largest displacement of
   the owned particles since the last list build (positions kept by id right
   after every build, rounded to float as the core keeps them), 0 without a
   pending drift; consistent with list_stale */
static void drift_displacement(void)
{
    check_abs("dem_world_drift_displacement(NULL) = 0", dem_world_drift_displacement(NULL), 0.0, 0.0);
    dem_world *w = make_a(BED_WALLS);
    dem_arrays A0;
    TRY(w, dem_world_arrays(w, &A0));
    int64_t idmax = 0;
    for (size_t i = 0; i < A0.n_owned; ++i) idmax = A0.id[i] > idmax ? A0.id[i] : idmax;
    check_range("drift_displacement: particle ids below 120 (x0 indexed by id)", (double)idmax, 0, 119);
    if (idmax >= 120) { dem_world_destroy(&w); return; }
    check_abs("dem_world_drift_displacement without a pending drift = 0", dem_world_drift_displacement(w), 0.0, 0.0);
    enum { NMAX = 120 };
    double x0[3 * NMAX]; /* kept as the core keeps them: in single precision */
    dem_arrays A;
    int builds = 0, moved = 0;
    double worst = 0, skin = dem_world_skin(w);
    int stale_bad = 0;
    /* the first drift builds the list before it moves (none yet), later
       ones after every stale step */
    TRY(w, dem_world_arrays(w, &A));
    for (size_t i = 0; i < 3 * A.n_owned; ++i) x0[3 * A.id[i / 3] + i % 3] = (float)A.x[i];
    for (int s = 0; s < 3000; ++s) {
        TRY(w, dem_world_step_drift(w));
        TRY(w, dem_world_arrays(w, &A));
        double d = 0;
        for (size_t i = 0; i < A.n_owned; ++i) {
            const double *a = A.x + 3 * i, *b = x0 + 3 * A.id[i];
            d = fmax(d, sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
        }
        const double dc = dem_world_drift_displacement(w);
        worst = fmax(worst, fabs(dc - d));
        moved += d > 0.1 * skin;
        const int stale = dem_world_list_stale(w);
        stale_bad += (2 * dc > skin) && !stale;
        TRY(w, dem_world_step_forces(w));
        if (stale) {
            ++builds;
            TRY(w, dem_world_arrays(w, &A));
            for (size_t i = 0; i < 3 * A.n_owned; ++i) x0[3 * A.id[i / 3] + i % 3] = (float)A.x[i];
        }
    }
    check_abs("drift_displacement vs the largest displacement since the build (float positions) by id [m]", worst, 0.0, 1e-15);
    check_range("drift_displacement: steps with a displacement above skin/10 (not vacuous)", moved, 10, 3000);
    check_range("drift_displacement: list builds in 3000 steps (not vacuous)", builds, 1, 3000);
    check_abs("drift_displacement: steps with 2 d > skin but list_stale 0", stale_bad, 0, 0);
    dem_world_destroy(&w);
}

static void ghost_order_and_list_control(void)
{
    /* skin: auto (0.2 x the largest diameter) before the first build */
    dem_world *w = make_a(PERIODIC_IO);
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    double amax = 0;
    for (size_t i = 0; i < A.n_owned; ++i) amax = fmax(amax, A.radius[i]);
    check_abs("dem_world_skin, auto, before any build = 0.4 x largest radius [m]", dem_world_skin(w), 0.4 * amax, 0.0);
    check_abs("dem_world_skin(NULL) = 0", dem_world_skin(NULL), 0.0, 0.0);
    check_abs("dem_world_list_stale(NULL) = 0", dem_world_list_stale(NULL), 0, 0);
    check_abs("dem_world_list_stale before any build = 1", dem_world_list_stale(w), 1, 0);
    TRY(w, dem_world_step(w, 10));
    check_abs("dem_world_skin, auto, after a build = 0.4 x largest radius [m]", dem_world_skin(w), 0.4 * amax, 0.0);
    check_abs("dem_world_list_stale between steps (valid list) = 0", dem_world_list_stale(w), 0, 0);

    /* five ghosts (ids 1000000 + k) well away from the owned particles */
    dem_world *d = NULL;
    TRY(d, dem_world_create(&d));
    dem_config c;
    dem_config_default(&c);
    TRY(d, dem_world_configure(d, &c));
    dem_material m = test_material(1e7, 0.3, 0.4, 1e-5, 0.6);
    int mid;
    TRY(d, dem_world_add_material(d, &m, &mid));
    enum { NG = 5 };
    dem_particle gp[NG];
    int64_t gid[NG];
    for (int k = 0; k < NG; ++k) {
        gp[k] = test_particle(0.0085, -0.008 + 0.0035 * k, 0.018, 0, 0, 0, 0.8e-3, 2500, 0);
        gp[k].id = gid[k] = 1000000 + 7 * (NG - k); /* descending ids: order not by id */
    }
    TRY(d, dem_world_add_particles(d, NG, gp));
    for (int k = 0; k < NG; ++k) send(d, (size_t)k, w, 1);
    check_abs("ghost ids at positions 0..4 after unpack (differences)", ghost_order_diff(w, gid, NG), 0, 0);

    /* steps with the inlet inserting during step_drift while ghosts exist */
    dem_stats s0, s1;
    int ins_steps = 0, order_bad = 0, stale_bad = 0, quiet_steps = 0, quiet_bad = 0;
    double xvw[9 * NG];
    for (int step = 0; step < 200; ++step) {
        TRY(w, dem_world_stats(w, &s0));
        TRY(w, dem_world_step_drift(w));
        TRY(w, dem_world_stats(w, &s1));
        order_bad += ghost_order_diff(w, gid, NG) != 0;
        if (s1.inserted > s0.inserted) {
            ins_steps++;
            stale_bad += dem_world_list_stale(w) != 1; /* insertion invalidates the list */
        }
        /* refresh the ghost states (unchanged values) without invalidating */
        TRY(w, dem_world_arrays(w, &A));
        for (int k = 0; k < NG; ++k) {
            size_t i = A.n_owned + (size_t)k;
            memcpy(xvw + 9 * k, A.x + 3 * i, 3 * sizeof(double));
            memcpy(xvw + 9 * k + 3, A.v + 3 * i, 3 * sizeof(double));
            memcpy(xvw + 9 * k + 6, A.omega + 3 * i, 3 * sizeof(double));
        }
        int stale = dem_world_list_stale(w);
        int64_t ro = dem_world_reorder_count(w);
        TRY(w, dem_world_set_ghost_states(w, 0, NG, xvw));
        if (!stale) {
            quiet_steps++;
            quiet_bad += dem_world_list_stale(w) != 0 || dem_world_reorder_count(w) != ro ||
                         dem_world_list_invalid(w) != 0;
        }
        TRY(w, dem_world_step_forces(w));
    }
    check_range("inlet: steps inserting during step_drift with ghosts present (not vacuous)", ins_steps, 5, 200);
    check_abs("inlet: steps where the ghost ids at positions 0..4 changed", order_bad, 0, 0);
    check_abs("inlet: insertion steps where dem_world_list_stale is not 1", stale_bad, 0, 0);
    check_range("set_ghost_states: steps with a valid list (not vacuous)", quiet_steps, 5, 200);
    check_abs("set_ghost_states: steps where it made the list stale or changed the reorder count", quiet_bad, 0, 0);
    dem_arrays B;
    TRY(w, dem_world_arrays(w, &B));
    check_abs("ghost position 2 holds id 1000021 after the inlet steps", (double)B.id[B.n_owned + 2], 1000021.0, 0.0);

    /* removal (-1) and owned unpack keep the ghost order */
    size_t sz = 0;
    TRY(w, dem_world_pack_particle(w, 0, NULL, &sz));
    void *pb = malloc(sz);
    TRY(w, dem_world_pack_particle(w, 0, pb, &sz));
    TRY(w, dem_world_remove_particle(w, 0, -1));
    check_abs("dem_world_list_invalid after remove_particle = 1", dem_world_list_invalid(w), 1, 0);
    check_abs("dem_world_list_invalid(NULL) = 0", dem_world_list_invalid(NULL), 0, 0);
    check_abs("dem_world_ghost_displacement with an invalid list = 0 [m]", dem_world_ghost_displacement(w), 0, 0);
    check_abs("remove_particle(-1): ghost order kept (differences)", ghost_order_diff(w, gid, NG), 0, 0);
    TRY(w, dem_world_unpack_particle(w, pb, sz, 0));
    free(pb);
    check_abs("unpack owned: ghost order kept (differences)", ghost_order_diff(w, gid, NG), 0, 0);
    TRY(w, dem_world_step(w, 2)); /* list build: owned re-sorted, ghosts not */
    check_abs("list build with spatial sort: ghost order kept (differences)", ghost_order_diff(w, gid, NG), 0, 0);

    /* set_ghost_states: the values land at their positions; errors */
    TRY(w, dem_world_arrays(w, &A));
    double one[9] = {0.0085, 0.0, 0.019, 0.01, 0.02, 0.03, 1, 2, 3};
    check_range("dem_world_ghost_displacement right after a build: float rounding only [m]",
                dem_world_ghost_displacement(w), 0, 1e-8);
    double dmove = 0;
    for (int k = 0; k < 3; ++k) {
        const double e = one[k] - A.x[3 * (A.n_owned + 3) + (size_t)k];
        dmove += e * e;
    }
    dmove = sqrt(dmove);
    TRY(w, dem_world_set_ghost_states(w, 3, 1, one));
    check_abs("dem_world_ghost_displacement after ghost 3 was moved = its move [m]",
              dem_world_ghost_displacement(w), dmove, 1e-8);
    TRY(w, dem_world_arrays(w, &A));
    size_t i3 = A.n_owned + 3;
    double dset = 0;
    for (int k = 0; k < 3; ++k)
        dset = fmax(dset, fmax(fabs(A.x[3 * i3 + k] - one[k]),
                               fmax(fabs(A.v[3 * i3 + k] - one[3 + k]), fabs(A.omega[3 * i3 + k] - one[6 + k]))));
    check_abs("set_ghost_states: x, v, omega of ghost position 3 as given (max |difference|)", dset, 0.0, 0.0);
    check_status("set_ghost_states [3, 6) of 5 ghosts: DEM_ERR_RANGE", dem_world_set_ghost_states(w, 3, 3, xvw),
                 DEM_ERR_RANGE);
    printf("# message: %s\n", dem_world_last_error(w));
    check_status("set_ghost_states first = 6, count 0: DEM_ERR_RANGE", dem_world_set_ghost_states(w, 6, 0, NULL),
                 DEM_ERR_RANGE);
    check_status("set_ghost_states first = 5, count 0: no-op", dem_world_set_ghost_states(w, 5, 0, NULL), DEM_OK);
    check_status("set_ghost_states xvw NULL: DEM_ERR_ARG", dem_world_set_ghost_states(w, 0, 1, NULL), DEM_ERR_ARG);
    check_status("set_ghost_states(NULL world): DEM_ERR_ARG", dem_world_set_ghost_states(NULL, 0, 1, one), DEM_ERR_ARG);
    double bad[18];
    memcpy(bad, one, sizeof one);
    memcpy(bad + 9, one, sizeof one);
    bad[0] = -0.0031; /* ghost 0: finite, must not be set */
    bad[9 + 4] = NAN;
    check_status("set_ghost_states with a NaN velocity: DEM_ERR_NAN", dem_world_set_ghost_states(w, 0, 2, bad),
                 DEM_ERR_NAN);
    printf("# message: %s\n", dem_world_last_error(w));
    TRY(w, dem_world_arrays(w, &A));
    check_abs("set_ghost_states with a NaN: nothing set (all or nothing; x of ghost 0 unchanged)",
              A.x[3 * A.n_owned] == bad[0] ? 1.0 : 0.0, 0.0, 0.0);
    TRY(w, dem_world_clear_ghosts(w));
    check_status("set_ghost_states without ghosts: DEM_ERR_RANGE", dem_world_set_ghost_states(w, 0, 1, one),
                 DEM_ERR_RANGE);
    dem_world_destroy(&d);
    dem_world_destroy(&w);

    /* invalidate_list: one more build, contact history carried over (a lost
       history would change v by ~ mu g dt = 2e-5 m/s in one step) */
    dem_world *w1 = make_a(BED_WALLS), *w2 = make_a(BED_WALLS);
    TRY(w1, dem_world_step(w1, QUICK ? 800 : 3000));
    TRY(w2, dem_world_step(w2, QUICK ? 800 : 3000));
    dem_stats b0, b1;
    TRY(w2, dem_world_stats(w2, &b0));
    check_status("invalidate_list", dem_world_invalidate_list(w2), DEM_OK);
    check_abs("dem_world_list_stale after invalidate_list = 1", dem_world_list_stale(w2), 1, 0);
    check_status("invalidate_list(NULL): DEM_ERR_ARG", dem_world_invalidate_list(NULL), DEM_ERR_ARG);
    TRY(w1, dem_world_step_drift(w1));
    TRY(w2, dem_world_step_drift(w2));
    check_abs("dem_world_list_stale after a drift following invalidate_list (list built at its start) = 0 or 1",
              dem_world_list_stale(w2) == dem_world_list_stale(w1) ? 0 : 1, 0, 0);
    TRY(w1, dem_world_step_forces(w1));
    TRY(w2, dem_world_invalidate_list(w2)); /* between the halves, as the coupling does */
    TRY(w2, dem_world_step_forces(w2));
    TRY(w2, dem_world_stats(w2, &b1));
    check_abs("invalidate_list before the step and between the halves: list builds + 2",
              (double)(b1.list_builds - b0.list_builds), 2.0, 0.0);
    dem_arrays a1, a2;
    TRY(w1, dem_world_arrays(w1, &a1));
    TRY(w2, dem_world_arrays(w2, &a2));
    double dv = 0;
    int nf = 0;
    for (size_t i = 0; i < a1.n_owned; ++i) {
        size_t j = index_of(&a2, a1.id[i]);
        if (j == (size_t)-1) { nf++; continue; }
        for (int k = 0; k < 3; ++k) dv = fmax(dv, fabs(a1.v[3 * i + k] - a2.v[3 * j + k]));
    }
    check_abs("invalidate_list: ids missing after the rebuilds", nf, 0, 0);
    check_abs("invalidate_list: max |v - v (no invalidation)| / 0.1 m/s after one step (history kept)", dv / 0.1,
              0.0, 1e-11);
    dem_world_destroy(&w1);
    dem_world_destroy(&w2);
}

int main(void)
{
    const int64_t na = QUICK ? 800 : 6000;
    bit_identity(BED_WALLS, "bit identity bed with walls", na);
    bit_identity(BED_COUPLED, "bit identity bed with coupling arrays", na);
    bit_identity(PERIODIC_IO, "bit identity periodic with inlet and outlet", na);
    two_particles("two ranks head-on", 0.0, 0.0, -1e-3);
    two_particles("two ranks oblique, migration in contact", 1e-3, 0.2, -2e-5);
    bed(QUICK ? 300 : 2000);
    check_abs("ghosts moved by a drift or force half (count)", ghost_moved, 0, 0);
    /* (b') Verlet scheme: explicit skin, the same on both ranks (0.2 x the
       largest diameter, as the auto skin of the reference) */
    cfg_skin = 0.4 * 1e-3;
    two_particles("Verlet scheme: two ranks head-on", 0.0, 0.0, -1e-3);
    two_particles("Verlet scheme: two ranks oblique, migration in contact", 1e-3, 0.2, -2e-5);
    cfg_skin = 0.4 * 1.1e-3;
    bed(QUICK ? 300 : 2000);
    cfg_skin = 0;
    order_and_bookkeeping();
    pack_many();
    ghost_order_and_list_control();
    drift_displacement();
    return check_exit();
}
