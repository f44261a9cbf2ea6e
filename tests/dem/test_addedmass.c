/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Added (virtual) mass, dem_arrays.added_mass: the translational inertia
 * becomes m + m_a while gravity stays m g.
 *  1. no drag, constant force_ext F and gravity: v(t) = (F + m g) t/(m + m_a)
 *     (exact to round-off: constant acceleration);
 *  2. with implicit drag K towards u, each half kick h = dt/2 solves
 *     (m + m_a)(v' - v)/h = F + m g + K (u - v'), so
 *       v_n - v* = (v_0 - v*) / (1 + h K/(m + m_a))^(2n),  v* = u + (F + m g)/K,
 *     and the particle's momentum obeys
 *       m (v_n - v_0) = n dt (F + m g) + drag_impulse - m_a (v_n - v_0);
 *  3. added_mass 0 is bit-identical to a world where it is never touched;
 *  4. added_mass follows its particle through the spatial re-sort, save/
 *     restore (bit-identical continuation) and pack/unpack;
 *  5. a negative added_mass is refused (DEM_ERR_RANGE). */
#include "check.h"
#include <time.h>

int main(void)
{
    const double a = 1e-3, rho = 2500, dt = 1e-5, g[3] = {0, 0, -9.81};
    const int n = 400;

    /* 1 and 2 */
    {
        dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, dt, g, 0.5);
        dem_material mat = test_material(1e7, 0.3, 0.3, 0.0, 0.5);
        int mid;
        TRY(w, dem_world_add_material(w, &mat, &mid));
        dem_particle p[2] = {test_particle(0, 0, 0, 0, 0, 0, a, rho, mid),
                             test_particle(0.1, 0, 0, 0, 0, 0.3, a, rho, mid)};
        TRY(w, dem_world_add_particles(w, 2, p));
        dem_arrays A;
        TRY(w, dem_world_arrays(w, &A));
        const double m = A.mass[0], ma = 0.5 * 1000.0 * m / rho * 3.0; /* m_a/m = 0.6 */
        const double F[3] = {2e-5, -1e-5, 3e-5};
        for (int i = 0; i < 2; ++i) {
            A.added_mass[i] = ma;
            for (int k = 0; k < 3; ++k) A.force_ext[3 * i + k] = F[k];
        }
        const double K = 2.0 * (m + ma) / (n * dt), u[3] = {0.01, 0.02, -0.05};
        A.drag_coeff[1] = K;
        for (int k = 0; k < 3; ++k) A.fluid_velocity[3 + k] = u[k];
        const double v0z = A.v[5];
        TRY(w, dem_world_step(w, n));
        TRY(w, dem_world_arrays(w, &A));
        const double t = n * dt;
        for (int k = 0; k < 3; ++k) {
            char name[128];
            snprintf(name, sizeof name, "added mass, no drag: v[%d] = (F + m g) t/(m + m_a)", k);
            check_rel(name, A.v[k], (F[k] + m * g[k]) * t / (m + ma), 1e-11);
        }
        const double q = 1.0 / pow(1.0 + 0.5 * dt * K / (m + ma), 2.0 * n);
        for (int k = 0; k < 3; ++k) {
            const double vs = u[k] + (F[k] + m * g[k]) / K, v0 = k == 2 ? v0z : 0.0;
            char name[128];
            snprintf(name, sizeof name, "added mass with implicit drag: v[%d] vs fixed point + decay", k);
            check_rel(name, A.v[3 + k], vs + (v0 - vs) * q, 1e-11);
            const double dv = A.v[3 + k] - v0;
            snprintf(name, sizeof name, "added mass with drag: m dv[%d] = t (F + m g) + J - m_a dv", k);
            check_rel(name, m * dv, t * (F[k] + m * g[k]) + A.drag_impulse[3 + k] - ma * dv, 1e-10);
        }
        /* time constant (m + m_a)/K against the continuous exp: the implicit half
     * kicks differ from it by a factor exp(n (h K/M)^2) = exp(1/n) here (0.25 %) */
        check_rel("added mass with drag: decay vs exp(-K t/(m + m_a))", q, exp(-K * t / (m + ma)), 3e-3);
        A.added_mass[0] = -1e-9;
        check_status("negative added_mass refused", dem_world_step(w, 1), DEM_ERR_RANGE);
        dem_world_destroy(&w);
    }

    /* 3 and 4: a settling pile with drag; added mass per particle from its id */
    {
        char path[512];
        const char *tmp = getenv("TMPDIR");
        int here;
        snprintf(path, sizeof path, "%s/dem_addedmass_test_%lx_%lx.state", tmp && *tmp ? tmp : "/tmp",
                 (unsigned long)time(NULL), (unsigned long)(size_t)&here);
        dem_world *w[3];
        for (int c = 0; c < 3; ++c) {
            w[c] = test_world(DEM_CONTACT_HERTZ_MINDLIN, 2e-6, g, 0.02);
            dem_material mat = test_material(1e7, 0.3, 0.3, 0.0, 0.5);
            int mid;
            TRY(w[c], dem_world_add_material(w[c], &mat, &mid));
            double o[3] = {0, 0, -0.01}, nz[3] = {0, 0, 1};
            TRY(w[c], dem_world_add_plane(w[c], o, nz, mid, NULL, NULL));
            dem_particle_template tp;
            memset(&tp, 0, sizeof tp);
            tp.diameter.kind = DEM_DIST_UNIFORM; tp.diameter.a = 1.6e-3; tp.diameter.b = 2.4e-3;
            tp.density.kind = DEM_DIST_FIXED; tp.density.a = rho;
            tp.material = mid;
            double lo[3] = {-0.01, -0.01, -0.01}, hi[3] = {0.01, 0.01, 0.01};
            size_t got;
            TRY(w[c], dem_world_fill_box(w[c], lo, hi, NULL, NULL, 200, &tp, &got));
            dem_arrays A;
            TRY(w[c], dem_world_arrays(w[c], &A));
            for (size_t i = 0; i < A.n_owned; ++i) {
                A.drag_coeff[i] = 1e-5;
                A.fluid_velocity[3 * i] = 0.02;
                if (c < 2) A.added_mass[i] = 1e-7 * (double)(A.id[i] % 7);
            }
        }
        /* w[2]: added_mass never touched vs a copy with explicit zeros */
        dem_world *z = NULL;
        {
            dem_arrays A;
            TRY(w[2], dem_world_save(w[2], path));
            TRY(z, dem_world_create(&z));
            TRY(z, dem_world_restore(z, path));
            TRY(z, dem_world_arrays(z, &A));
            for (size_t i = 0; i < A.n_owned; ++i) A.added_mass[i] = 0.0;
        }
        TRY(w[0], dem_world_step(w[0], 3000));
        TRY(w[1], dem_world_step(w[1], 1500));
        TRY(w[1], dem_world_save(w[1], path));
        dem_world *r = NULL;
        TRY(r, dem_world_create(&r));
        TRY(r, dem_world_restore(r, path));
        TRY(r, dem_world_step(r, 1500));
        TRY(w[2], dem_world_step(w[2], 3000));
        TRY(z, dem_world_step(z, 3000));
        remove(path);
        dem_arrays A, R, W2, Z;
        TRY(w[0], dem_world_arrays(w[0], &A));
        TRY(r, dem_world_arrays(r, &R));
        TRY(w[2], dem_world_arrays(w[2], &W2));
        TRY(z, dem_world_arrays(z, &Z));
        size_t wrong = 0;
        for (size_t i = 0; i < A.n_owned; ++i)
            if (A.added_mass[i] != 1e-7 * (double)(A.id[i] % 7)) wrong++;
        check_abs("added_mass follows its particle through the re-sort (mismatches)", (double)wrong, 0, 0);
        int same = A.n_owned == R.n_owned && !memcmp(A.v, R.v, 3 * A.n_owned * sizeof(double)) &&
                   !memcmp(A.x, R.x, 3 * A.n_owned * sizeof(double)) &&
                   !memcmp(A.added_mass, R.added_mass, A.n_owned * sizeof(double));
        check_abs("added mass: save/restore continues bit-identically (0 = identical)", same ? 0 : 1, 0, 0);
        int zsame = W2.n_owned == Z.n_owned && !memcmp(W2.v, Z.v, 3 * W2.n_owned * sizeof(double)) &&
                    !memcmp(W2.x, Z.x, 3 * W2.n_owned * sizeof(double));
        check_abs("added_mass 0 bit-identical to untouched (0 = identical)", zsame ? 0 : 1, 0, 0);
        /* pack/unpack one particle into an empty world with the same material */
        size_t sz = 0;
        TRY(w[0], dem_world_pack_particle(w[0], 5, NULL, &sz));
        void *buf = malloc(sz);
        TRY(w[0], dem_world_pack_particle(w[0], 5, buf, &sz));
        dem_world *u = test_world(DEM_CONTACT_HERTZ_MINDLIN, 2e-6, g, 0.02);
        dem_material mat = test_material(1e7, 0.3, 0.3, 0.0, 0.5);
        int mid;
        TRY(u, dem_world_add_material(u, &mat, &mid));
        dem_arrays U;
        TRY(u, dem_world_arrays(u, &U));
        TRY(u, dem_world_unpack_particle(u, buf, sz, 0));
        TRY(u, dem_world_arrays(u, &U));
        check_rel("added_mass survives pack/unpack", U.added_mass[0], A.added_mass[5], 0);
        free(buf);
        dem_world_destroy(&u);
        dem_world_destroy(&r);
        dem_world_destroy(&z);
        for (int c = 0; c < 3; ++c) dem_world_destroy(&w[c]);
    }
    return check_exit();
}
