/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Triangle-mesh walls: a sphere hitting the shared edge of two coplanar
 * triangles, or the vertex shared by a fan of four, behaves exactly as
 * against one infinite plane (one contact, same force history), including
 * a sphere that slides across the shared edge (history handed over). */
#include "check.h"

typedef struct { double x[3], v[3], w[3]; size_t wall_contacts_max; } result;

static void run(int mesh, const double x0[3], const double v0[3], const double w0[3], double g,
                long nsteps, result *r)
{
    const double a = 1e-3, rho = 2500, dt = 2e-7;
    double gv[3] = {0, 0, -g};
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, dt, gv, 0.02);
    dem_material mat = test_material(1e7, 0.3, 0.3, 1e-5, 0.7);
    int mid;
    TRY(w, dem_world_add_material(w, &mat, &mid));
    const double L = 0.01;
    if (mesh == 0) {
        double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
        TRY(w, dem_world_add_plane(w, p0, nz, mid, NULL, NULL));
    } else if (mesh == 1) { /* square split along its diagonal (-L,-L)-(L,L) */
        double v[12] = {-L, -L, 0, L, -L, 0, L, L, 0, -L, L, 0};
        int t[6] = {0, 1, 2, 0, 2, 3};
        TRY(w, dem_world_add_trimesh(w, 4, v, 2, t, mid, NULL, NULL));
    } else { /* fan of four triangles around the origin */
        double v[15] = {0, 0, 0, L, 0, 0, 0, L, 0, -L, 0, 0, 0, -L, 0};
        int t[12] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1};
        TRY(w, dem_world_add_trimesh(w, 5, v, 4, t, mid, NULL, NULL));
    }
    dem_particle p = test_particle(x0[0], x0[1], x0[2], v0[0], v0[1], v0[2], a, rho, mid);
    for (int k = 0; k < 3; ++k) p.omega[k] = w0[k];
    TRY(w, dem_world_add_particles(w, 1, &p));
    r->wall_contacts_max = 0;
    for (long s = 0; s < nsteps; s += 50) {
        TRY(w, dem_world_step(w, 50));
        dem_stats st;
        TRY(w, dem_world_stats(w, &st));
        if (st.wall_contacts > r->wall_contacts_max) r->wall_contacts_max = st.wall_contacts;
    }
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    for (int k = 0; k < 3; ++k) { r->x[k] = A.x[k]; r->v[k] = A.v[k]; r->w[k] = A.omega[k]; }
    dem_world_destroy(&w);
}

static double diff(const result *a, const result *b)
{
    double d = 0;
    for (int k = 0; k < 3; ++k) {
        d = fmax(d, fabs(a->x[k] - b->x[k]) / 1e-3);
        d = fmax(d, fabs(a->v[k] - b->v[k]) / 1.0);
        d = fmax(d, fabs(a->w[k] - b->w[k]) * 1e-3 / 1.0);
    }
    return d;
}

int main(void)
{
    const double a = 1e-3;
    char name[160];
    /* 1. impact on the shared edge with spin and an oblique velocity */
    {
        double x0[3] = {0.001, 0.001, a + 1e-5}, v0[3] = {0.3, -0.2, -0.5}, w0[3] = {10, -20, 5};
        result rp, rm, rf;
        run(0, x0, v0, w0, 0.0, 3000, &rp);
        run(1, x0, v0, w0, 0.0, 3000, &rm);
        check_below("edge impact: |mesh - plane| (x/a, v, a w; m/s)", diff(&rm, &rp), 1e-9);
        check_abs("edge impact: simultaneous wall contacts", (double)rm.wall_contacts_max, 1.0, 0.0);
        check_below("edge impact: rebound happened (v_z > 0)", -rm.v[2], 0.0);
        double xv[3] = {0.0, 0.0, a + 1e-5};
        run(0, xv, v0, w0, 0.0, 3000, &rp);
        run(2, xv, v0, w0, 0.0, 3000, &rf);
        check_below("vertex impact (4 triangles): |mesh - plane|", diff(&rf, &rp), 1e-9);
        check_abs("vertex impact: simultaneous wall contacts", (double)rf.wall_contacts_max, 1.0, 0.0);
    }
    /* 2. sphere resting under gravity and sliding across the diagonal edge */
    {
        double deq = 0; /* start slightly above the surface; it settles while sliding */
        double x0[3] = {-0.002, 0.002, a - deq}, v0[3] = {0.2, -0.2, 0}, w0[3] = {0, 0, 0};
        result rp, rm;
        long n = 100000;
        run(0, x0, v0, w0, 9.81, n, &rp);
        run(1, x0, v0, w0, 9.81, n, &rm);
        snprintf(name, sizeof name, "slide across edge (%ld steps): |mesh - plane|", n);
        check_below(name, diff(&rm, &rp), 1e-9);
        check_abs("slide across edge: simultaneous wall contacts", (double)rm.wall_contacts_max, 1.0, 0.0);
        check_below("slide across edge: crossed the diagonal (y - x < 0)", rm.x[1] - rm.x[0], 0.0);
    }
    return check_exit();
}
