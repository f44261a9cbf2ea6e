/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Random fills in blocks (dem_world_fill_blocks_box / _cylinder):
 * exactly n particles, none overlapping another or the region's boundary,
 * ids 0..n-1 once each, spread uniformly within the blocks (the share of
 * the box's centres in the lower halves of 1 mm layers, far finer than a
 * block, so that the stratified counts do not decide it, and the share in
 * the inner half of the cylinder's cross-section, each 0.5 within 4
 * binomial standard deviations); the same fills in four
 * worlds that keep x < a, a <= x < b, b <= x < c and x >= c (keep filter
 * and keep box, as the processors of a decomposed set-up) hold together
 * exactly the unfiltered particles, bit for bit, with no shadow list; a
 * keep box away from the region keeps none and still counts n inserted;
 * a solid fraction of 0.2 of a small cube fits; the world's own random stream is unchanged; a region with a
 * particle in it and a block that cannot hold its share are refused. */
#include "check.h"

static const double cut[3] = {0.024, 0.051, 0.113};

static const double blo[3] = {0, 0, 0}, bhi[3] = {0.1, 0.05, 0.08};
static const double cbase[3] = {0.15, 0.02, 0.01}, caxis[3] = {0, 1, 1};
static const double cR = 0.015, cL = 0.05;
enum { NBOX = 4000, NCYL = 1500 };

/* a world with a box and a cylinder fill in blocks (slab: keep filter) */
static dem_world *make(test_slab *slab)
{
    int mid;
    dem_world *w = test_fill_world(&mid);
    if (slab) test_set_keep_slab(w, slab);
    dem_particle_template t = test_fill_template(mid);
    size_t got = 0;
    TRY(w, dem_world_fill_blocks_box(w, blo, bhi, NBOX, &t, &got));
    check_abs("blocks box: inserted count", (double)got, NBOX, 0);
    TRY(w, dem_world_fill_blocks_cylinder(w, cbase, caxis, cR, cL, NCYL, &t, &got));
    if (slab) TRY(w, dem_world_set_keep_filter(w, NULL, NULL));
    return w;
}

int main(void)
{
    dem_world *all = make(NULL);
    dem_arrays A;
    TRY(all, dem_world_arrays(all, &A));
    check_abs("blocks: particles", (double)A.n_owned, NBOX + NCYL, 0);
    check_abs("blocks: overlapping pairs", (double)test_overlapping_pairs(&A), 0, 0);
    int outside = 0;
    size_t low = 0, inner = 0;
    unsigned char *seen = calloc(NBOX + NCYL, 1);
    int badid = 0;
    const double al = sqrt(2.0);
    for (size_t i = 0; i < A.n_owned; ++i) {
        const double *x = A.x + 3 * i, r = A.radius[i];
        const int64_t id = A.id[i];
        if (id < 0 || id >= NBOX + NCYL || seen[id]) { badid++; continue; }
        seen[id] = 1;
        if (id < NBOX) {
            for (int k = 0; k < 3; ++k) outside += x[k] - r < blo[k] || x[k] + r > bhi[k];
            low += fmod(x[2], 1e-3) < 0.5e-3;
        } else {
            double q[3] = {x[0] - cbase[0], x[1] - cbase[1], x[2] - cbase[2]}, ax[3];
            for (int k = 0; k < 3; ++k) ax[k] = caxis[k] / al;
            double t = q[0] * ax[0] + q[1] * ax[1] + q[2] * ax[2], rad2 = 0;
            for (int k = 0; k < 3; ++k) { double d = q[k] - t * ax[k]; rad2 += d * d; }
            outside += t < r || t > cL - r || sqrt(rad2) > cR - r;
            /* centres' disc radius R - 1.2 mm: half its area within (R - 1.2 mm)/sqrt 2 */
            inner += sqrt(rad2) < (cR - 1.2e-3) / al;
        }
    }
    check_abs("blocks: particles reaching out of their region (box or cylinder)", (double)outside, 0, 0);
    check_abs("blocks: ids not 0..n-1 once each", (double)badid, 0, 0);
    /* uniform: binomial(n, 1/2) shares (the centres' 77.6 mm z-range holds
       whole 1 mm layers but for 0.6 mm, a bias below 0.004) */
    check_abs("blocks box: share of centres in the lower halves of 1 mm layers", (double)low / NBOX, 0.5,
              4 * 0.5 / sqrt(NBOX));
    check_abs("blocks cylinder: share of centres in the inner half of the cross-section", (double)inner / NCYL,
              0.5, 4 * 0.5 / sqrt(NCYL));

    /* four keep-filtered worlds hold together exactly the particles of all */
    test_keep_slabs("blocks", make, cut, 3, &A);
    free(seen);

    {
        /* a keep box away from the region: none kept, n counted */
        int mid;
        test_slab far = {cut, 3, 9};
        dem_world *w = test_fill_world(&mid);
        dem_particle_template t = test_fill_template(mid);
        const double lo[3] = {5, 5, 5}, hi[3] = {6, 6, 6};
        TRY(w, dem_world_set_keep_filter(w, test_keep_slab, &far));
        TRY(w, dem_world_set_keep_box(w, lo, hi));
        size_t got;
        TRY(w, dem_world_fill_blocks_box(w, blo, bhi, NBOX, &t, &got));
        dem_stats st;
        TRY(w, dem_world_stats(w, &st));
        check_abs("blocks: keep box away from the region: particles stored", (double)dem_world_count(w), 0, 0);
        check_abs("blocks: keep box away from the region: inserted", (double)st.inserted, NBOX, 0);
        dem_world_destroy(&w);
    }
    {
        /* solid fraction 0.2 of a 20 mm cube, 2 mm spheres (the blocks jam near 0.24, fill_box near 0.27: docs/demProperties.md) */
        int mid;
        dem_world *w = test_fill_world(&mid);
        dem_particle_template t = test_fill_template(mid);
        t.diameter.kind = DEM_DIST_FIXED; t.diameter.a = 2e-3;
        const size_t n = (size_t)(0.2 * 8e-6 / (M_PI / 6 * 8e-9));
        const double lo[3] = {0, 0, 0}, hi[3] = {0.02, 0.02, 0.02};
        size_t got;
        TRY(w, dem_world_fill_blocks_box(w, lo, hi, n, &t, &got));
        dem_arrays B;
        TRY(w, dem_world_arrays(w, &B));
        check_abs("blocks: solid fraction 0.2 in a 20 mm cube: particles", (double)B.n_owned, (double)n, 0);
        check_abs("blocks: solid fraction 0.2 in a 20 mm cube: overlapping pairs", (double)test_overlapping_pairs(&B), 0, 0);
        dem_world_destroy(&w);
    }

    /* the world's random stream: a random fill after the block fills is the
       one placed without them */
    {
        int mid;
        dem_world *p = make(NULL), *q = test_fill_world(&mid);
        dem_particle_template t = test_fill_template(mid);
        const double lo[3] = {-0.1, -0.1, -0.1}, hi[3] = {-0.05, -0.05, -0.05};
        size_t got;
        test_stream_untouched("blocks: a random fill after them equals the one without them (world stream untouched)",
                              p, q, mid, NBOX + NCYL, lo, hi);
        /* refused: over particles placed before; a block that cannot hold its share */
        check_status("blocks box over existing particles", dem_world_fill_blocks_box(p, lo, hi, 10, &t, &got),
                     DEM_ERR_RANGE);
        const double lo2[3] = {0.3, 0.3, 0.3}, hi2[3] = {0.31, 0.31, 0.31};
        check_status("blocks box: 1000 particles of 1.6-2.4 mm in a 10 mm cube",
                     dem_world_fill_blocks_box(p, lo2, hi2, 1000, &t, &got), DEM_ERR_FULL);
        check_status("blocks cylinder: radius below the largest radius",
                     dem_world_fill_blocks_cylinder(p, hi2, caxis, 1e-3, 0.01, 10, &t, &got), DEM_ERR_FULL);
        dem_world_destroy(&p); dem_world_destroy(&q);
    }
    dem_world_destroy(&all);
    return check_exit();
}
