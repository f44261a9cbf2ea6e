/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Lattice fills (dem_world_fill_lattice_box / _cylinder): exactly n
 * particles, none overlapping another or the region's boundary, ids
 * 0..n-1, spread over the region's height; the same fill in three worlds
 * that keep x < a, a <= x < b and x >= b (keep filter and keep box, as
 * each processor of a decomposed set-up) holds together exactly the
 * unfiltered particles, bit for bit, with no shadow list; the world's own
 * random stream is unchanged (a random fill after it places the same
 * particles); a region with a particle in it and too many particles are
 * refused. */
#include "check.h"

static const double cut[2] = {0.031, 0.064};

static const double blo[3] = {0, 0, 0}, bhi[3] = {0.1, 0.05, 0.08};
static const double cbase[3] = {0.05, 0.02, 0.01}, caxis[3] = {0, 1, 1};
static const double cR = 0.015, cL = 0.05;
enum { NBOX = 3000, NCYL = 1500 };

/* a world with a box and a cylinder lattice fill (slab: keep filter) */
static dem_world *make(test_slab *slab)
{
    int mid;
    dem_world *w = test_fill_world(&mid);
    if (slab) test_set_keep_slab(w, slab);
    dem_particle_template t = test_fill_template(mid);
    size_t got = 0;
    TRY(w, dem_world_fill_lattice_box(w, blo, bhi, NBOX, &t, &got));
    check_abs("lattice box: inserted count", (double)got, NBOX, 0);
    const double b2[3] = {cbase[0] + 0.1, cbase[1], cbase[2]};
    TRY(w, dem_world_fill_lattice_cylinder(w, b2, caxis, cR, cL, NCYL, &t, &got));
    if (slab) TRY(w, dem_world_set_keep_filter(w, NULL, NULL));
    return w;
}

int main(void)
{
    dem_world *all = make(NULL);
    dem_arrays A;
    TRY(all, dem_world_arrays(all, &A));
    check_abs("lattice: particles", (double)A.n_owned, NBOX + NCYL, 0);
    check_abs("lattice: overlapping pairs", (double)test_overlapping_pairs(&A), 0, 0);
    int outside = 0, badid = 0;
    double zmin = 1, zmax = -1;
    for (size_t i = 0; i < A.n_owned; ++i) {
        const double *x = A.x + 3 * i, r = A.radius[i];
        badid += A.id[i] != (int64_t)i;
        if (A.id[i] < NBOX) {
            for (int k = 0; k < 3; ++k) outside += x[k] - r < blo[k] || x[k] + r > bhi[k];
            zmin = fmin(zmin, x[2]); zmax = fmax(zmax, x[2]);
        } else {
            /* cylinder: axial position in [r, L - r], radial distance <= R - r */
            double q[3] = {x[0] - cbase[0] - 0.1, x[1] - cbase[1], x[2] - cbase[2]}, ax[3];
            const double al = sqrt(2.0);
            for (int k = 0; k < 3; ++k) ax[k] = caxis[k] / al;
            double t = q[0] * ax[0] + q[1] * ax[1] + q[2] * ax[2], rad2 = 0;
            for (int k = 0; k < 3; ++k) { double d = q[k] - t * ax[k]; rad2 += d * d; }
            outside += t < r || t > cL - r || sqrt(rad2) > cR - r;
        }
    }
    check_abs("lattice: particles reaching out of their region (box or cylinder)", (double)outside, 0, 0);
    check_abs("lattice: ids not 0..n-1 in order", (double)badid, 0, 0);
    check_range("lattice box: height spanned by the centres / box height (spread, not piled)",
                (zmax - zmin) / (bhi[2] - blo[2]), 0.8, 1.0);

    /* three keep-filtered worlds hold together exactly the particles of all */
    test_keep_slabs("lattice", make, cut, 2, &A);

    /* the world's random stream: a random fill placed after a lattice fill
       is the one placed without it */
    {
        int mid;
        dem_world *p = make(NULL), *q = test_fill_world(&mid);
        dem_particle_template t = test_fill_template(mid);
        const double lo[3] = {-0.1, -0.1, -0.1}, hi[3] = {-0.05, -0.05, -0.05};
        size_t got;
        test_stream_untouched("lattice: a random fill after it equals the one without it (world stream untouched)",
                              p, q, mid, NBOX + NCYL, lo, hi);
        /* refused: a lattice fill over particles placed before; too many */
        check_status("lattice box over existing particles", dem_world_fill_lattice_box(p, lo, hi, 10, &t, &got),
                     DEM_ERR_RANGE);
        const double lo2[3] = {0.3, 0.3, 0.3}, hi2[3] = {0.31, 0.31, 0.31};
        check_status("lattice box: 1000 particles of 2.4 mm in a 10 mm cube", 
                     dem_world_fill_lattice_box(p, lo2, hi2, 1000, &t, &got), DEM_ERR_FULL);
        dem_world_destroy(&p); dem_world_destroy(&q);
    }
    dem_world_destroy(&all);
    return check_exit();
}
