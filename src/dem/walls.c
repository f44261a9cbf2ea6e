/*---------------------------------------------------------------------------*\
  demFoam DEM core - walls: infinite planes and triangle meshes, each with a
  material and a translational velocity (position = p(t0) + vel (t - t0)).
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
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

static dem_status check_vel(dem_world *w, const double *vel, double out[3])
{
    for (int k = 0; k < 3; ++k) {
        out[k] = vel ? vel[k] : 0.0;
        if (!isfinite(out[k]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "wall velocity[%d] = %g; must be finite", k, out[k]);
    }
    return DEM_OK;
}

dem_status dem_world_add_plane(dem_world *w, const double point[3], const double normal[3],
                               int material, const double velocity[3], int *wall_id)
{
    if (!w || !point || !normal) return DEM_ERR_ARG;
    if (material < 0 || material >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "plane wall: material = %d; %d materials defined", material, w->nmat);
    double nn = sqrt(dem_dot(normal, normal));
    if (!(nn > 0) || !isfinite(nn) || !isfinite(point[0] + point[1] + point[2]))
        return DEM_FAIL(w, DEM_ERR_RANGE, "plane wall: normal (%g %g %g) must be finite and non-zero, "
                        "point finite", normal[0], normal[1], normal[2]);
    dem_plane P;
    memset(&P, 0, sizeof P);
    dem_status s = check_vel(w, velocity, P.vel);
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
    if (!w || (nv && !vertices) || (ntri && !triangles)) return DEM_ERR_ARG;
    if (material < 0 || material >= w->nmat)
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "trimesh wall: material = %d; %d materials defined", material, w->nmat);
    if (ntri == 0) return DEM_FAIL(w, DEM_ERR_ARG, "trimesh wall: no triangles");
    for (size_t i = 0; i < 3 * nv; ++i)
        if (!isfinite(vertices[i]))
            return DEM_FAIL(w, DEM_ERR_RANGE, "trimesh wall: vertex %zu coordinate %zu = %g; must be finite",
                            i / 3, i % 3, vertices[i]);
    dem_mesh M;
    memset(&M, 0, sizeof M);
    dem_status s = check_vel(w, velocity, M.vel);
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
                return DEM_FAIL(w, DEM_ERR_RANGE, "trimesh wall: triangle %zu vertex index %d; allowed 0..%zu",
                                t, tv[c], nv - 1);
            }
        const double *a = vertices + 3 * tv[0], *b = vertices + 3 * tv[1], *c = vertices + 3 * tv[2];
        double e1[3], e2[3], nr[3];
        for (int k = 0; k < 3; ++k) { e1[k] = b[k] - a[k]; e2[k] = c[k] - a[k]; }
        dem_cross(e1, e2, nr);
        double l = sqrt(dem_dot(nr, nr));
        if (!(l > 0)) {
            free(M.v0); free(M.tri); free(M.nrm);
            return DEM_FAIL(w, DEM_ERR_RANGE, "trimesh wall: triangle %zu (vertices %d %d %d) has zero area",
                            t, tv[0], tv[1], tv[2]);
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
        return DEM_FAIL(w, DEM_ERR_NOTFOUND, "wall %d; %d walls defined", wall_id, w->nwalls);
    double v[3];
    dem_status s = check_vel(w, velocity, v);
    if (s) return s;
    if (w->wall_kind[wall_id] == 0) {
        dem_plane *P = &w->planes[w->wall_index[wall_id]];
        for (int k = 0; k < 3; ++k) { P->x0[k] += P->vel[k] * (w->time - P->t0); P->vel[k] = v[k]; }
        P->t0 = w->time;
    } else {
        dem_mesh *M = &w->meshes[w->wall_index[wall_id]];
        for (size_t i = 0; i < M->nv; ++i)
            for (int k = 0; k < 3; ++k) M->v0[3 * i + k] += M->vel[k] * (w->time - M->t0);
        for (int k = 0; k < 3; ++k) M->vel[k] = v[k];
        M->t0 = w->time;
    }
    /* displacement since the last build is no longer vel * (t - t_build): rebuild */
    w->list_valid = 0;
    return DEM_OK;
}
