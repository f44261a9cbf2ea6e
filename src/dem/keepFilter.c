/*---------------------------------------------------------------------------*\
  demFoam DEM core - the keep filter of a decomposed set-up: which particles
  a processor stores (particles.c keeps the others' centres and radii in
  the shadow list, which random fills avoid), and the keep box that limits
  index-computed fills.
  docs/parallel.md, "Initial particles and settling".
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "dem_private.h"
#include <stdlib.h>
#include <string.h>

dem_status dem_world_set_keep_filter(dem_world *w, dem_inside_fn keep, void *user)
{
    if (!w) return DEM_ERR_ARG;
    w->keep = keep; w->keep_user = user;
    if (!keep) { free(w->shadow); w->shadow = NULL; w->nshadow = w->capshadow = 0; w->keep_box_set = 0; }
    return DEM_OK;
}

dem_status dem_world_set_keep_box(dem_world *w, const double lo[3], const double hi[3])
{
    if (!w) return DEM_ERR_ARG;
    if (!lo || !hi) { w->keep_box_set = 0; return DEM_OK; }
    memcpy(w->keep_lo, lo, sizeof w->keep_lo);
    memcpy(w->keep_hi, hi, sizeof w->keep_hi);
    w->keep_box_set = 1;
    return DEM_OK;
}
