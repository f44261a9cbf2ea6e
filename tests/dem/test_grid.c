/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* The cell grid of the list build spans the particles, not the domain
 * (docs/demCore.md, "Neighbour search and contact history"): a compressed
 * cluster of 6 x 6 x 6 spheres on a triangle floor, with a second triangle
 * far from it, in a domain 20 mm wide and in one 20 m wide (where a grid
 * over the domain would be limited to cells far larger than the cut-off),
 * and in the wide domain with one more sphere far outside it.  Each world
 * finds every overlapping pair (against the all-pairs count) and every
 * floor contact, the far triangle none, and the per-particle contact
 * forces of the wide worlds equal the narrow one's to round-off. */
#include "check.h"

enum { NS = 6, N = NS * NS * NS };
static const double a = 1e-3, gap = 1.96e-3; /* spacing below 2a: every neighbour touches */

static dem_world *make(double half, int stray, double xs[][3])
{
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-7, NULL, half);
    dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    dem_particle p[N + 1];
    size_t n = 0;
    for (int k = 0; k < NS; ++k)
        for (int j = 0; j < NS; ++j)
            for (int i = 0; i < NS; ++i, ++n) {
                /* a fixed small jitter so that no pair sits exactly at the cut-off */
                const double jit = 1e-5 * (double)((n * 7919) % 13) / 13.0;
                xs[n][0] = i * gap + jit;
                xs[n][1] = j * gap - jit;
                xs[n][2] = a * 0.98 + k * gap + 0.5 * jit;
                p[n] = test_particle(xs[n][0], xs[n][1], xs[n][2], 0, 0, 0, a, 2500, mid);
            }
    if (stray) p[n++] = test_particle(0.9 * half, 0.9 * half, 3 * half, 0, 0, 0, a, 2500, mid);
    TRY(w, dem_world_add_particles(w, n, p));
    /* a floor at z = 0 under the cluster, and a triangle 5 mm beside it */
    const double v[] = {-0.01, -0.01, 0,  0.03, -0.01, 0,  -0.01, 0.03, 0,
                        0.03, 0.03, 0,
                        0.0, 0.0, 0.02,  0.005, 0.0, 0.02,  0.0, 0.005, 0.02};
    const int floorTri[] = {0, 1, 2, 1, 3, 2}, farTri[] = {0, 1, 2};
    const double still[3] = {0, 0, 0};
    int wid;
    TRY(w, dem_world_add_trimesh(w, 4, v, 2, floorTri, mid, still, &wid));
    const double farV[] = {v[12] + 0.03, v[13], v[14], v[15] + 0.03, v[16], v[17], v[18] + 0.03, v[19], v[20]};
    TRY(w, dem_world_add_trimesh(w, 3, farV, 1, farTri, mid, still, &wid));
    TRY(w, dem_world_record_contacts(w, 1));
    TRY(w, dem_world_step(w, 1));
    return w;
}

/* contact force per particle by id (the world may sort its storage) */
static void forces_by_id(dem_world *w, double f[][3])
{
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    static double cf[3 * (N + 1)];
    TRY(w, dem_world_particle_contacts(w, NULL, cf));
    for (size_t i = 0; i < A.n_owned; ++i)
        if (A.id[i] < N)
            for (int c = 0; c < 3; ++c) f[A.id[i]][c] = cf[3 * i + c];
}

int main(void)
{
    static double xs[N][3], ref[N][3], got[N][3];
    /* all-pairs count of overlapping pairs and of spheres on the floor */
    size_t pairs = 0, onFloor = 0;
    {
        dem_world *w = make(0.01, 0, xs);
        for (size_t i = 0; i < N; ++i) {
            onFloor += xs[i][2] < a;
            for (size_t j = i + 1; j < N; ++j) {
                double d2 = 0;
                for (int c = 0; c < 3; ++c) d2 += (xs[i][c] - xs[j][c]) * (xs[i][c] - xs[j][c]);
                pairs += d2 < 4 * a * a;
            }
        }
        dem_world_destroy(&w);
    }
    const char *names[3] = {"domain 20 mm", "domain 20 m", "domain 20 m with a sphere outside"};
    const double halves[3] = {0.01, 10.0, 10.0};
    for (int t = 0; t < 3; ++t) {
        dem_world *w = make(halves[t], t == 2, xs);
        size_t count = 0;
        TRY(w, dem_world_contacts(w, NULL, 0, &count));
        static dem_contact con[8 * N];
        TRY(w, dem_world_contacts(w, con, 8 * N, &count));
        size_t np = 0, nw = 0;
        for (size_t k = 0; k < count; ++k) {
            if (con[k].wall) ++nw;
            else ++np;
        }
        char name[160];
        snprintf(name, sizeof name, "grid, %s: particle contacts vs all pairs", names[t]);
        check_abs(name, (double)np, (double)pairs, 0);
        snprintf(name, sizeof name, "grid, %s: wall contacts vs spheres on the floor", names[t]);
        check_abs(name, (double)nw, (double)onFloor, 0);
        forces_by_id(w, t == 0 ? ref : got);
        if (t > 0) {
            double dmax = 0, fbig = 0;
            for (size_t i = 0; i < N; ++i)
                for (int c = 0; c < 3; ++c) {
                    dmax = fmax(dmax, fabs(got[i][c] - ref[i][c]));
                    fbig = fmax(fbig, fabs(ref[i][c]));
                }
            snprintf(name, sizeof name, "grid, %s: largest contact-force difference / largest force vs 20 mm",
                     names[t]);
            check_below(name, dmax / fbig, 1e-12);
        }
        dem_world_destroy(&w);
    }
    return check_exit();
}
