/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Insertion and outlets against exact bookkeeping and simple statistics:
 * fill_cylinder keeps every sphere inside and free of overlaps and draws
 * uniform diameters with the right mean; fill_box honours the inside test;
 * discrete and normal distributions; an inlet at a number rate inserts
 * rate x time particles, at a mass rate rate x time kg (within one particle);
 * a plane outlet books count, mass and one record per removed particle;
 * a box that cannot hold the request returns DEM_ERR_FULL with the count. */
#include "check.h"

static int in_ball(const double x[3], void *user)
{
    const double *c = user;
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (x[k] - c[k]) * (x[k] - c[k]);
    return d2 < c[3] * c[3];
}

static double min_gap(const dem_arrays *A)
{
    double g = INFINITY;
    for (size_t i = 0; i < A->n_owned; ++i)
        for (size_t j = i + 1; j < A->n_owned; ++j) {
            double d2 = 0;
            for (int k = 0; k < 3; ++k) d2 += (A->x[3 * i + k] - A->x[3 * j + k]) * (A->x[3 * i + k] - A->x[3 * j + k]);
            g = fmin(g, sqrt(d2) - A->radius[i] - A->radius[j]);
        }
    return g;
}

int main(void)
{
    /* fill_cylinder, uniform diameters */
    {
        dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-6, NULL, 0.05);
        dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
        int mid;
        TRY(w, dem_world_add_material(w, &m, &mid));
        dem_particle_template t;
        memset(&t, 0, sizeof t);
        t.diameter.kind = DEM_DIST_UNIFORM; t.diameter.a = 1e-3; t.diameter.b = 1.5e-3;
        t.density.kind = DEM_DIST_FIXED; t.density.a = 2500;
        t.material = mid;
        double base[3] = {0.01, 0, 0}, axis[3] = {0, 0, 2}, R = 0.006, L = 0.012;
        size_t got;
        const size_t n = 200;
        TRY(w, dem_world_fill_cylinder(w, base, axis, R, L, n, &t, &got));
        dem_arrays A;
        TRY(w, dem_world_arrays(w, &A));
        double worst = -INFINITY, dsum = 0;
        for (size_t i = 0; i < A.n_owned; ++i) {
            const double *x = A.x + 3 * i, r = A.radius[i];
            double rho = hypot(x[0] - base[0], x[1] - base[1]);
            worst = fmax(worst, rho + r - R);
            worst = fmax(worst, r - x[2]);
            worst = fmax(worst, x[2] + r - L);
            dsum += 2 * r;
        }
        check_abs("fill_cylinder inserted", (double)got, (double)n, 0.0);
        check_below("fill_cylinder: max protrusion outside the cylinder [m]", worst, 1e-15);
        check_below("fill_cylinder: overlaps (-min gap) [m]", -min_gap(&A), 0.0);
        double sd = 0.5e-3 / sqrt(12.0);
        check_abs("fill_cylinder: mean diameter, uniform [1, 1.5] mm (3 sigma)", dsum / n, 1.25e-3, 3 * sd / sqrt((double)n));
        dem_world_destroy(&w);
    }
    /* fill_box with an inside test; discrete and normal distributions; FULL */
    {
        dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-6, NULL, 0.05);
        dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
        int mid;
        TRY(w, dem_world_add_material(w, &m, &mid));
        double vals[2] = {1e-3, 2e-3}, wts[2] = {1, 3};
        dem_particle_template t;
        memset(&t, 0, sizeof t);
        t.diameter.kind = DEM_DIST_DISCRETE; t.diameter.n = 2; t.diameter.values = vals; t.diameter.weights = wts;
        t.density.kind = DEM_DIST_NORMAL; t.density.a = 2500; t.density.b = 100;
        t.material = mid;
        double ball[4] = {0, 0, 0, 0.02}, lo[3] = {-0.02, -0.02, -0.02}, hi[3] = {0.02, 0.02, 0.02};
        size_t got;
        const size_t n = 400;
        TRY(w, dem_world_fill_box(w, lo, hi, in_ball, ball, n, &t, &got));
        dem_arrays A;
        TRY(w, dem_world_arrays(w, &A));
        int outside = 0, big = 0;
        double rmin = INFINITY, rmax = -INFINITY;
        for (size_t i = 0; i < A.n_owned; ++i) {
            if (!in_ball(A.x + 3 * i, ball)) outside++;
            if (A.radius[i] > 0.75e-3) big++;
            rmin = fmin(rmin, A.density[i]);
            rmax = fmax(rmax, A.density[i]);
        }
        check_abs("fill_box: centres outside the inside() region", outside, 0, 0);
        check_abs("fill_box: fraction of 2 mm (weights 1:3), 3 sigma", (double)big / n, 0.75, 3 * sqrt(0.75 * 0.25 / n));
        check_range("fill_box: normal density truncated at +-3 sd", rmin, 2200, 2800);
        check_range("fill_box: normal density truncated at +-3 sd (max)", rmax, 2200, 2800);
        check_below("fill_box: overlaps (-min gap) [m]", -min_gap(&A), 0.0);
        double tlo[3] = {0.03, 0.03, 0.03}, thi[3] = {0.034, 0.034, 0.034};
        dem_particle_template t2 = t;
        t2.diameter.kind = DEM_DIST_FIXED; t2.diameter.a = 2e-3;
        check_status("fill_box: request that cannot fit", dem_world_fill_box(w, tlo, thi, NULL, NULL, 50, &t2, &got), DEM_ERR_FULL);
        check_range("fill_box: DEM_ERR_FULL reports the number placed", (double)got, 1, 49);
        dem_world_destroy(&w);
    }
    /* inlets and an outlet */
    {
        dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 5e-6, NULL, 0.1);
        dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
        int mid;
        TRY(w, dem_world_add_material(w, &m, &mid));
        dem_particle_template t;
        memset(&t, 0, sizeof t);
        t.diameter.kind = DEM_DIST_FIXED; t.diameter.a = 1e-3;
        t.density.kind = DEM_DIST_UNIFORM; t.density.a = 2000; t.density.b = 3000;
        t.velocity[2] = -2.0;
        t.material = mid;
        double sq1[12] = {0.001, 0, 0.05, 0.02, 0, 0.05, 0.02, 0.02, 0.05, 0.001, 0.02, 0.05};
        double sq2[12] = {-0.04, 0, 0.05, -0.02, 0, 0.05, -0.02, 0.02, 0.05, -0.04, 0.02, 0.05};
        int in1, in2, out;
        TRY(w, dem_world_add_inlet(w, 4, sq1, DEM_RATE_NUMBER, 5000.0, 0.0, 0.01, &t, &in1));
        TRY(w, dem_world_add_inlet(w, 4, sq2, DEM_RATE_MASS, 1e-3, 0.0, 0.01, &t, &in2));
        double op[3] = {0, 0, 0.02}, on[3] = {0, 0, -1};
        TRY(w, dem_world_add_outlet_plane(w, op, on, &out));
        /* a duct wall along the edge x = 0.001 of inlet 1 (plane, normal +x) */
        double wp[3] = {0.001, 0, 0}, wn[3] = {1, 0, 0};
        TRY(w, dem_world_add_plane(w, wp, wn, mid, NULL, NULL));
        TRY(w, dem_world_step(w, 2000)); /* 0.01 s: nothing reaches the outlet yet */
        dem_arrays A;
        TRY(w, dem_world_arrays(w, &A));
        int n1 = 0;
        double m2 = 0, mall = 0, mpmax = 3000 * 1e-9 * M_PI / 6;
        for (size_t i = 0; i < A.n_owned; ++i) {
            if (A.x[3 * i] > 0) n1++; else m2 += A.mass[i];
            mall += A.mass[i];
        }
        size_t ntot = A.n_owned;
        double wallgap = INFINITY;
        for (size_t i = 0; i < A.n_owned; ++i)
            if (A.x[3 * i] > 0) wallgap = fmin(wallgap, A.x[3 * i] - 0.001 - A.radius[i]);
        check_below("inlet next to a wall: no new particle overlaps the wall (-min gap) [m]", -wallgap, 1e-12);
        check_abs("inlet number rate 5000/s for 0.01 s: inserted", n1, 50.0, 1.0);
        check_abs("inlet mass rate 1 g/s for 0.01 s: inserted mass [kg]", m2, 1e-5, mpmax);
        TRY(w, dem_world_step(w, 4000)); /* all pass z = 0.02 */
        int64_t c;
        double mout;
        TRY(w, dem_world_outlet_totals(w, out, &c, &mout));
        const dem_removed_record *rec;
        size_t nrec;
        TRY(w, dem_world_removed_records(w, &rec, &nrec));
        double mrec = 0, tmin = INFINITY, tmax = 0;
        for (size_t k = 0; k < nrec; ++k) {
            mrec += rec[k].density * rec[k].diameter * rec[k].diameter * rec[k].diameter * M_PI / 6;
            tmin = fmin(tmin, rec[k].time);
            tmax = fmax(tmax, rec[k].time);
        }
        dem_stats st;
        TRY(w, dem_world_stats(w, &st));
        check_abs("outlet: removed everything inserted (stats.inserted)", (double)c, (double)st.inserted, 0.0);
        check_range("outlet: removed at least the particles present at 0.01 s", (double)c, (double)ntot, (double)ntot + 2);
        check_abs("outlet: one record per removed particle", (double)nrec, (double)c, 0.0);
        check_range("outlet: booked mass vs mass present at 0.01 s (+ at most 2 late particles)", mout, mall * (1 - 1e-12), mall + 2 * mpmax);
        check_rel("outlet: booked mass = sum over records", mout, mrec, 1e-12);
        check_range("outlet: removal times (z from 0.05 to 0.02 at 2 m/s: >= 0.015 s)", tmin, 0.015, 0.03);
        check_abs("outlet: particles left", (double)dem_world_count(w), 0.0, 0.0);
        dem_world_clear_removed_records(w);
        TRY(w, dem_world_removed_records(w, &rec, &nrec));
        check_abs("records cleared", (double)nrec, 0.0, 0.0);
        dem_world_destroy(&w);
    }
    return check_exit();
}
