/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Decomposition support: a world that owns particles A, B and holds C as a
 * ghost (packed from a world that owns all three) computes the same forces
 * on A and B for one step as the world that owns all three; ghosts are not
 * integrated; clear_ghosts removes them; outlets of every kind book
 * count and mass. */
#include "check.h"

static dem_world *make(int n, const dem_particle *p)
{
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-6, NULL, 0.05);
    dem_material m = test_material(1e7, 0.3, 0.4, 1e-5, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    TRY(w, dem_world_add_particles(w, (size_t)n, p));
    return w;
}

int main(void)
{
    const double a = 1e-3;
    /* at rest, overlapping: in one step the ghost (fixed in the partial
       world) and its original (moved by its contact force) differ by ~1e-9 m */
    dem_particle p[3] = {test_particle(0, 0, 0, 0, 0, 0, a, 2500, 0),
                         test_particle(1.99e-3, 0, 0, 0, 0, 0, a, 2500, 0),
                         test_particle(1e-3, 1.72e-3, 0, 0, 0, 0, a, 2500, 0)};
    for (int i = 0; i < 3; ++i) p[i].id = 10 + i;
    dem_world *all = make(3, p), *part = make(2, p);
    size_t sz = 0;
    dem_arrays A;
    TRY(all, dem_world_arrays(all, &A));
    size_t ic = 0;
    for (size_t i = 0; i < 3; ++i) if (A.id[i] == 12) ic = i;
    TRY(all, dem_world_pack_particle(all, ic, NULL, &sz));
    char *buf = malloc(sz);
    TRY(all, dem_world_pack_particle(all, ic, buf, &sz));
    TRY(part, dem_world_unpack_particle(part, buf, sz, 1));
    free(buf);
    TRY(part, dem_world_arrays(part, &A));
    check_abs("ghost: owned count", (double)A.n_owned, 2.0, 0.0);
    check_abs("ghost: ghost count", (double)A.n_ghost, 1.0, 0.0);
    double gx0 = A.x[3 * 2];
    TRY(all, dem_world_step(all, 1));
    TRY(part, dem_world_step(part, 1));
    dem_arrays B;
    TRY(all, dem_world_arrays(all, &B));
    TRY(part, dem_world_arrays(part, &A));
    double fa[9], fp[6];
    TRY(all, dem_world_particle_contacts(all, NULL, fa));
    TRY(part, dem_world_particle_contacts(part, NULL, fp));
    double dmax = 0, fref = 0;
    for (size_t i = 0; i < 2; ++i)
        for (size_t j = 0; j < 3; ++j)
            if (A.id[i] == B.id[j])
                for (int k = 0; k < 3; ++k) {
                    dmax = fmax(dmax, fabs(fp[3 * i + k] - fa[3 * j + k]));
                    fref = fmax(fref, fabs(fa[3 * j + k]));
                }
    /* difference: the original of the ghost gains a*dt/2 velocity (damping), the ghost does not */
    check_below("ghost: contact forces on owned particles with a ghost vs all owned (1 step) / |F|", dmax / fref, 5e-3);
    check_abs("ghost: ghost not integrated (x unchanged)", A.x[3 * 2], gx0, 0.0);
    int coord[2];
    TRY(part, dem_world_particle_contacts(part, coord, NULL));
    check_abs("ghost: contacts of owned particles include the ghost", (double)(coord[0] + coord[1]), 4.0, 0.0);
    TRY(part, dem_world_clear_ghosts(part));
    TRY(part, dem_world_arrays(part, &A));
    check_abs("clear_ghosts: ghost count", (double)A.n_ghost, 0.0, 0.0);
    TRY(part, dem_world_step(part, 1));
    TRY(part, dem_world_particle_contacts(part, coord, NULL));
    check_abs("clear_ghosts: contacts without the ghost", (double)(coord[0] + coord[1]), 2.0, 0.0);
    dem_world_destroy(&part);
    dem_world_destroy(&all);

    /* outlets: box and geometry-less */
    dem_particle q[3] = {test_particle(0, 0, 0, 0, 0, 0, a, 2500, 0),
                         test_particle(0.01, 0, 0, 0, 0, 0, a, 2000, 0),
                         test_particle(0.02, 0, 0, 0, 0, 0, a, 3000, 0)};
    dem_world *w = make(3, q);
    int ob, og;
    double lo[3] = {0.005, -0.005, -0.005}, hi[3] = {0.015, 0.005, 0.005};
    TRY(w, dem_world_add_outlet_box(w, lo, hi, &ob));
    TRY(w, dem_world_add_outlet(w, &og));
    TRY(w, dem_world_step(w, 1));
    int64_t c;
    double mm, m1 = 2000 * 4.0 / 3.0 * M_PI * a * a * a;
    TRY(w, dem_world_outlet_totals(w, ob, &c, &mm));
    check_abs("box outlet: count", (double)c, 1.0, 0.0);
    check_rel("box outlet: mass", mm, m1, 1e-12);
    TRY(w, dem_world_arrays(w, &A));
    size_t ir = A.id[0] == 2 ? 0 : 1;
    TRY(w, dem_world_remove_particle(w, ir, og));
    TRY(w, dem_world_outlet_totals(w, og, &c, &mm));
    check_abs("geometry-less outlet: count", (double)c, 1.0, 0.0);
    check_rel("geometry-less outlet: mass", mm, 3000 * 4.0 / 3.0 * M_PI * a * a * a, 1e-12);
    check_abs("particles left", (double)dem_world_count(w), 1.0, 0.0);
    dem_world_destroy(&w);
    return check_exit();
}
