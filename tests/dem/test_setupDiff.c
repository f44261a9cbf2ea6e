/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* dem_world_setup_diff: a world and its saved-and-restored copy are the
 * same setup (also with particles moved on: the state differs, the setup
 * not); a changed friction, contact law, extra material, material pair or
 * wall material is found and named, the first world's value first. */
#include "check.h"

/* law, friction of material 0, wall material, with a pair override */
static dem_world *setup(dem_contact_law law, double mu, int wallMat, int pair)
{
    dem_world *w = test_world(law, 1e-5, NULL, 0.05);
    dem_material m = test_material(1e7, 0.3, mu, 0, 0.5);
    int a, b;
    TRY(w, dem_world_add_material(w, &m, &a));
    TRY(w, dem_world_add_material(w, &m, &b));
    if (pair) TRY(w, dem_world_set_pair(w, a, b, &m));
    const double o[3] = {0, 0, -0.05}, n[3] = {0, 0, 1};
    TRY(w, dem_world_add_plane(w, o, n, wallMat, NULL, NULL));
    return w;
}

/* 1 if diff(a, b) reports a difference whose text contains want */
static int names(dem_world *a, dem_world *b, const char *want)
{
    char what[256];
    const int d = dem_world_setup_diff(a, b, what, sizeof what);
    printf("  setup_diff: %d \"%s\"\n", d, what);
    return d == 1 && strstr(what, want) != NULL;
}

static void expect(const char *name, int ok)
{
    printf("%s: %s: %s vs yes (tol exact)\n", ok ? "PASS" : "FAIL", name, ok ? "yes" : "no");
    if (!ok) check_failures++;
}

int main(void)
{
    dem_world *a = setup(DEM_CONTACT_HERTZ_MINDLIN, 0.4, 0, 1);
    dem_particle p = test_particle(0, 0, 0, 0, 0, -1, 1e-3, 2500, 0);
    TRY(a, dem_world_add_particles(a, 1, &p));
    void *buf = NULL;
    size_t cap = 0, size = 0;
    TRY(a, dem_world_save_memory(a, &buf, &cap, &size));
    TRY(a, dem_world_step(a, 100));
    dem_world *b = NULL;
    TRY(b, dem_world_create(&b));
    TRY(b, dem_world_restore_memory(b, buf, size));
    free(buf);
    expect("setup_diff: a world against its restored earlier state: the same setup",
           dem_world_setup_diff(a, b, NULL, 0) == 0);
    dem_world_destroy(&b);

    /* one change each: law, friction of material 0, wall material, pair */
    const struct { dem_contact_law law; double mu; int wall, pair; const char *name, *want; } cases[] = {
        {DEM_CONTACT_HERTZ_MINDLIN, 0.5, 0, 1, "friction 0.4 vs 0.5", "material 0: friction 0.4, the state's 0.5"},
        {DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP, 0.4, 0, 1, "contact law",
         "contactLaw: hertzMindlin, the state's hertzMindlinNoSlip"},
        {DEM_CONTACT_HERTZ_MINDLIN, 0.4, 0, 0, "a material pair more", "1 material pairs, the state 0"},
        {DEM_CONTACT_HERTZ_MINDLIN, 0.4, 1, 1, "wall material", "wall 0: material 0, the state's 1"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        b = setup(cases[k].law, cases[k].mu, cases[k].wall, cases[k].pair);
        char name[96];
        snprintf(name, sizeof name, "setup_diff: %s named", cases[k].name);
        expect(name, names(a, b, cases[k].want));
        dem_world_destroy(&b);
    }
    dem_world_destroy(&a);
    return check_exit();
}
