/*---------------------------------------------------------------------------*\
  demFoam DEM core - save/restore and pack/unpack (placeholder).
\*---------------------------------------------------------------------------*/
#include "dem_private.h"

dem_status dem_world_save(const dem_world *w, const char *path)
{
    if (!w || !path) return DEM_ERR_ARG;
    return DEM_FAIL(w, DEM_ERR_STATE, "save to '%s': not implemented yet", path);
}
dem_status dem_world_restore(dem_world *w, const char *path)
{
    if (!w || !path) return DEM_ERR_ARG;
    return DEM_FAIL(w, DEM_ERR_STATE, "restore from '%s': not implemented yet", path);
}
dem_status dem_world_pack_particle(const dem_world *w, size_t index, void *buf, size_t *size)
{
    (void)buf; (void)size;
    if (!w) return DEM_ERR_ARG;
    return DEM_FAIL(w, DEM_ERR_STATE, "pack particle %zu: not implemented yet", index);
}
dem_status dem_world_unpack_particle(dem_world *w, const void *buf, size_t size, int ghost)
{
    (void)buf; (void)ghost;
    if (!w) return DEM_ERR_ARG;
    return DEM_FAIL(w, DEM_ERR_STATE, "unpack (%zu bytes): not implemented yet", size);
}
dem_status dem_world_clear_ghosts(dem_world *w)
{
    if (!w) return DEM_ERR_ARG;
    w->ng = 0;
    w->list_valid = 0;
    return DEM_OK;
}
