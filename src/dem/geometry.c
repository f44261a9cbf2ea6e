/*---------------------------------------------------------------------------*\
  demFoam DEM core - geometry helpers: wall displacement and the closest point
  on a triangle (wall contacts, neighbour search, insertion).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <string.h>

void dem_wall_position(const dem_world *w, int wall, double time, double off[3])
{
    const double *vel; double t0;
    if (w->wall_kind[wall] == 0) { const dem_plane *p = &w->planes[w->wall_index[wall]]; vel = p->vel; t0 = p->t0; }
    else { const dem_mesh *m = &w->meshes[w->wall_index[wall]]; vel = m->vel; t0 = m->t0; }
    for (int k = 0; k < 3; ++k) off[k] = vel[k] * (time - t0);
}

/* Closest point on triangle abc to p; returns feature: 0 face, 1..3 vertex
 * a,b,c, 4 edge ab, 5 edge bc, 6 edge ca (Voronoi regions of the triangle). */
int dem_closest_on_triangle(const double *p, const double *a, const double *b,
                            const double *c, double q[3])
{
    double ab[3], ac[3], ap[3];
    for (int k = 0; k < 3; ++k) { ab[k] = b[k] - a[k]; ac[k] = c[k] - a[k]; ap[k] = p[k] - a[k]; }
    double d1 = dem_dot(ab, ap), d2 = dem_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) { memcpy(q, a, 3 * sizeof(double)); return 1; }
    double bp[3];
    for (int k = 0; k < 3; ++k) bp[k] = p[k] - b[k];
    double d3 = dem_dot(ab, bp), d4 = dem_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) { memcpy(q, b, 3 * sizeof(double)); return 2; }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        double t = d1 / (d1 - d3);
        for (int k = 0; k < 3; ++k) q[k] = a[k] + t * ab[k];
        return 4;
    }
    double cp[3];
    for (int k = 0; k < 3; ++k) cp[k] = p[k] - c[k];
    double d5 = dem_dot(ab, cp), d6 = dem_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) { memcpy(q, c, 3 * sizeof(double)); return 3; }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        double t = d2 / (d2 - d6);
        for (int k = 0; k < 3; ++k) q[k] = a[k] + t * ac[k];
        return 6;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int k = 0; k < 3; ++k) q[k] = b[k] + t * (c[k] - b[k]);
        return 5;
    }
    double den = 1.0 / (va + vb + vc), v = vb * den, ww = vc * den;
    for (int k = 0; k < 3; ++k) q[k] = a[k] + ab[k] * v + ac[k] * ww;
    return 0;
}
