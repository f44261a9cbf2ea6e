/*---------------------------------------------------------------------------*\
  demFoam DEM core - the contact-law registry: the one place a law is
  listed (its file under laws/ holds everything else).
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/
#include "law.h"
#include <math.h>
#include <string.h>

/* in the order of dem_contact_law (dem.h) */
const dem_law *const dem_laws[DEM_CONTACT_LAW_COUNT] = {
    [DEM_CONTACT_HERTZ_MINDLIN] = &dem_law_hertzMindlin,
    [DEM_CONTACT_LINEAR_SPRING_DASHPOT] = &dem_law_linearSpringDashpot,
    [DEM_CONTACT_HERTZ_SPRING_DASHPOT] = &dem_law_hertzSpringDashpot,
    [DEM_CONTACT_HERTZ_MINDLIN_NO_SLIP] = &dem_law_hertzMindlinNoSlip,
};

const char *dem_contact_law_name(dem_contact_law law)
{
    if ((int)law < 0 || law >= DEM_CONTACT_LAW_COUNT) return NULL;
    return dem_laws[law]->name;
}

dem_status dem_contact_law_from_name(const char *name, dem_contact_law *law)
{
    if (!name || !law) return DEM_ERR_ARG;
    for (int i = 0; i < DEM_CONTACT_LAW_COUNT; ++i)
        if (strcmp(name, dem_laws[i]->name) == 0) { *law = (dem_contact_law)i; return DEM_OK; }
    return DEM_ERR_NOTFOUND;
}

int dem_material_rigid(const dem_material *m, int law)
{
    return isinf(dem_laws[law]->stiffness(m));
}
