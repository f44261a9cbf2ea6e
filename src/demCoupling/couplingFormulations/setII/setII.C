/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "setII.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace couplingFormulations
{
    defineTypeNameAndDebug(setII, 0);
    addToRunTimeSelectionTable(couplingFormulation, setII, dictionary);
}
}
