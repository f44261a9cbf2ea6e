/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* OpenFOAM runs with floating-point traps (FOAM_SIGFPE): the core must not
 * raise division-by-zero, invalid or overflow in normal operation.  With
 * those traps enabled (glibc feenableexcept), pour spheres onto plane and
 * triangle-mesh walls whose material has zero rolling friction and
 * damping given (coupling report 1), for every contact law; any exception
 * kills the test (non-zero exit). */
#define _GNU_SOURCE
#include <fenv.h>
#include "check.h"

int main(void)
{
#if defined(__GLIBC__)
    feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
    const dem_contact_law laws[4] = {DEM_CONTACT_HERTZ_MINDLIN, DEM_CONTACT_LINEAR_SPRING_DASHPOT,
                                     DEM_CONTACT_HERTZ_SPRING_DASHPOT, DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP};
    for (int l = 0; l < 4; ++l) {
        dem_world *w = NULL;
        TRY(w, dem_world_create(&w));
        dem_config c;
        dem_config_default(&c);
        c.contact_law = laws[l];
        c.dt = 2e-6;
        c.max_dt_fraction = 1.0;
        c.max_overlap_ratio = 0.5;
        for (int k = 0; k < 3; ++k) { c.domain_lo[k] = 0; c.domain_hi[k] = 0.03; }
        c.domain_hi[2] = 0.1;
        TRY(w, dem_world_configure(w, &c));
        dem_material m = test_material(1e7, 0.3, 0.4, 4e-5, -1);
        m.damping = laws[l] == DEM_CONTACT_HERTZ_MINDLIN || laws[l] == DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP ? 0.3 : 0.005;
        m.stiffness_n = 20000;
        int glass, wall;
        TRY(w, dem_world_add_material(w, &m, &glass));
        dem_material wm = test_material(1e7, 0.3, 0.1, 0.0, -1);
        wm.damping = m.damping;
        wm.stiffness_n = 20000;
        TRY(w, dem_world_add_material(w, &wm, &wall));
        double o[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
        TRY(w, dem_world_add_plane(w, o, nz, wall, NULL, NULL));
        double v[12] = {0, 0, 0, 0.03, 0, 0, 0.03, 0, 0.1, 0, 0, 0.1};
        double v2[12] = {0, 0.03, 0, 0.03, 0.03, 0, 0.03, 0.03, 0.1, 0, 0.03, 0.1};
        int t[6] = {0, 1, 2, 0, 2, 3};
        TRY(w, dem_world_add_trimesh(w, 4, v, 2, t, wall, NULL, NULL));
        TRY(w, dem_world_add_trimesh(w, 4, v2, 2, t, wall, NULL, NULL));
        dem_particle_template tp;
        memset(&tp, 0, sizeof tp);
        tp.diameter.kind = DEM_DIST_UNIFORM; tp.diameter.a = 1.8e-3; tp.diameter.b = 2.2e-3;
        tp.density.kind = DEM_DIST_FIXED; tp.density.a = 2500;
        tp.material = glass;
        double lo[3] = {0, 0, 0}, hi[3] = {0.03, 0.03, 0.09};
        size_t got;
        TRY(w, dem_world_fill_box(w, lo, hi, NULL, NULL, QUICK ? 300 : 500, &tp, &got));
        dem_arrays A;
        TRY(w, dem_world_arrays(w, &A)); /* coupling arrays on */
        double tc;
        TRY(w, dem_world_contact_time(w, 0.0, &tc));
        TRY(w, dem_world_contact_time(w, 1.0, &tc));
        size_t seen = 0;
        dem_stats st;
        for (int chunk = 0; chunk < 20; ++chunk) {
            TRY(w, dem_world_step(w, 1500));
            TRY(w, dem_world_stats(w, &st));
            if (st.pair_contacts + st.wall_contacts > seen) seen = st.pair_contacts + st.wall_contacts;
        }
        char name[128];
        snprintf(name, sizeof name, "%s with FP traps on: poured and settling, max contacts seen", dem_contact_law_name(laws[l]));
        check_below(name, -(double)seen, 0.0);
        dem_world_destroy(&w);
    }
#else
    printf("SKIP: fpe traps: feenableexcept needs glibc\n");
#endif
    return check_exit();
}
