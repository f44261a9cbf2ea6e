/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* The keep filter of a decomposed set-up (dem_world_set_keep_filter,
 * docs/parallel.md "Initial particles and settling"): a list, a box fill
 * and a second fill that must avoid the first ones, made in one world
 * without a filter and in three worlds that keep x < a, a <= x < b and
 * x >= b.  The three filtered worlds together hold exactly the unfiltered
 * particles (same ids, positions, radii, densities bit for bit), each
 * holds only its own, and all four agree on the next id and the inserted
 * count; clearing the filter frees the shadow list and later particles are
 * stored again. */
#include "check.h"

static const double cut[2] = {0.012, 0.021};

/* the set-up of every world: list, box fill, cylinder fill, list */
static dem_world *make(test_slab *slab)
{
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-6, NULL, 0.05);
    dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    if (slab) TRY(w, dem_world_set_keep_filter(w, test_keep_slab, slab));
    dem_particle list[3] = {
        test_particle(0.005, 0.005, 0.005, 0, 0, 0, 1e-3, 2500, mid),
        test_particle(0.015, 0.005, 0.005, 0, 0, 0, 1e-3, 2500, mid),
        test_particle(0.025, 0.005, 0.005, 0, 0, 0, 1e-3, 2500, mid),
    };
    TRY(w, dem_world_add_particles(w, 3, list));
    dem_particle_template t;
    memset(&t, 0, sizeof t);
    t.diameter.kind = DEM_DIST_UNIFORM; t.diameter.a = 1e-3; t.diameter.b = 2e-3;
    t.density.kind = DEM_DIST_UNIFORM; t.density.a = 2000; t.density.b = 3000;
    t.material = mid;
    const double lo[3] = {0, 0, 0}, hi[3] = {0.03, 0.01, 0.01};
    size_t got = 0;
    TRY(w, dem_world_fill_box(w, lo, hi, NULL, NULL, 200, &t, &got));
    const double base[3] = {0.015, 0.005, 0}, axis[3] = {0, 0, 1};
    TRY(w, dem_world_fill_cylinder(w, base, axis, 0.005, 0.01, 15, &t, &got));
    if (slab) TRY(w, dem_world_set_keep_filter(w, NULL, NULL));
    dem_particle last = test_particle(0.029, 0.009, 0.009, 0, 0, 0, 1e-3, 2500, mid);
    TRY(w, dem_world_add_particles(w, 1, &last));
    return w;
}

int main(void)
{
    dem_world *all = make(NULL);
    test_slab slabs[3] = {{cut, 2, 0}, {cut, 2, 1}, {cut, 2, 2}};
    dem_world *part[3];
    for (int k = 0; k < 3; ++k) part[k] = make(&slabs[k]);

    dem_arrays A;
    TRY(all, dem_world_arrays(all, &A));
    dem_stats S;
    TRY(all, dem_world_stats(all, &S));
    size_t nSum = 0, found = 0, same = 0, wrongSlab = 0, last = 0;
    for (int k = 0; k < 3; ++k) {
        dem_arrays B;
        TRY(part[k], dem_world_arrays(part[k], &B));
        dem_stats T;
        TRY(part[k], dem_world_stats(part[k], &T));
        char name[96];
        snprintf(name, sizeof name, "keep filter: inserted count of slab %d vs unfiltered", k);
        check_abs(name, (double)T.inserted, (double)S.inserted, 0);
        nSum += B.n_owned;
        for (size_t j = 0; j < B.n_owned; ++j) {
            if (B.id[j] == A.id[A.n_owned - 1]) { ++last; continue; }   /* added after the filter */
            if (!test_keep_slab(B.x + 3 * j, &slabs[k])) ++wrongSlab;
            for (size_t i = 0; i < A.n_owned; ++i) {
                if (A.id[i] != B.id[j]) continue;
                ++found;
                same += memcmp(A.x + 3 * i, B.x + 3 * j, 3 * sizeof(double)) == 0
                     && A.radius[i] == B.radius[j] && A.density[i] == B.density[j];
            }
        }
    }
    check_abs("keep filter: particles of the three slabs (the one added after clearing: in each)",
              (double)nSum, (double)(A.n_owned + 2), 0);
    check_abs("keep filter: particles held by the slabs found by id in the unfiltered world",
              (double)found, (double)(A.n_owned - 1), 0);
    check_abs("keep filter: of those, bit for bit the same position, radius and density",
              (double)same, (double)found, 0);
    check_abs("keep filter: particles held by a slab that does not keep them", (double)wrongSlab, 0, 0);
    check_abs("keep filter: the particle added after clearing the filter, held by every slab",
              (double)last, 3, 0);
    check_range("keep filter: particles placed (3 + 200 + 15 + 1)", (double)A.n_owned, 219, 219);
    for (int k = 0; k < 3; ++k) dem_world_destroy(&part[k]);
    dem_world_destroy(&all);
    return check_exit();
}
