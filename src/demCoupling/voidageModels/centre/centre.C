/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "centre.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace voidageModels
{
    defineTypeNameAndDebug(centre, 0);
    addToRunTimeSelectionTable(voidageModel, centre, dictionary);
}
}

Foam::voidageModels::centre::centre
(
    const dictionary& dict, const fvMesh& mesh, const particleLocator& l
)
:
    voidageModel(typeName, dict, mesh, l)
{}


void Foam::voidageModels::centre::addWeights
(
    const point&, const scalar, const label hostCell,
    DynamicList<label>& cells, DynamicList<scalar>& weights,
    DynamicList<remoteSample>&
) const
{
    cells.append(hostCell);
    weights.append(1.0);
}
