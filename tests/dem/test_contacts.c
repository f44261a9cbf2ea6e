/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Per-contact output (dem_world_record_contacts, dem_world_contacts):
 * - two spheres pressed together, no damping or friction: the reported
 *   normal force is Hertz's (4/3) E* sqrt(R*) delta^(3/2) (Johnson, Contact
 *   Mechanics, 1985, sec. 4.2) at the reported overlap (1e-12 relative; the
 *   kernel evaluates the same expression in another order), the overlap is
 *   that of the positions (1e-12), force_n + force_t is the particle's
 *   contact force bit for bit, and m dv over one step equals
 *   dt/2 (F_old + F_new) of velocity Verlet (1e-12 relative, round-off);
 * - a sphere on a rigid plane: E* = E/(1 - nu^2), R* = a, the wall id;
 *   on the shared edge of a two-triangle mesh: one contact, Hertz's force;
 * - a sheared contact, every law: a tangential force normal to n (1e-12),
 *   against the relative sliding velocity, within mu |f_n|;
 * - a small periodic bed per law: per particle, the reported forces sum to
 *   its contact force (1e-12 of the sum of the magnitudes: summation order),
 *   no pair twice, the count is dem_stats' pair + wall contacts, and the
 *   same bed without recording ends bit-identical; again with two
 *   materials and damping_predicted (the general pair loops);
 * - an owned-ghost contact is reported once, flagged;
 * - errors: buffer too small, recording off, particles changed, NULLs. */
#include "check.h"
#include <stdint.h>

static const dem_contact_law laws[4] = {DEM_CONTACT_HERTZ_MINDLIN, DEM_CONTACT_LINEAR_SPRING_DASHPOT,
                                        DEM_CONTACT_HERTZ_SPRING_DASHPOT, DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP};

static dem_material law_material(dem_contact_law law, double mu, double e)
{
    dem_material m = test_material(1e7, 0.3, mu, 0.0, e);
    if (law == DEM_CONTACT_LINEAR_SPRING_DASHPOT || law == DEM_CONTACT_HERTZ_SPRING_DASHPOT) {
        m.youngs_modulus = 0; m.stiffness_n = 1000.0; m.stiffness_t = -1;
    }
    return m;
}

/* the one contact of w (count checked) */
static dem_contact one_contact(dem_world *w, const char *what)
{
    dem_contact c[2];
    memset(c, 0, sizeof c);
    size_t n = 0;
    TRY(w, dem_world_contacts(w, c, 2, &n));
    char name[160];
    snprintf(name, sizeof name, "%s: number of contacts", what);
    check_abs(name, (double)n, 1.0, 0.0);
    return c[0];
}

static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* largest |a_k - b_k| (exact comparison: 0) */
static double maxdiff3(const double *a, const double *b)
{
    double m = 0;
    for (int k = 0; k < 3; ++k) m = fmax(m, fabs(a[k] - b[k]));
    return m;
}

static void hertz_pair(void)
{
    const double a = 1e-3, rho = 2500, E = 1e7, nu = 0.3, d0 = 2e-5, dt = 1e-7;
    const double m = rho * 4.0 / 3.0 * M_PI * a * a * a;
    const double estar = E / (2.0 * (1.0 - nu * nu)), rstar = 0.5 * a;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, dt, NULL, 0.01);
    dem_material mat = test_material(E, nu, 0.0, 0.0, 1.0);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    dem_particle p[2] = {test_particle(a - 0.5 * d0, 0, 0, 0, 0, 0, a, rho, mid),
                         test_particle(-(a - 0.5 * d0), 0, 0, 0, 0, 0, a, rho, mid)};
    p[0].id = 7; p[1].id = 3;
    TRY(w, dem_world_add_particles(w, 2, p));
    TRY(w, dem_world_record_contacts(w, 1));
    TRY(w, dem_world_step(w, 1));
    dem_contact c1 = one_contact(w, "pressed pair");
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    size_t ia = A.id[0] == c1.id_a ? 0 : 1, ib = 1 - ia;
    check_abs("pressed pair: particle-particle (wall flag 0, ghost 0)", (double)(c1.wall + c1.ghost), 0.0, 0.0);
    check_abs("pressed pair: ids {7, 3}", (double)(c1.id_a + c1.id_b) + 100.0 * fabs((double)(c1.id_a - c1.id_b)),
              10.0 + 400.0, 0.0);
    double dx[3] = {A.x[3 * ia] - A.x[3 * ib], A.x[3 * ia + 1] - A.x[3 * ib + 1], A.x[3 * ia + 2] - A.x[3 * ib + 2]};
    double r = norm3(dx);
    check_rel("pressed pair: overlap vs 2a - |x_a - x_b| [m]", c1.overlap, 2 * a - r, 1e-12);
    double nref[3] = {dx[0] / r, dx[1] / r, dx[2] / r};
    check_abs("pressed pair: normal vs (x_a - x_b)/|x_a - x_b|", maxdiff3(c1.normal, nref), 0.0, 1e-15);
    const double fh = 4.0 / 3.0 * estar * sqrt(rstar) * pow(c1.overlap, 1.5);
    check_rel("pressed pair: |force_n| vs Hertz (4/3) E* sqrt(R*) delta^1.5 [N]", norm3(c1.force_n), fh, 1e-12);
    check_rel("pressed pair: force_n . normal (repulsive, on a) [N]",
              c1.force_n[0] * c1.normal[0] + c1.force_n[1] * c1.normal[1] + c1.force_n[2] * c1.normal[2], fh, 1e-12);
    check_abs("pressed pair: |force_t| (mu = 0) [N]", norm3(c1.force_t), 0.0, 0.0);
    double f[6];
    TRY(w, dem_world_particle_contacts(w, NULL, f));
    double F1[3] = {c1.force_n[0] + c1.force_t[0], c1.force_n[1] + c1.force_t[1], c1.force_n[2] + c1.force_t[2]};
    check_abs("pressed pair: force_n + force_t vs the core's contact force on a (bits)", maxdiff3(F1, f + 3 * ia), 0.0, 0.0);
    double mF1[3] = {-F1[0], -F1[1], -F1[2]};
    check_abs("pressed pair: -(force_n + force_t) vs the contact force on b (bits)", maxdiff3(mF1, f + 3 * ib), 0.0, 0.0);
    /* one more step: m (v_new - v_old) = dt/2 (F_old + F_new) (velocity Verlet, no gravity) */
    double v1 = A.v[3 * ia];
    TRY(w, dem_world_step(w, 1));
    dem_contact c2 = one_contact(w, "pressed pair, second step");
    TRY(w, dem_world_arrays(w, &A));
    ia = A.id[0] == c1.id_a ? 0 : 1;
    double dp = m * (A.v[3 * ia] - v1);
    double imp = 0.5 * dt * (F1[0] + c2.force_n[0] + c2.force_t[0]);
    check_rel("pressed pair: m dv over one step vs dt/2 (F_old + F_new) [N s]", dp, imp, 1e-12);
    dem_world_destroy(&w);
}

static void hertz_wall(void)
{
    const double a = 1e-3, rho = 2500, E = 1e7, nu = 0.3, d0 = 1e-5, dt = 1e-7;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, dt, NULL, 0.01);
    dem_material mat = test_material(E, nu, 0.0, 0.0, 1.0), rig = test_material(DEM_RIGID, 0.25, 0.0, 0.0, 1.0);
    int mid, rid, wid0, wid1;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    TRY(w, dem_world_add_material(w, &rig, &rid));
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1}, p1[3] = {0, 0, 0.005}, nm[3] = {0, 0, -1};
    TRY(w, dem_world_add_plane(w, p1, nm, rid, NULL, &wid0));   /* far away: no contact */
    TRY(w, dem_world_add_plane(w, p0, nz, rid, NULL, &wid1));
    dem_particle p = test_particle(0, 0, a - d0, 0, 0, 0, a, rho, mid);
    TRY(w, dem_world_add_particles(w, 1, &p));
    TRY(w, dem_world_record_contacts(w, 1));
    TRY(w, dem_world_step(w, 1));
    dem_contact c = one_contact(w, "sphere on rigid plane");
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    check_abs("sphere on plane: wall flag 1, id_b = wall id", (double)(c.wall * 100 + c.id_b), 100.0 + wid1, 0.0);
    check_abs("sphere on plane: id_a", (double)c.id_a, (double)A.id[0], 0.0);
    check_rel("sphere on plane: overlap vs a - z [m]", c.overlap, a - A.x[2], 1e-12);
    const double fh = 4.0 / 3.0 * E / (1.0 - nu * nu) * sqrt(a) * pow(c.overlap, 1.5);
    check_rel("sphere on plane: force_n z vs Hertz with E* = E/(1-nu^2), R* = a [N]", c.force_n[2], fh, 1e-12);
    check_abs("sphere on plane: force_n x, y [N]", fabs(c.force_n[0]) + fabs(c.force_n[1]), 0.0, 0.0);
    double f[3];
    TRY(w, dem_world_particle_contacts(w, NULL, f));
    double F[3] = {c.force_n[0] + c.force_t[0], c.force_n[1] + c.force_t[1], c.force_n[2] + c.force_t[2]};
    check_abs("sphere on plane: force_n + force_t vs the core's contact force (bits)", maxdiff3(F, f), 0.0, 0.0);
    dem_world_destroy(&w);
}

/* a sphere pressed onto the shared edge of two triangles: one contact */
static void mesh_wall(void)
{
    const double a = 1e-3, rho = 2500, E = 1e7, nu = 0.3, d0 = 1e-5, h = 4e-3;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-7, NULL, 0.01);
    dem_material mat = test_material(E, nu, 0.0, 0.0, 1.0), rig = test_material(DEM_RIGID, 0.25, 0.0, 0.0, 1.0);
    int mid, rid, wid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    TRY(w, dem_world_add_material(w, &rig, &rid));
    const double v[12] = {-h, -h, 0, h, -h, 0, h, h, 0, -h, h, 0};
    const int tri[6] = {0, 1, 2, 0, 2, 3};
    TRY(w, dem_world_add_trimesh(w, 4, v, 2, tri, rid, NULL, &wid));
    dem_particle p = test_particle(0, 0, a - d0, 0, 0, 0, a, rho, mid);
    TRY(w, dem_world_add_particles(w, 1, &p));
    TRY(w, dem_world_record_contacts(w, 1));
    TRY(w, dem_world_step(w, 1));
    dem_contact c = one_contact(w, "sphere on the shared edge of a mesh");
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    check_abs("sphere on mesh: wall flag 1, id_b = mesh wall id", (double)(c.wall * 100 + c.id_b), 100.0 + wid, 0.0);
    check_rel("sphere on mesh: overlap vs a - z [m]", c.overlap, a - A.x[2], 1e-12);
    const double fh = 4.0 / 3.0 * E / (1.0 - nu * nu) * sqrt(a) * pow(c.overlap, 1.5);
    check_rel("sphere on mesh: force_n z vs Hertz, rigid mesh [N]", c.force_n[2], fh, 1e-12);
    dem_world_destroy(&w);
}

static void sheared(dem_contact_law law)
{
    const double a = 1e-3, rho = 2500, d0 = 2e-5, dt = 1e-6, vs = 0.02, mu = 0.5;
    char name[200];
    const char *ln = dem_contact_law_name(law);
    dem_world *w = test_world(law, dt, NULL, 0.01);
    dem_material mat = law_material(law, mu, 0.8);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    /* a moves +y, b -y: a's sliding velocity relative to b is +2 vs y */
    dem_particle p[2] = {test_particle(a - 0.5 * d0, 0, 0, 0, vs, 0, a, rho, mid),
                         test_particle(-(a - 0.5 * d0), 0, 0, 0, -vs, 0, a, rho, mid)};
    p[0].id = 0; p[1].id = 1;
    TRY(w, dem_world_add_particles(w, 2, p));
    TRY(w, dem_world_record_contacts(w, 1));
    TRY(w, dem_world_step(w, 20));
    snprintf(name, sizeof name, "sheared %s", ln);
    dem_contact c = one_contact(w, name);
    double sgn = c.id_a == 0 ? 1.0 : -1.0;   /* a's sliding direction */
    double ft = norm3(c.force_t), fn = norm3(c.force_n);
    snprintf(name, sizeof name, "sheared %s: |force_t| > 0 [N]", ln);
    check_range(name, ft, 1e-12, INFINITY);
    snprintf(name, sizeof name, "sheared %s: force_t . normal / |force_t|", ln);
    check_abs(name, (c.force_t[0] * c.normal[0] + c.force_t[1] * c.normal[1] + c.force_t[2] * c.normal[2]) / ft, 0.0, 1e-12);
    snprintf(name, sizeof name, "sheared %s: force_t y against a's sliding / |force_t|", ln);
    check_range(name, -sgn * c.force_t[1] / ft, 0.99, 1.0 + 1e-12);
    snprintf(name, sizeof name, "sheared %s: |force_t| / (mu |force_n|)", ln);
    check_range(name, ft / (mu * fn), 0.0, 1.0 + 1e-12);
    double f[6];
    TRY(w, dem_world_particle_contacts(w, NULL, f));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    size_t ia = A.id[0] == c.id_a ? 0 : 1;
    double F[3] = {c.force_n[0] + c.force_t[0], c.force_n[1] + c.force_t[1], c.force_n[2] + c.force_t[2]};
    snprintf(name, sizeof name, "sheared %s: force_n + force_t vs the core's contact force (bits)", ln);
    check_abs(name, maxdiff3(F, f + 3 * ia), 0.0, 0.0);
    dem_world_destroy(&w);
}

/* A periodic bed of 150 spheres on a floor; rec: record contacts; mixed:
 * a second material for the floor and damping_predicted (the general pair
 * loops). */
static dem_world *bed(dem_contact_law law, int rec, int mixed, int64_t nsteps)
{
    const double d = 2e-3, L = 6 * d;
    dem_world *w = NULL;
    TRY(w, dem_world_create(&w));
    dem_config c;
    dem_config_default(&c);
    c.contact_law = law;
    c.dt = 1e-5;   /* < 0.2 x Rayleigh time of the smallest sphere, 6.9e-5 s */
    c.domain_lo[0] = c.domain_lo[1] = 0; c.domain_hi[0] = c.domain_hi[1] = L;
    c.periodic[0] = c.periodic[1] = 1;
    c.domain_lo[2] = 0; c.domain_hi[2] = 0.05;
    c.seed = 11;
    c.damping_predicted = mixed;
    TRY(w, dem_world_configure(w, &c));
    dem_material m = law_material(law, 0.4, 0.5);
    m.rolling_friction = 2e-5;
    int mid, fid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    fid = mid;
    if (mixed) {
        dem_material f = m;
        f.friction = 0.3; f.restitution = 0.7;
        TRY(w, dem_world_add_material(w, &f, &fid));
    }
    double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, p0, nz, fid, NULL, NULL));
    dem_particle_template t;
    memset(&t, 0, sizeof t);
    t.diameter.kind = DEM_DIST_UNIFORM; t.diameter.a = 0.8 * d; t.diameter.b = d;
    t.density.kind = DEM_DIST_FIXED; t.density.a = 2500;
    t.material = mid;
    double lo[3] = {0, 0, 0.5 * d}, hi[3] = {L, L, 0.02};
    size_t got = 0;
    TRY(w, dem_world_fill_box(w, lo, hi, NULL, NULL, 150, &t, &got));
    if (rec) TRY(w, dem_world_record_contacts(w, 1));
    TRY(w, dem_world_step(w, nsteps));
    return w;
}

static int cmp_pair(const void *x, const void *y)
{
    const int64_t *a = x, *b = y;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    if (a[1] != b[1]) return a[1] < b[1] ? -1 : 1;
    return 0;
}

static void bed_sums(dem_contact_law law, int mixed)
{
    char ln[120], name[240];
    snprintf(ln, sizeof ln, "%s%s", dem_contact_law_name(law), mixed ? " (2 materials, damping_predicted)" : "");
    const int64_t nsteps = QUICK ? 3000 : 8000;
    dem_world *w = bed(law, 1, mixed, nsteps), *w0 = bed(law, 0, mixed, nsteps);
    size_t nc = 0;
    TRY(w, dem_world_contacts(w, NULL, 0, &nc));
    dem_contact *c = malloc((nc + 1) * sizeof *c);
    size_t nc2 = 0;
    TRY(w, dem_world_contacts(w, c, nc, &nc2));
    dem_stats st;
    TRY(w, dem_world_stats(w, &st));
    snprintf(name, sizeof name, "bed %s: contacts vs stats pair + wall contacts", ln);
    check_abs(name, (double)nc2, (double)(st.pair_contacts + st.wall_contacts), 0.0);
    snprintf(name, sizeof name, "bed %s: wall contacts present (settled on the floor)", ln);
    check_range(name, (double)st.wall_contacts, 1.0, 1e9);
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    const size_t n = A.n_owned;
    int64_t idmax = 0;
    for (size_t i = 0; i < n; ++i) if (A.id[i] > idmax) idmax = A.id[i];
    size_t *at = malloc((size_t)(idmax + 1) * sizeof *at);
    double *sum = calloc(3 * n, sizeof *sum), *mag = calloc(n, sizeof *mag), *f = malloc(3 * n * sizeof *f);
    int64_t *pairs = malloc(2 * (nc + 1) * sizeof *pairs);
    size_t np = 0;
    for (size_t i = 0; i < n; ++i) at[A.id[i]] = i;
    for (size_t k = 0; k < nc; ++k) {
        const dem_contact *q = c + k;
        size_t ia = at[q->id_a];
        double F[3] = {q->force_n[0] + q->force_t[0], q->force_n[1] + q->force_t[1], q->force_n[2] + q->force_t[2]};
        for (int d = 0; d < 3; ++d) sum[3 * ia + d] += F[d];
        mag[ia] += norm3(F);
        if (!q->wall) {
            size_t ib = at[q->id_b];
            for (int d = 0; d < 3; ++d) sum[3 * ib + d] -= F[d];
            mag[ib] += norm3(F);
            pairs[2 * np] = q->id_a < q->id_b ? q->id_a : q->id_b;
            pairs[2 * np + 1] = q->id_a < q->id_b ? q->id_b : q->id_a;
            np++;
        }
    }
    TRY(w, dem_world_particle_contacts(w, NULL, f));
    double worst = 0;
    for (size_t i = 0; i < n; ++i) {
        double e = maxdiff3(sum + 3 * i, f + 3 * i);
        double r = mag[i] > 0 ? e / mag[i] : (e > 0 ? INFINITY : 0.0);
        if (r > worst) worst = r;
    }
    snprintf(name, sizeof name, "bed %s: max over particles |sum of reported forces - contact force| / sum |F|", ln);
    check_abs(name, worst, 0.0, 1e-12);
    qsort(pairs, np, 2 * sizeof *pairs, cmp_pair);
    size_t dup = 0;
    for (size_t k = 1; k < np; ++k) dup += pairs[2 * k] == pairs[2 * k - 2] && pairs[2 * k + 1] == pairs[2 * k - 1];
    snprintf(name, sizeof name, "bed %s: pairs reported twice (periodic x, y)", ln);
    check_abs(name, (double)dup, 0.0, 0.0);
    /* recording changes nothing: the same state, bit for bit */
    dem_arrays B;
    TRY(w0, dem_world_arrays(w0, &B));
    int same = B.n_owned == n && !memcmp(A.x, B.x, 3 * n * sizeof(double)) &&
               !memcmp(A.v, B.v, 3 * n * sizeof(double)) && !memcmp(A.omega, B.omega, 3 * n * sizeof(double)) &&
               !memcmp(A.id, B.id, n * sizeof(int64_t));
    snprintf(name, sizeof name, "bed %s: x, v, omega with recording vs without (bits equal)", ln);
    check_abs(name, same ? 0.0 : 1.0, 0.0, 0.0);
    free(at); free(sum); free(mag); free(f); free(pairs); free(c);
    dem_world_destroy(&w);
    dem_world_destroy(&w0);
}

/* one owned particle touching a ghost copy of another world's particle */
static void ghost_pair(void)
{
    const double a = 1e-3, rho = 2500;
    dem_world *src = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-7, NULL, 0.01);
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-7, NULL, 0.01);
    dem_material mat = test_material(1e7, 0.3, 0.3, 0.0, 0.9);
    int mid;
    TRY(src, dem_world_add_material(src, &mat, &mid));
    TRY(w, dem_world_add_material(w, &mat, &mid));
    dem_particle pg = test_particle(-(a - 1e-5), 0, 0, 0, 0, 0, a, rho, mid), po = test_particle(a - 1e-5, 0, 0, 0, 0, 0, a, rho, mid);
    pg.id = 42; po.id = 5;
    TRY(src, dem_world_add_particles(src, 1, &pg));
    TRY(w, dem_world_add_particles(w, 1, &po));
    size_t sz = 0;
    TRY(src, dem_world_pack_ghost(src, 0, NULL, &sz));
    void *buf = malloc(sz);
    TRY(src, dem_world_pack_ghost(src, 0, buf, &sz));
    TRY(w, dem_world_unpack_particle(w, buf, sz, 1));
    TRY(w, dem_world_record_contacts(w, 1));
    TRY(w, dem_world_step(w, 1));
    dem_contact c = one_contact(w, "owned-ghost pair");
    check_abs("owned-ghost pair: ghost flag 1, wall flag 0", (double)(c.ghost * 10 + c.wall), 10.0, 0.0);
    check_abs("owned-ghost pair: ids {5, 42}", (double)(c.id_a * c.id_b), 210.0, 0.0);
    double f[3];
    TRY(w, dem_world_particle_contacts(w, NULL, f));
    double F[3] = {c.force_n[0] + c.force_t[0], c.force_n[1] + c.force_t[1], c.force_n[2] + c.force_t[2]};
    if (c.id_a != 5) for (int k = 0; k < 3; ++k) F[k] = -F[k];
    check_abs("owned-ghost pair: force on the owned particle vs its contact force (bits)", maxdiff3(F, f), 0.0, 0.0);
    free(buf);
    dem_world_destroy(&w);
    dem_world_destroy(&src);
}

static void errors(void)
{
    const double a = 1e-3, rho = 2500;
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-7, NULL, 0.01);
    dem_material mat = test_material(1e7, 0.3, 0.3, 0.0, 0.9);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    const double s = 2 * a - 1e-5;   /* a triangle of three touching spheres */
    dem_particle p[3] = {test_particle(0, 0, 0, 0, 0, 0, a, rho, mid),
                         test_particle(s, 0, 0, 0, 0, 0, a, rho, mid),
                         test_particle(0.5 * s, 0.5 * sqrt(3.0) * s, 0, 0, 0, 0, a, rho, mid)};
    TRY(w, dem_world_add_particles(w, 3, p));
    size_t n = 99;
    dem_contact c[4];
    check_status("contacts before recording", dem_world_contacts(w, c, 4, &n), DEM_ERR_STATE);
    check_abs("contacts before recording: count 0", (double)n, 0.0, 0.0);
    check_status("record_contacts(w, 2)", dem_world_record_contacts(w, 2), DEM_ERR_ARG);
    check_status("record_contacts(NULL, 1)", dem_world_record_contacts(NULL, 1), DEM_ERR_ARG);
    TRY(w, dem_world_record_contacts(w, 1));
    check_status("contacts with recording on but no step yet", dem_world_contacts(w, c, 4, &n), DEM_ERR_STATE);
    TRY(w, dem_world_step(w, 1));
    check_status("contacts with count NULL", dem_world_contacts(w, c, 4, NULL), DEM_ERR_ARG);
    check_status("contacts(NULL world)", dem_world_contacts(NULL, c, 4, &n), DEM_ERR_ARG);
    check_status("contacts count only (out NULL)", dem_world_contacts(w, NULL, 0, &n), DEM_OK);
    check_abs("contacts count: three touching pairs", (double)n, 3.0, 0.0);
    memset(c, 0x5a, sizeof c);
    dem_contact ref;
    memset(&ref, 0x5a, sizeof ref);
    size_t n2 = 0;
    check_status("contacts with capacity 2 < 3", dem_world_contacts(w, c, 2, &n2), DEM_ERR_RANGE);
    check_abs("contacts with capacity 2: *count set to the need", (double)n2, 3.0, 0.0);
    check_abs("contacts with capacity 2: nothing written", memcmp(&c[0], &ref, sizeof ref) ? 1.0 : 0.0, 0.0, 0.0);
    printf("# last error: %s\n", dem_world_last_error(w));
    check_abs("contacts with capacity 2: message names the capacity",
              strstr(dem_world_last_error(w), "capacity = 2") ? 1.0 : 0.0, 1.0, 0.0);
    check_status("contacts with capacity 3", dem_world_contacts(w, c, 3, &n2), DEM_OK);
    TRY(w, dem_world_remove_particle(w, 0, -1));
    check_status("contacts after a removal (particles changed)", dem_world_contacts(w, c, 4, &n), DEM_ERR_STATE);
    TRY(w, dem_world_step(w, 1));
    check_status("contacts after the next step", dem_world_contacts(w, c, 4, &n), DEM_OK);
    check_abs("contacts after the next step: one pair left", (double)n, 1.0, 0.0);
    TRY(w, dem_world_record_contacts(w, 0));
    check_status("contacts after recording off", dem_world_contacts(w, c, 4, &n), DEM_ERR_STATE);
    dem_world_destroy(&w);
}

int main(void)
{
    hertz_pair();
    hertz_wall();
    for (int k = 0; k < 4; ++k) sheared(laws[k]);
    for (int k = 0; k < 4; ++k) bed_sums(laws[k], 0);
    for (int k = 0; k < 4; ++k) bed_sums(laws[k], 1);
    mesh_wall();
    ghost_pair();
    errors();
    return check_exit();
}
