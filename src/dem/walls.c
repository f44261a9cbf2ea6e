/*---------------------------------------------------------------------------*\
  demFoam DEM core - walls: infinite planes and triangle meshes, each with a
  material and a translational velocity (position = p(t0) + vel (t - t0)).

  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static dem_status new_wall(dem_world *w, int kind, int index, int *wall_id)
{
    int *a = realloc(w->wall_kind, (size_t)(w->nwalls + 1) * sizeof(int));
    if (!a) return DEM_FAIL(w, DEM_ERR_NOMEM, "walls: %d", w->nwalls + 1);
    w->wall_kind = a;
    int *b = realloc(w->wall_index, (size_t)(w->nwalls + 1) * sizeof(int));
    if (!b) return DEM_FAIL(w, DEM_ERR_NOMEM, "walls: %d", w->nwalls + 1);
    w->wall_index = b;
    w->wall_kind[w->nwalls] = kind;
    w->wall_index[w->nwalls] = index;
    if (wall_id) *wall_id = w->nwalls;
    w->nwalls++;
    w->list_valid = 0;
    w->forces_valid = 0;
    return DEM_OK;
}

static dem_status check_vel(dem_world *w, const double *vel, double out[3], const char *fn)
{
    for (int k = 0; k < 3; ++k) {
        out[k] = vel ? vel[k] : 0.0;
        if (!isfinite(out[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "%s: velocity[%d] = %g; must be finite", fn, k, out[k]);
    }
    return DEM_OK;
}

dem_status dem_world_add_plane(dem_world *w, const double point[3], const double normal[3],
                               int material, const double velocity[3], int *wall_id)
{
    if (!w) return DEM_ERR_ARG;
    DEM_NEED(w, point, "add_plane");
    DEM_NEED(w, normal, "add_plane");
    if (material < 0 || material >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "add_plane: material = %d; allowed 0..%d (%d materials defined)",
                        material, w->nmat - 1, w->nmat);
    double nn = sqrt(dem_dot(normal, normal));
    if (!(nn > 0) || !isfinite(nn))
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_plane: normal (%g %g %g) has length %g; need finite components "
                        "and a length > 0 and finite", normal[0], normal[1], normal[2], nn);
    if (!isfinite(point[0] + point[1] + point[2]))
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_plane: point (%g %g %g); need finite coordinates (and a finite sum)",
                        point[0], point[1], point[2]);
    dem_plane P;
    memset(&P, 0, sizeof P);
    dem_status s = check_vel(w, velocity, P.vel, "add_plane");
    if (s) return s;
    for (int k = 0; k < 3; ++k) { P.x0[k] = point[k]; P.n[k] = normal[k] / nn; }
    P.t0 = w->time;
    P.material = material;
    P.wall = w->nwalls;
    dem_plane *a = realloc(w->planes, (size_t)(w->nplanes + 1) * sizeof *a);
    if (!a) return DEM_FAIL(w, DEM_ERR_NOMEM, "planes: %d", w->nplanes + 1);
    w->planes = a;
    w->planes[w->nplanes] = P;
    s = new_wall(w, 0, w->nplanes, wall_id);
    if (s) return s;
    w->nplanes++;
    return DEM_OK;
}

dem_status dem_world_add_trimesh(dem_world *w, size_t nv, const double *vertices,
                                 size_t ntri, const int *triangles, int material,
                                 const double velocity[3], int *wall_id)
{
    if (!w) return DEM_ERR_ARG;
    if (nv) DEM_NEED(w, vertices, "add_trimesh");
    if (ntri) DEM_NEED(w, triangles, "add_trimesh");
    if (material < 0 || material >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "add_trimesh: material = %d; allowed 0..%d (%d materials defined)",
                        material, w->nmat - 1, w->nmat);
    if (nv < 3 || nv > (size_t)INT_MAX)
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_trimesh: nv = %zu vertices; allowed 3..%d", nv, INT_MAX);
    if (ntri == 0 || ntri > (size_t)INT_MAX - w->ntri_all)
        return DEM_FAIL(w, DEM_ERR_RANGE, "add_trimesh: ntri = %zu triangles (%zu in other meshes); allowed 1..%zu",
                        ntri, w->ntri_all, (size_t)INT_MAX - w->ntri_all);
    for (size_t i = 0; i < 3 * nv; ++i)
        if (!isfinite(vertices[i]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "add_trimesh: vertex %zu coordinate %zu = %g; must be finite",
                            i / 3, i % 3, vertices[i]);
    dem_mesh M;
    memset(&M, 0, sizeof M);
    dem_status s = check_vel(w, velocity, M.vel, "add_trimesh");
    if (s) return s;
    M.nv = nv; M.ntri = ntri; M.material = material; M.t0 = w->time; M.wall = w->nwalls;
    M.v0 = malloc(3 * nv * sizeof(double));
    M.tri = malloc(3 * ntri * sizeof(int));
    M.nrm = malloc(3 * ntri * sizeof(double));
    if (!M.v0 || !M.tri || !M.nrm) {
        free(M.v0); free(M.tri); free(M.nrm);
        return DEM_FAIL(w, DEM_ERR_NOMEM, "trimesh wall: %zu vertices, %zu triangles", nv, ntri);
    }
    memcpy(M.v0, vertices, 3 * nv * sizeof(double));
    memcpy(M.tri, triangles, 3 * ntri * sizeof(int));
    for (size_t t = 0; t < ntri; ++t) {
        const int *tv = triangles + 3 * t;
        for (int c = 0; c < 3; ++c)
            if (tv[c] < 0 || (size_t)tv[c] >= nv) {
                free(M.v0); free(M.tri); free(M.nrm);
                return DEM_FAIL(w, DEM_ERR_RANGE, "add_trimesh: triangles[%zu] = %d (triangle %zu); allowed 0..%zu",
                                3 * t + (size_t)c, tv[c], t, nv - 1);
            }
        const double *a = vertices + 3 * tv[0], *b = vertices + 3 * tv[1], *c = vertices + 3 * tv[2];
        double e1[3], e2[3], nr[3];
        for (int k = 0; k < 3; ++k) { e1[k] = b[k] - a[k]; e2[k] = c[k] - a[k]; }
        dem_cross(e1, e2, nr);
        double l = sqrt(dem_dot(nr, nr));
        if (!(l > 0) || !isfinite(l)) {
            free(M.v0); free(M.tri); free(M.nrm);
            return DEM_FAIL(w, DEM_ERR_RANGE, "add_trimesh: triangle %zu (vertices %d %d %d) has area %g; need > 0 "
                            "and finite", t, tv[0], tv[1], tv[2], 0.5 * l);
        }
        for (int k = 0; k < 3; ++k) M.nrm[3 * t + k] = nr[k] / l;
    }
    dem_mesh *a = realloc(w->meshes, (size_t)(w->nmeshes + 1) * sizeof *a);
    int *tm = realloc(w->tri_mesh, (w->ntri_all + ntri) * sizeof(int));
    if (tm) w->tri_mesh = tm;
    int *tl = tm ? realloc(w->tri_local, (w->ntri_all + ntri) * sizeof(int)) : NULL;
    if (tl) w->tri_local = tl;
    if (a) w->meshes = a;
    if (!a || !tm || !tl) {
        free(M.v0); free(M.tri); free(M.nrm);
        return DEM_FAIL(w, DEM_ERR_NOMEM, "trimesh wall: %zu triangles", ntri);
    }
    for (size_t t = 0; t < ntri; ++t) {
        w->tri_mesh[w->ntri_all + t] = w->nmeshes;
        w->tri_local[w->ntri_all + t] = (int)t;
    }
    w->ntri_all += ntri;
    w->meshes[w->nmeshes] = M;
    s = new_wall(w, 1, w->nmeshes, wall_id);
    if (s) return s;
    w->nmeshes++;
    return DEM_OK;
}

dem_status dem_world_set_wall_velocity(dem_world *w, int wall_id, const double velocity[3])
{
    if (!w) return DEM_ERR_ARG;
    if (wall_id < 0 || wall_id >= w->nwalls)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "set_wall_velocity: wall %d; allowed 0..%d (%d walls defined)",
                        wall_id, w->nwalls - 1, w->nwalls);
    double v[3];
    dem_status s = check_vel(w, velocity, v, "set_wall_velocity");
    if (s) return s;
    /* the wall moves to its current position, which must be representable */
    if (w->wall_kind[wall_id] == 0) {
        dem_plane *P = &w->planes[w->wall_index[wall_id]];
        for (int k = 0; k < 3; ++k)
            if (!isfinite(P->x0[k] + P->vel[k] * (w->time - P->t0)))
                return DEM_FAIL(w, DEM_ERR_RANGE, "set_wall_velocity: wall %d has moved out of the range of "
                                "doubles (point[%d] = %g + %g x %g s)", wall_id, k, P->x0[k], P->vel[k],
                                w->time - P->t0);
        for (int k = 0; k < 3; ++k) { P->x0[k] += P->vel[k] * (w->time - P->t0); P->vel[k] = v[k]; }
        P->t0 = w->time;
    } else {
        dem_mesh *M = &w->meshes[w->wall_index[wall_id]];
        for (size_t i = 0; i < M->nv; ++i)
            for (int k = 0; k < 3; ++k)
                if (!isfinite(M->v0[3 * i + k] + M->vel[k] * (w->time - M->t0)))
                    return DEM_FAIL(w, DEM_ERR_RANGE, "set_wall_velocity: wall %d has moved out of the range of "
                                    "doubles (vertex %zu coordinate %d = %g + %g x %g s)", wall_id, i, k,
                                    M->v0[3 * i + k], M->vel[k], w->time - M->t0);
        for (size_t i = 0; i < M->nv; ++i)
            for (int k = 0; k < 3; ++k) M->v0[3 * i + k] += M->vel[k] * (w->time - M->t0);
        for (int k = 0; k < 3; ++k) M->vel[k] = v[k];
        M->t0 = w->time;
    }
    /* displacement since the last build is no longer vel * (t - t_build): rebuild */
    w->list_valid = 0;
    return DEM_OK;
}
