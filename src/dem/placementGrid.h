/*---------------------------------------------------------------------------*\
  demFoam DEM core - the private linked-cell grid on which the random fills
  (fill.c, fillBlocks.c) test a trial position against the spheres placed.
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#ifndef DEM_PLACEMENT_GRID_H
#define DEM_PLACEMENT_GRID_H

#include "dem_private.h"

typedef struct {
    double lo[3], cs; int nc[3];
    int *head, *next; double *xr; /* x, y, z, r per item */
    size_t n, cap;
} dem_pgrid;

/* cells of edge cs (>= the largest diameter) over [lo, hi], grown if they
   would be more than 4 expect + 1e6; 0 if out of memory */
int  dem_pgrid_init(dem_pgrid *g, const double lo[3], const double hi[3], double cs, size_t expect);
void dem_pgrid_free(dem_pgrid *g);
/* add sphere (x, r); 0 if out of memory */
int  dem_pgrid_add(dem_pgrid *g, const double *x, double r);
/* 1 if sphere (x, r) overlaps none in the grid */
int  dem_pgrid_free_at(const dem_pgrid *g, const double *x, double r);

#endif
