/*---------------------------------------------------------------------------*\
  demFoam DEM core tests - the clock (dem_world_set_time).
  The coupling sets the DEM clock to the fluid's, with settling run before
  the fluid's start time: the clock then counts from the value set, inlets
  open at their start time on it, and a moving wall keeps its position.

  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "check.h"

int main(void)
{
    /* time, invalid values */
    {
        dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-5, NULL, 0.1);
        check_status("set_time: NaN refused", dem_world_set_time(w, NAN), DEM_ERR_RANGE);
        TRY(w, dem_world_set_time(w, -0.05));
        check_abs("set_time: clock [s]", dem_world_time(w), -0.05, 0);
        TRY(w, dem_world_step(w, 1000));
        check_abs("set_time: clock after 1000 steps of 1e-5 s [s]", dem_world_time(w), -0.04, 1e-13);
        dem_world_destroy(&w);
    }
    /* an inlet opening at t = 0 on a clock that starts at -0.02 s: nothing
       before 0, then 5000/s */
    {
        dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 5e-6, NULL, 0.1);
        dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
        int mid, in;
        TRY(w, dem_world_add_material(w, &m, &mid));
        dem_particle_template t;
        memset(&t, 0, sizeof t);
        t.diameter.kind = DEM_DIST_FIXED; t.diameter.a = 1e-3;
        t.density.kind = DEM_DIST_FIXED; t.density.a = 2500;
        t.velocity[2] = -2.0;
        t.material = mid;
        double sq[12] = {0, 0, 0.05, 0.02, 0, 0.05, 0.02, 0.02, 0.05, 0, 0.02, 0.05};
        TRY(w, dem_world_set_time(w, -0.02));
        TRY(w, dem_world_add_inlet(w, 4, sq, DEM_RATE_NUMBER, 5000.0, 0.0, 1.0, &t, &in));
        TRY(w, dem_world_step(w, 4000));   /* to t = 0 */
        check_abs("set_time: particles inserted before the inlet's start", (double)dem_world_count(w), 0, 0);
        TRY(w, dem_world_step(w, 400));    /* to t = 0.002 s: 10 particles */
        check_abs("set_time: particles inserted in the first 2 ms after the start", (double)dem_world_count(w), 10, 1);
        dem_world_destroy(&w);
    }
    /* a plane moving at 0.1 m/s keeps its position when the clock is set:
       a particle resting on it (after settling) does not jump */
    {
        dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-6, NULL, 0.1);
        dem_material m = test_material(1e7, 0.3, 0.3, 0, 0.5);
        int mid, wall;
        TRY(w, dem_world_add_material(w, &m, &mid));
        double p0[3] = {0, 0, 0}, n[3] = {0, 0, 1}, v[3] = {0, 0, 0.1};
        TRY(w, dem_world_add_plane(w, p0, n, mid, v, &wall));
        TRY(w, dem_world_step(w, 1000));   /* the plane is at z = 1e-4 m */
        TRY(w, dem_world_set_time(w, 5.0));
        dem_particle p;
        memset(&p, 0, sizeof p);
        p.x[2] = 1e-4 + 0.5e-3;           /* touching the plane where it is now */
        p.id = -1; p.radius = 0.5e-3; p.density = 2500; p.material = mid;
        TRY(w, dem_world_add_particles(w, 1, &p));
        TRY(w, dem_world_step(w, 1));
        dem_arrays a;
        TRY(w, dem_world_arrays(w, &a));
        /* had the plane jumped by 0.1 m/s x 5 s it would be far above */
        check_below("set_time: moving plane kept its position (particle speed after one step) [m/s]",
                    fabs(a.v[2]), 0.01);
        dem_world_destroy(&w);
    }
    return check_exit();
}
