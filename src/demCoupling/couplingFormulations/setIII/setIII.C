/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "setIII.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace couplingFormulations
{
    defineTypeNameAndDebug(setIII, 0);
    addToRunTimeSelectionTable(couplingFormulation, setIII, dictionary);
}
}
