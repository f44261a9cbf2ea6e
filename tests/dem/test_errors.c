/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* Input checks return the documented status and say where and what. */
#include "check.h"

static void has_text(const char *name, dem_world *w, const char *needle)
{
    const char *e = dem_world_last_error(w);
    int ok = strstr(e, needle) != NULL && strstr(e, ".c:") != NULL;
    printf("%s: %s: \"%s\" vs contains \"%s\" and file:line (tol exact)\n", ok ? "PASS" : "FAIL", name, e, needle);
    if (!ok) check_failures++;
}

int main(void)
{
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-6, NULL, 0.05);
    dem_material m = test_material(1e7, 0.3, 0.3, 0.0, 0.5);
    int id;
    m.poisson_ratio = 0.5;
    check_status("error nu = 0.5", dem_world_add_material(w, &m, &id), DEM_ERR_RANGE);
    has_text("error text nu", w, "0.5");
    m.poisson_ratio = -0.1;
    check_status("error nu = -0.1", dem_world_add_material(w, &m, &id), DEM_ERR_RANGE);
    m.poisson_ratio = 0.3;
    m.friction = -0.1;
    check_status("error friction < 0", dem_world_add_material(w, &m, &id), DEM_ERR_RANGE);
    has_text("error text friction", w, "-0.1");
    m.friction = 0.3;
    m.rolling_friction = -1e-5;
    check_status("error rolling friction < 0", dem_world_add_material(w, &m, &id), DEM_ERR_RANGE);
    m.rolling_friction = 0;
    m.restitution = 1.5;
    check_status("error restitution 1.5", dem_world_add_material(w, &m, &id), DEM_ERR_RANGE);
    m.restitution = 0.0;
    check_status("error restitution 0", dem_world_add_material(w, &m, &id), DEM_ERR_RANGE);
    m.restitution = 0.5;
    m.damping = 0.2;
    check_status("error restitution and damping both given", dem_world_add_material(w, &m, &id), DEM_ERR_ARG);
    m.damping = -1;
    m.youngs_modulus = 0;
    check_status("error E = 0 (Hertz-Mindlin)", dem_world_add_material(w, &m, &id), DEM_ERR_RANGE);
    m.youngs_modulus = 1e7;
    TRY(w, dem_world_add_material(w, &m, &id));
    dem_particle p = test_particle(0, 0, 0, 0, 0, 0, 0.0, 2500, id);
    check_status("error radius = 0", dem_world_add_particles(w, 1, &p), DEM_ERR_RANGE);
    has_text("error text radius", w, "radius");
    p.radius = -1e-3;
    check_status("error radius < 0", dem_world_add_particles(w, 1, &p), DEM_ERR_RANGE);
    p.radius = 1e-3;
    p.density = 0;
    check_status("error density = 0", dem_world_add_particles(w, 1, &p), DEM_ERR_RANGE);
    p.density = 2500;
    p.material = 7;
    check_status("error unknown material", dem_world_add_particles(w, 1, &p), DEM_ERR_NOTFOUND);
    p.material = id;
    p.v[0] = NAN;
    check_status("error NaN velocity on input", dem_world_add_particles(w, 1, &p), DEM_ERR_NAN);
    p.v[0] = 0;
    TRY(w, dem_world_add_particles(w, 1, &p));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    A.x[1] = NAN;
    check_status("error NaN position in state", dem_world_step(w, 1), DEM_ERR_NAN);
    has_text("error text NaN", w, "position");
    A.x[1] = 0;
    A.fluid_velocity[2] = INFINITY;
    A.drag_coeff[0] = 1e-3;
    check_status("error Inf fluid velocity in state", dem_world_step(w, 1), DEM_ERR_NAN);
    A.fluid_velocity[2] = 0;
    TRY(w, dem_world_step(w, 1));
    /* time step above the safe fraction of the contact time */
    double tc;
    TRY(w, dem_world_contact_time(w, 0.0, &tc));
    dem_config c;
    dem_config_default(&c);
    c.dt = 0.3 * tc;
    for (int k = 0; k < 3; ++k) { c.domain_lo[k] = -0.05; c.domain_hi[k] = 0.05; }
    c.gravity[2] = 0;
    TRY(w, dem_world_configure(w, &c));
    check_status("error dt = 0.3 t_contact (max 0.2)", dem_world_step(w, 1), DEM_ERR_TIMESTEP);
    has_text("error text dt", w, "dt");
    c.dt = 0.1 * tc;
    TRY(w, dem_world_configure(w, &c));
    check_status("dt = 0.1 t_contact accepted", dem_world_step(w, 1), DEM_OK);
    /* impact_speed > 0: Hertz time at that speed instead of the Rayleigh time */
    double th;
    TRY(w, dem_world_contact_time(w, 1.0, &th));
    c.dt = 0.3 * tc;
    c.impact_speed = 1.0;
    TRY(w, dem_world_configure(w, &c));
    check_status(0.3 * tc < 0.2 * th ? "dt = 0.3 t_Rayleigh accepted with impact_speed 1 m/s (< 0.2 t_Hertz)"
                                     : "(setup) dt between the limits", dem_world_step(w, 1), DEM_OK);
    c.impact_speed = 0.0;
    c.dt = -1;
    check_status("error dt < 0", dem_world_configure(w, &c), DEM_ERR_RANGE);
    c.dt = 1e-6;
    c.skin = 1e-3;
    check_status("error changing skin with particles present", dem_world_configure(w, &c), DEM_ERR_STATE);
    check_status("error remove index out of range", dem_world_remove_particle(w, 5, -1), DEM_ERR_RANGE);
    check_status("error step < 0", dem_world_step(w, -1), DEM_ERR_RANGE);
    dem_contact_law law;
    check_status("law lookup hertzMindlin", dem_contact_law_from_name("hertzMindlin", &law), DEM_OK);
    check_status("law lookup unknown", dem_contact_law_from_name("hooke", &law), DEM_ERR_NOTFOUND);
    int ok = strcmp(dem_status_string(DEM_ERR_TIMESTEP),
                    "time step above the safe fraction of the contact time") == 0;
    printf("%s: status string DEM_ERR_TIMESTEP: \"%s\" vs header text (tol exact)\n", ok ? "PASS" : "FAIL",
           dem_status_string(DEM_ERR_TIMESTEP));
    if (!ok) check_failures++;
    dem_world_destroy(&w);
    check_abs("destroy NULLs the handle", w == NULL ? 0.0 : 1.0, 0.0, 0.0);
    return check_exit();
}
