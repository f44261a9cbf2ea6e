/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

/* The caller's per-particle tags (dem_arrays.tag, dem.h DEM_N_TAGS):
 *  1. every tag follows its particle through the spatial re-sort of a list
 *     build, in a world where the sort does permute the particles;
 *  2. a removal (swap with the last owned) and the ghost block's shifts
 *     keep each particle's tags; an inserted particle and an unpacked
 *     ghost start with -1;
 *  3. an owned unpack (migration) and a restore start with -1 (tags are
 *     neither packed nor saved). */
#include "check.h"

enum { N = 400 };

/* The tag values the test gives particle id */
static int64_t want(int k, int64_t id) { return 1000 * (k + 1) + 3 * id; }

/* Particles whose tags are not want(k, id) (owned [0, n_owned)) */
static size_t wrong_tags(const dem_arrays *A)
{
    size_t bad = 0;
    for (size_t i = 0; i < A->n_owned; ++i)
        for (int k = 0; k < DEM_N_TAGS; ++k) bad += A->tag[k][i] != want(k, A->id[i]);
    return bad;
}

/* Tags other than -1 among [first, last) */
static size_t set_tags(const dem_arrays *A, size_t first, size_t last)
{
    size_t bad = 0;
    for (size_t i = first; i < last; ++i)
        for (int k = 0; k < DEM_N_TAGS; ++k) bad += A->tag[k][i] != -1;
    return bad;
}

static dem_world *make(void)
{
    const double g[3] = {0, 0, -9.81};
    dem_world *w = test_world(DEM_CONTACT_HERTZ_MINDLIN, 1e-5, g, 0.05);
    dem_material m = test_material(1e7, 0.3, 0.3, 0.0, 0.5);
    int mid;
    TRY(w, dem_world_add_material(w, &m, &mid));
    return w;
}

int main(void)
{
    dem_world *w = make();
    /* scattered in the reverse of the cell order, so that the sort permutes */
    dem_particle p[N];
    for (int i = 0; i < N; ++i) {
        const int j = N - 1 - i;
        p[i] = test_particle(-0.04 + 0.004 * (j % 20), -0.04 + 0.004 * (j / 20), 0.01 * ((i * 7) % 5 - 2),
                             0, 0, 0, 1e-3, 1000, 0);
    }
    TRY(w, dem_world_add_particles(w, N, p));
    dem_arrays A;
    TRY(w, dem_world_arrays(w, &A));
    check_abs("tags of added particles are -1 (particles with another value)", (double)set_tags(&A, 0, N), 0,
              0);
    int64_t first_ids[N];
    for (size_t i = 0; i < A.n_owned; ++i) {
        first_ids[i] = A.id[i];
        for (int k = 0; k < DEM_N_TAGS; ++k) A.tag[k][i] = want(k, A.id[i]);
    }

    /* 1. re-sort */
    const int64_t r0 = dem_world_reorder_count(w);
    TRY(w, dem_world_step(w, 20));
    TRY(w, dem_world_arrays(w, &A));
    size_t moved = 0;
    for (size_t i = 0; i < A.n_owned; ++i) moved += A.id[i] != first_ids[i];
    check_range("the list build re-sorted the particles (particles moved)", (double)moved, N / 2, N);
    check_range("reorder count rose", (double)(dem_world_reorder_count(w) - r0), 1, 1e9);
    check_abs("tags follow their particle through the re-sort (wrong tags)", (double)wrong_tags(&A), 0, 0);

    /* 2. a ghost, an insertion, removals */
    size_t sz = 0;
    TRY(w, dem_world_pack_ghost(w, 0, NULL, &sz));
    char *buf = malloc(sz);
    TRY(w, dem_world_pack_ghost(w, 0, buf, &sz));
    dem_world *o = make();
    dem_particle q = test_particle(0.045, 0.045, 0, 0, 0, 0, 1e-3, 1000, 0);
    TRY(o, dem_world_add_particles(o, 1, &q));
    dem_arrays B;
    TRY(o, dem_world_arrays(o, &B));
    B.tag[0][0] = 77;
    TRY(o, dem_world_unpack_particle(o, buf, sz, 1));
    TRY(o, dem_world_arrays(o, &B));
    check_abs("an unpacked ghost has tags -1 (other values)", (double)set_tags(&B, 1, 2), 0, 0);
    B.tag[1][1] = 55;    /* the ghost's, to follow through the shifts */
    dem_particle q2 = test_particle(0.045, 0.040, 0, 0, 0, 0, 1e-3, 1000, 0);
    TRY(o, dem_world_add_particles(o, 1, &q2));
    TRY(o, dem_world_arrays(o, &B));
    check_abs("an inserted particle has tags -1 (other values)", (double)set_tags(&B, 1, 2), 0, 0);
    check_abs("the owned particle keeps its tag across an insertion", (double)B.tag[0][0], 77, 0);
    check_abs("the ghost keeps its tag when shifted up", (double)B.tag[1][2], 55, 0);
    B.tag[2][1] = 66;
    TRY(o, dem_world_remove_particle(o, 0, -1));
    TRY(o, dem_world_arrays(o, &B));
    check_abs("the last owned particle keeps its tag in the removed one's slot", (double)B.tag[2][0], 66, 0);
    check_abs("the ghost keeps its tag when shifted down", (double)B.tag[1][1], 55, 0);
    free(buf);
    dem_world_destroy(&o);

    /* removal in the big world: the swapped particle keeps its tags */
    TRY(w, dem_world_remove_particle(w, 3, -1));
    TRY(w, dem_world_remove_particle(w, 0, -1));
    TRY(w, dem_world_arrays(w, &A));
    check_abs("tags after removals (wrong tags)", (double)wrong_tags(&A), 0, 0);

    /* 3. owned unpack and restore */
    TRY(w, dem_world_pack_particle(w, 5, NULL, &sz));
    buf = malloc(sz);
    TRY(w, dem_world_pack_particle(w, 5, buf, &sz));
    o = make();
    TRY(o, dem_world_arrays(o, &B));
    TRY(o, dem_world_unpack_particle(o, buf, sz, 0));
    TRY(o, dem_world_arrays(o, &B));
    check_abs("a particle unpacked as owned has tags -1 (other values)", (double)set_tags(&B, 0, 1), 0, 0);
    free(buf);
    dem_world_destroy(&o);
    void *mem = NULL;
    size_t cap = 0, size = 0;
    TRY(w, dem_world_save_memory(w, &mem, &cap, &size));
    o = make();
    TRY(o, dem_world_restore_memory(o, mem, size));
    TRY(o, dem_world_arrays(o, &B));
    check_abs("restored particles have tags -1 (other values)", (double)set_tags(&B, 0, B.n_owned), 0, 0);
    check_abs("restored particle count", (double)B.n_owned, N - 2, 0);
    free(mem);
    dem_world_destroy(&o);
    dem_world_destroy(&w);
    return check_exit();
}
