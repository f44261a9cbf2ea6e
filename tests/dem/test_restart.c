/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Save/restore: a run interrupted by dem_world_save, a fresh handle and
 * dem_world_restore continues bit for bit like the uninterrupted run
 * (particles pouring from an inlet into a box of planes and a triangle-mesh
 * floor, with an outlet, friction history, rolling friction, drag arrays,
 * spatial re-sorting).  Also: pack/unpack round trip of one particle with
 * its contact history, and a corrupt file is refused. */
#include "check.h"
#include <stddef.h>
#include <time.h>

static int floor_inside(const double x[3], void *user) { (void)user; return x[2] > 0.004; }

/* The world of this test; fill: the byte the padding of the caller's
 * configuration and particle template holds (state files must not depend
 * on it). */
static dem_world *setup_filled(unsigned char fill)
{
    const double d = 2e-3;
    dem_world *w = NULL;
    TRY(w, dem_world_create(&w));
    dem_config c;
    dem_config_default(&c);
    memset((char *)&c + sizeof c.contact_law, fill, offsetof(dem_config, dt) - sizeof c.contact_law);
    c.dt = 1e-5;
    for (int k = 0; k < 3; ++k) { c.domain_lo[k] = 0; c.domain_hi[k] = 0.02; }
    c.domain_hi[2] = 0.06;
    c.seed = 99;
    TRY(w, dem_world_configure(w, &c));
    dem_material m = test_material(1e7, 0.3, 0.4, 2e-5, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    double nx[3] = {1, 0, 0}, nmx[3] = {-1, 0, 0}, ny[3] = {0, 1, 0}, nmy[3] = {0, -1, 0};
    double o[3] = {0, 0, 0}, hi[3] = {0.02, 0.02, 0};
    TRY(w, dem_world_add_plane(w, o, nx, mid, NULL, NULL));
    TRY(w, dem_world_add_plane(w, hi, nmx, mid, NULL, NULL));
    TRY(w, dem_world_add_plane(w, o, ny, mid, NULL, NULL));
    TRY(w, dem_world_add_plane(w, hi, nmy, mid, NULL, NULL));
    /* tilted two-triangle floor */
    double v[12] = {0, 0, 0.002, 0.02, 0, 0.0, 0.02, 0.02, 0.0, 0, 0.02, 0.002};
    int t[6] = {0, 1, 2, 0, 2, 3};
    TRY(w, dem_world_add_trimesh(w, 4, v, 2, t, mid, NULL, NULL));
    dem_particle_template tp;
    memset(&tp, fill, sizeof tp);
    tp.diameter.n = tp.density.n = 0;
    tp.diameter.values = tp.diameter.weights = tp.density.values = tp.density.weights = NULL;
    tp.velocity[0] = tp.velocity[1] = tp.velocity[2] = 0;
    tp.diameter.kind = DEM_DIST_UNIFORM; tp.diameter.a = 0.8 * d; tp.diameter.b = 1.2 * d;
    tp.density.kind = DEM_DIST_NORMAL; tp.density.a = 2500; tp.density.b = 100;
    tp.material = mid;
    double lo[3] = {0, 0, 0.004}, hb[3] = {0.02, 0.02, 0.03};
    size_t got;
    TRY(w, dem_world_fill_box(w, lo, hb, floor_inside, NULL, 150, &tp, &got));
    double poly[12] = {0.004, 0.004, 0.05, 0.016, 0.004, 0.05, 0.016, 0.016, 0.05, 0.004, 0.016, 0.05};
    tp.velocity[2] = -0.5;
    TRY(w, dem_world_add_inlet(w, 4, poly, DEM_RATE_NUMBER, 2000.0, 0.0, 1.0, &tp, NULL));
    double op[3] = {0.0185, 0, 0}, on[3] = {1, 0, 0};
    TRY(w, dem_world_add_outlet_plane(w, op, on, NULL));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    for (size_t i = 0; i < A.n_owned; ++i) { A.drag_coeff[i] = 1e-6; A.fluid_velocity[3 * i] = 0.05; }
    return w;
}

static dem_world *setup(void) { return setup_filled(0); }

/* The state of w in memory (caller frees *buf). */
static size_t state_bytes(dem_world *w, void **buf)
{
    size_t cap = 0, size = 0;
    *buf = NULL;
    TRY(w, dem_world_save_memory(w, buf, &cap, &size));
    return size;
}

/* Equal runs give byte-identical state files whatever the padding bytes of
 * the caller's structs held, and a restored state saves to the same bytes:
 * restarted and uninterrupted runs can be compared file by file. */
/* two worlds restored from the state after nsteps of setup() (contacts
   with history), for comparing two ways of doing the same */
static void two_copies(int64_t nsteps, dem_world **p, dem_world **q)
{
    dem_world *s = setup();
    TRY(s, dem_world_step(s, nsteps));
    void *buf;
    size_t nb = state_bytes(s, &buf);
    TRY(*p, dem_world_create(p));
    TRY(*q, dem_world_create(q));
    TRY(*p, dem_world_restore_memory(*p, buf, nb));
    TRY(*q, dem_world_restore_memory(*q, buf, nb));
    free(buf);
    dem_world_destroy(&s);
}

static void check_state_bytes(int64_t nsteps)
{
    dem_world *z = setup_filled(0x00), *g = setup_filled(0xA5);
    TRY(z, dem_world_step(z, nsteps));
    TRY(g, dem_world_step(g, nsteps));
    void *bz, *bg, *br;
    size_t nz = state_bytes(z, &bz), ng = state_bytes(g, &bg);
    check_abs("state bytes: equal runs, caller padding 0x00 vs 0xA5: identical states",
              (double)(nz == ng && !memcmp(bz, bg, nz)), 1.0, 0.0);
    dem_world *r = NULL;
    TRY(r, dem_world_create(&r));
    TRY(r, dem_world_restore_memory(r, bz, nz));
    size_t nr = state_bytes(r, &br);
    check_abs("state bytes: restore then save gives the saved bytes",
              (double)(nr == nz && !memcmp(br, bz, nz)), 1.0, 0.0);
    free(bz); free(bg); free(br);
    dem_world_destroy(&z); dem_world_destroy(&g); dem_world_destroy(&r);
}

static int same(dem_world *a, dem_world *b, double *maxdiff)
{
    dem_arrays A, B;
    TRY(a, dem_world_arrays(a, &A));
    TRY(b, dem_world_arrays(b, &B));
    *maxdiff = 0;
    if (A.n_owned != B.n_owned) { *maxdiff = INFINITY; return 0; }
    size_t n = A.n_owned;
    int ok = memcmp(A.x, B.x, 3 * n * sizeof(double)) == 0 && memcmp(A.v, B.v, 3 * n * sizeof(double)) == 0 &&
             memcmp(A.omega, B.omega, 3 * n * sizeof(double)) == 0 && memcmp(A.id, B.id, n * sizeof(int64_t)) == 0 &&
             memcmp(A.drag_impulse, B.drag_impulse, 3 * n * sizeof(double)) == 0;
    for (size_t i = 0; i < 3 * n; ++i) *maxdiff = fmax(*maxdiff, fabs(A.x[i] - B.x[i]) + fabs(A.v[i] - B.v[i]));
    return ok;
}

/* p and q run nsteps on and stay bit-identical */
static void same_after(dem_world *p, dem_world *q, int64_t nsteps, const char *what)
{
    TRY(p, dem_world_step(p, nsteps));
    TRY(q, dem_world_step(q, nsteps));
    double md;
    const int ok = same(p, q, &md);
    printf("%s: %s, %lld steps on: max |dx|+|dv| %g vs 0 (tol exact, memcmp)\n", ok ? "PASS" : "FAIL", what,
           (long long)nsteps, md);
    if (!ok) check_failures++;
}

int main(void)
{
    /* outside the source tree, unique per run (normal and sanitizer runs may overlap) */
    char path[512];
    const char *tmp = getenv("TMPDIR");
    int here;
    snprintf(path, sizeof path, "%s/dem_restart_test_%lx_%lx.state", tmp && *tmp ? tmp : "/tmp",
             (unsigned long)time(NULL), (unsigned long)(size_t)&here);
    const int64_t n1 = QUICK ? 2000 : 6000, n2 = QUICK ? 2000 : 6000;
    dem_world *a = setup(), *b = setup();
    TRY(a, dem_world_step(a, n1 + n2));
    TRY(b, dem_world_step(b, n1));
    TRY(b, dem_world_save(b, path));
    dem_world_destroy(&b);
    dem_world *c = NULL;
    TRY(c, dem_world_create(&c));
    TRY(c, dem_world_restore(c, path));
    TRY(c, dem_world_step(c, n2));
    double md;
    int ok = same(a, c, &md);
    printf("%s: restart bit-identical after %lld + %lld steps: max |dx|+|dv| %g vs 0 (tol exact, memcmp)\n",
           ok ? "PASS" : "FAIL", (long long)n1, (long long)n2, md);
    if (!ok) check_failures++;
    dem_stats sa, sc;
    TRY(a, dem_world_stats(a, &sa));
    TRY(c, dem_world_stats(c, &sc));
    check_abs("restart: inserted by inlet+fill equal", (double)sc.inserted, (double)sa.inserted, 0.0);
    check_abs("restart: removed by outlet equal", (double)sc.removed, (double)sa.removed, 0.0);
    check_below("restart: inlet inserted particles", 150.0 - (double)sa.inserted, 0.0);
    int64_t ca, cc; double ma, mc;
    TRY(a, dem_world_outlet_totals(a, 0, &ca, &ma));
    TRY(c, dem_world_outlet_totals(c, 0, &cc, &mc));
    check_abs("restart: outlet count equal", (double)cc, (double)ca, 0.0);
    check_abs("restart: outlet mass equal", mc, ma, 0.0);
    check_abs("restart: time equal", dem_world_time(c), dem_world_time(a), 0.0);
    {
        /* the configuration of the restored world is the saved one
           (demSplitState takes the periodic box from it) */
        dem_config ga, gc;
        TRY(a, dem_world_get_config(a, &ga));
        TRY(c, dem_world_get_config(c, &gc));
        check_abs("restart: dem_world_get_config: domain_hi[2] [m]", gc.domain_hi[2], 0.06, 0.0);
        int differ = ga.contact_law != gc.contact_law || ga.dt != gc.dt || ga.skin != gc.skin;
        for (int k = 0; k < 3; ++k)
            differ += ga.periodic[k] != gc.periodic[k] || ga.domain_lo[k] != gc.domain_lo[k]
                      || ga.domain_hi[k] != gc.domain_hi[k] || ga.gravity[k] != gc.gravity[k];
        check_abs("restart: dem_world_get_config: law, dt, skin, box, periodicity, gravity that differ from the saving world's",
                  (double)differ, 0.0, 0.0);
        check_status("dem_world_get_config without a config", dem_world_get_config(c, NULL), DEM_ERR_ARG);
    }

    check_state_bytes(n1);

    /* dem_world_remove_unkept against repeated remove_particle(i, -1) from
       the highest index down, on the state after n1 steps (contacts with
       history): the same particles in the same order, and the same run
       after it (pairs of two removed particles are not kept pending, which
       a list build drops anyway) */
    {
        dem_world *p = NULL, *q = NULL;
        two_copies(n1, &p, &q);
        const size_t n = dem_world_count(p);
        unsigned char *keep = malloc(n);
        for (size_t i = 0; i < n; ++i) keep[i] = (unsigned char)(i % 3 != 1 && i % 7 != 0);
        for (size_t i = n; i-- > 0;)
            if (!keep[i]) TRY(p, dem_world_remove_particle(p, i, -1));
        TRY(q, dem_world_remove_unkept(q, keep));
        double md;
        int ok = same(p, q, &md) && dem_world_count(q) < n;
        printf("%s: remove_unkept vs remove_particle from the top: the same %zu of %zu particles in the same order: "
               "max |dx|+|dv| %g vs 0 (tol exact, memcmp)\n", ok ? "PASS" : "FAIL", dem_world_count(q), n, md);
        if (!ok) check_failures++;
        same_after(p, q, n2, "remove_unkept vs remove_particle from the top");
        check_status("remove_unkept without a mask", dem_world_remove_unkept(q, NULL), DEM_ERR_ARG);
        /* a processor that holds none: an empty mask (NULL from an empty
           std::vector) is not an error */
        {
            dem_world *e = NULL;
            TRY(e, dem_world_create(&e));
            check_status("remove_unkept of an empty world without a mask", dem_world_remove_unkept(e, NULL), DEM_OK);
            dem_world_destroy(&e);
        }
        free(keep);
        dem_world_destroy(&p); dem_world_destroy(&q);
    }

    /* dem_world_remove_particles (one call, indices in any order, some
       booked on outlet 0, some on none) against repeated remove_particle
       from the highest index down: the same particles in the same order,
       the same outlet books, and the same run after it */
    {
        dem_world *p = NULL, *q = NULL;
        two_copies(n1, &p, &q);
        const size_t n = dem_world_count(p);
        size_t *idx = malloc(n * sizeof *idx), m = 0;
        int *out = malloc(n * sizeof *out);
        /* ascending, then listed odd positions first (any order is allowed) */
        for (size_t i = 0; i < n; ++i)
            if (i % 5 == 2 || i % 11 == 0) { idx[m] = i; out[m] = i % 2 ? 0 : -1; ++m; }
        for (size_t i = n; i-- > 0;)
            for (size_t k = 0; k < m; ++k)
                if (idx[k] == i) TRY(p, dem_world_remove_particle(p, i, out[k]));
        for (size_t k = 0; k + 1 < m; k += 2) {
            size_t t = idx[k]; idx[k] = idx[k + 1]; idx[k + 1] = t;
            int o = out[k]; out[k] = out[k + 1]; out[k + 1] = o;
        }
        TRY(q, dem_world_remove_particles(q, idx, out, m));
        double md;
        int ok = same(p, q, &md) && dem_world_count(q) + m == n;
        printf("%s: remove_particles vs remove_particle from the top: the same %zu of %zu particles in the same order: "
               "max |dx|+|dv| %g vs 0 (tol exact, memcmp)\n", ok ? "PASS" : "FAIL", dem_world_count(q), n, md);
        if (!ok) check_failures++;
        int64_t cp, cq; double mp, mq;
        TRY(p, dem_world_outlet_totals(p, 0, &cp, &mp));
        TRY(q, dem_world_outlet_totals(q, 0, &cq, &mq));
        check_abs("remove_particles: outlet 0 count as the repeated calls'", (double)cq, (double)cp, 0.0);
        check_abs("remove_particles: outlet 0 mass as the repeated calls'", mq, mp, 0.0);
        check_below("remove_particles: some booked on outlet 0", 1.0 - (double)cq, 0.0);
        same_after(p, q, n2, "remove_particles vs remove_particle from the top");
        const size_t twice[2] = {0, 0}, beyond[1] = {dem_world_count(q)};
        const int badOutlet[1] = {7};
        check_status("remove_particles: an index given twice", dem_world_remove_particles(q, twice, NULL, 2),
                     DEM_ERR_ARG);
        check_status("remove_particles: an index beyond the owned", dem_world_remove_particles(q, beyond, NULL, 1),
                     DEM_ERR_RANGE);
        check_status("remove_particles: an outlet not defined", dem_world_remove_particles(q, twice, badOutlet, 1),
                     DEM_ERR_NOTFOUND);
        check_status("remove_particles: none (m = 0, no index array)", dem_world_remove_particles(q, NULL, NULL, 0),
                     DEM_OK);
        check_abs("remove_particles: refused calls removed nothing", (double)dem_world_count(q),
                  (double)dem_world_count(p), 0.0);
        free(idx); free(out);
        dem_world_destroy(&p); dem_world_destroy(&q);
    }

    /* in-memory checkpoint (demFoam's last good state): save after n1 steps,
       run on by n2/2 steps, go back and run n2: bit-identical to a; a
       truncated buffer is refused and leaves the world as it was */
    {
        dem_world *m = setup();
        TRY(m, dem_world_step(m, n1));
        void *snap = NULL;
        size_t snapSize = 0, snapCap = 0;
        TRY(m, dem_world_save_memory(m, &snap, &snapCap, &snapSize));
        /* a second save reuses the buffer and gives the same bytes */
        void *first = malloc(snapSize);
        memcpy(first, snap, snapSize);
        void *before = snap;
        size_t size2 = 0;
        TRY(m, dem_world_save_memory(m, &snap, &snapCap, &size2));
        check_abs("checkpoint: second save into the same buffer", (double)(snap == before), 1.0, 0.0);
        check_abs("checkpoint: second save same bytes", (double)(size2 == snapSize && !memcmp(first, snap, snapSize)), 1.0, 0.0);
        free(first);
        TRY(m, dem_world_step(m, n2 / 2));
        const size_t nBefore = dem_world_count(m);
        const double tBefore = dem_world_time(m);
        check_status("checkpoint: truncated buffer refused",
                     dem_world_restore_memory(m, snap, snapSize / 2), DEM_ERR_FORMAT);
        check_abs("checkpoint: refused restore leaves the time", dem_world_time(m), tBefore, 0.0);
        check_abs("checkpoint: refused restore leaves the count", (double)dem_world_count(m), (double)nBefore, 0.0);
        TRY(m, dem_world_restore_memory(m, snap, snapSize));
        free(snap);
        TRY(m, dem_world_step(m, n2));
        double mdm;
        int okm = same(a, m, &mdm);
        printf("%s: checkpoint in memory: back and on bit-identical: max |dx|+|dv| %g vs 0 (tol exact, memcmp)\n",
               okm ? "PASS" : "FAIL", mdm);
        if (!okm) check_failures++;

        /* dem_world_max_dt is the bound dem_world_step enforces */
        double dtMax = 0;
        TRY(m, dem_world_max_dt(m, &dtMax));
        check_range("max_dt: finite and above the configured step 1e-5 s that steps fine", dtMax, 1e-5, 1.0);
        dem_world_destroy(&m);
    }

    /* pack/unpack: move particle 0 out and back in; the run stays bit-identical
       to one where nothing moved except storage order */
    dem_world *p = setup(), *q = setup();
    TRY(p, dem_world_step(p, 9000));
    TRY(q, dem_world_step(q, 9000));
    size_t sz = 0, ip = 0;
    int *coord = calloc(dem_world_count(p), sizeof(int));
    TRY(p, dem_world_particle_contacts(p, coord, NULL));
    for (size_t i = 0; i < dem_world_count(p); ++i) if (coord[i] > coord[ip]) ip = i;
    int z0 = coord[ip];
    free(coord);
    check_below("pack: moved particle has contacts to carry", -(double)z0, 0.0);
    TRY(p, dem_world_pack_particle(p, ip, NULL, &sz));
    char *buf = malloc(sz);
    TRY(p, dem_world_pack_particle(p, ip, buf, &sz));
    TRY(p, dem_world_remove_particle(p, ip, -1));
    TRY(p, dem_world_unpack_particle(p, buf, sz, 0));
    free(buf);
    /* the unpack dropped the neighbour list: the coordination is not known
       (an error, not zeros) until the next step */
    int *cp = calloc(dem_world_count(p), sizeof(int));
    check_status("particle_contacts after remove + unpack: DEM_ERR_STATE",
                 dem_world_particle_contacts(p, cp, NULL), DEM_ERR_STATE);
    free(cp);
    check_status("contact forces alone after remove + unpack: still those of the last evaluation",
                 dem_world_particle_contacts(p, NULL, NULL), DEM_OK);
    TRY(p, dem_world_step(p, 1));
    TRY(q, dem_world_step(q, 1));
    /* compare by id */
    dem_arrays P, Q;
    TRY(p, dem_world_arrays(p, &P));
    TRY(q, dem_world_arrays(q, &Q));
    /* (the step may insert: size by the counts after it) */
    cp = calloc(P.n_owned + 1, sizeof(int));
    int *cq = calloc(Q.n_owned + 1, sizeof(int));
    TRY(p, dem_world_particle_contacts(p, cp, NULL));
    TRY(q, dem_world_particle_contacts(q, cq, NULL));
    long zdiff = 0, zq = 0;
    for (size_t i = 0; i < Q.n_owned; ++i) {
        zq += cq[i];
        for (size_t j = 0; j < P.n_owned; ++j)
            if (P.id[j] == Q.id[i]) zdiff += labs((long)cp[j] - (long)cq[i]);
    }
    free(cp); free(cq);
    check_below("pack/unpack: contacts counted after the next step (sum over the bed > 0)", -(double)zq, 0.0);
    check_abs("pack/unpack: coordination by id after the next step as without the move", (double)zdiff, 0.0, 0.0);
    double dmax = 0;
    for (size_t i = 0; i < Q.n_owned; ++i)
        for (size_t j = 0; j < P.n_owned; ++j)
            if (P.id[j] == Q.id[i])
                for (int k = 0; k < 3; ++k)
                    dmax = fmax(dmax, fabs(P.v[3 * j + k] - Q.v[3 * i + k]) + fabs(P.omega[3 * j + k] - Q.omega[3 * i + k]) * 1e-3);
    check_below("pack/unpack with history: max velocity difference after 1 step [m/s]", dmax, 1e-12);
    dem_world_destroy(&p);
    dem_world_destroy(&q);

    /* corrupt file */
    FILE *f = fopen(path, "r+b");
    if (f) { fseek(f, 0, SEEK_SET); fputc('X', f); fclose(f); }
    dem_world *e = NULL;
    TRY(e, dem_world_create(&e));
    check_status("restore of a corrupt file", dem_world_restore(e, path), DEM_ERR_FORMAT);
    check_status("restore of a missing file", dem_world_restore(e, "no/such/file.state"), DEM_ERR_IO);
    dem_world_destroy(&e);
    remove(path);
    dem_world_destroy(&a);
    dem_world_destroy(&c);
    return check_exit();
}
