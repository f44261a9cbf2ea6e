/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Inlets in decomposed runs: (1) the insertion overlap test includes ghost
 * copies: a ghost sphere covering the whole inlet square blocks it (no
 * particle inserted), while the same world without the ghost inserts at the
 * given rate; (2) dem_world_clear_inlets stops insertion (a serial state
 * restored on every processor keeps its inlets on the master only). */
#include "check.h"

static dem_world *inlet_world(int *mid)
{
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 5e-6, NULL, 0.1);
    dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
    TRY(w, dem_world_add_material(w, &m, mid));
    dem_particle_template t;
    memset(&t, 0, sizeof t);
    t.diameter.kind = DEM_DIST_FIXED; t.diameter.a = 1e-3;
    t.density.kind = DEM_DIST_FIXED; t.density.a = 2500;
    t.velocity[2] = -1.0;
    t.material = *mid;
    /* 4 x 4 mm square at z = 0.05, 2000 particles/s from t = 0 */
    double sq[12] = {0, 0, 0.05, 0.004, 0, 0.05, 0.004, 0.004, 0.05, 0, 0.004, 0.05};
    int in;
    TRY(w, dem_world_add_inlet(w, 4, sq, DEM_RATE_NUMBER, 2000.0, 0.0, 1.0, &t, &in));
    return w;
}

int main(void)
{
    int mid;
    /* 2000 steps of 5e-6 s = 0.01 s: 20 particles owed */
    dem_world *free_ = inlet_world(&mid);
    TRY(free_, dem_world_step(free_, 2000));
    check_abs("inlet without ghosts: particles inserted in 0.01 s at 2000/s", (double)dem_world_count(free_), 20.0, 1.0);

    /* a ghost of radius 5 mm centred on the inlet square (packed from a
       world that owns it) covers every candidate position */
    dem_world *owner = test_world(DEM_CONTACT_HERTZ_MINDLIN, 5e-6, NULL, 0.1);
    dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
    int omid;
    TRY(owner, dem_world_add_material(owner, &m, &omid));
    dem_particle big = test_particle(0.002, 0.002, 0.0505, 0, 0, 0, 5e-3, 2500, omid);
    big.id = 7000;
    TRY(owner, dem_world_add_particles(owner, 1, &big));
    size_t sz = 0;
    TRY(owner, dem_world_pack_ghost(owner, 0, NULL, &sz));
    char *buf = malloc(sz);
    TRY(owner, dem_world_pack_ghost(owner, 0, buf, &sz));
    dem_world *blocked = inlet_world(&mid);
    TRY(blocked, dem_world_unpack_particle(blocked, buf, sz, 1));
    free(buf);
    for (int s = 0; s < 2000; ++s) {
        TRY(blocked, dem_world_step_drift(blocked));
        TRY(blocked, dem_world_step_forces(blocked));
    }
    check_abs("inlet under a ghost sphere: particles inserted", (double)dem_world_count(blocked), 0.0, 0.0);

    /* clear_inlets: no insertion afterwards, count kept */
    TRY(free_, dem_world_clear_inlets(free_));
    const double n0 = (double)dem_world_count(free_);
    TRY(free_, dem_world_step(free_, 2000));
    check_abs("after dem_world_clear_inlets: particles inserted in 0.01 s", (double)dem_world_count(free_) - n0, 0.0, 0.0);
    check_status("dem_world_clear_inlets(NULL)", dem_world_clear_inlets(NULL), DEM_ERR_ARG);

    dem_world_destroy(&free_);
    dem_world_destroy(&blocked);
    dem_world_destroy(&owner);
    return check_exit();
}
