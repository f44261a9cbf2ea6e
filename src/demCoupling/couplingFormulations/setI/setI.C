/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "setI.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace couplingFormulations
{
    defineTypeNameAndDebug(setI, 0);
    addToRunTimeSelectionTable(couplingFormulation, setI, dictionary);
}
}
