/*---------------------------------------------------------------------------*\
  demFoam DEM core - insertion and outlets (placeholder).
\*---------------------------------------------------------------------------*/
#include "dem_private.h"

dem_status dem_inlets_run(dem_world *w) { (void)w; return DEM_OK; }
dem_status dem_outlets_run(dem_world *w) { (void)w; return DEM_OK; }
