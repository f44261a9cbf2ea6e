/*---------------------------------------------------------------------------*\
  demFoam DEM core - the frame of a box or cylinder fill that computes each
  particle from its index (lattice and randomBlocks fills): axes, extents,
  the keep box seen in the frame, the check that the region is empty.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#ifndef DEM_FILL_FRAME_H
#define DEM_FILL_FRAME_H

#include "dem_private.h"

typedef struct {
    double o[3], e[3][3]; /* origin, axes: e[0], e[1] in a layer, e[2] across */
    double len[3];        /* extent along each axis from o */
    double R;             /* cylinder: radius about o + (R, R, t) (0: box) */
} dem_fill_frame;

/* box [lo, hi] (layers along z) */
dem_status dem_fill_frame_box(dem_world *w, const char *fn, const double lo[3], const double hi[3],
                              dem_fill_frame *f);
/* cylinder (layers along its axis); o is the corner of the square around
   the base disc */
dem_status dem_fill_frame_cylinder(dem_world *w, const char *fn, const double base[3], const double axis[3],
                                   double radius, double length, dem_fill_frame *f);
/* DEM_ERR_RANGE naming a particle placed before that lies in the region
   (these fills check no overlaps with earlier particles) */
dem_status dem_fill_region_free(dem_world *w, const dem_fill_frame *f, const char *fn);
/* the keep box in frame coordinates (its 8 corners' extent): 0 if no keep
   box is set (compute everything) */
int dem_fill_keep_extent(const dem_world *w, const dem_fill_frame *f, double mn[3], double mx[3]);
/* a world position from frame coordinates */
void dem_fill_frame_point(const dem_fill_frame *f, const double c[3], double x[3]);
/* a fill over a frame, and the public box / cylinder entry points built on
   it (frame checked, then fill(w, &frame, n, t, inserted, fn)) */
typedef dem_status (*dem_frame_fill)(dem_world *w, const dem_fill_frame *f, size_t n,
                                     const dem_particle_template *t, size_t *inserted, const char *fn);
dem_status dem_fill_in_box(dem_world *w, const char *fn, dem_frame_fill fill, const double lo[3],
                           const double hi[3], size_t n, const dem_particle_template *t, size_t *inserted);
dem_status dem_fill_in_cylinder(dem_world *w, const char *fn, dem_frame_fill fill, const double base[3],
                                const double axis[3], double radius, double length, size_t n,
                                const dem_particle_template *t, size_t *inserted);
/* store particle id at x (radius r, density rho, the template's material
   and velocity) */
dem_status dem_fill_append(dem_world *w, const dem_particle_template *t, int64_t id, const double x[3],
                           double r, double rho);
/* book a completed fill of n particles with ids base .. base + n - 1 */
void dem_fill_done(dem_world *w, int64_t base, size_t n, size_t *inserted);
/* splitmix64's finaliser: independent streams from (seed, index) */
uint64_t dem_mix64(uint64_t z);

#endif
