/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "Beetstra.H"
#include "addToRunTimeSelectionTable.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace dragModels
{
    defineTypeNameAndDebug(Beetstra, 0);
    addToRunTimeSelectionTable(dragModel, Beetstra, dictionary);
}
}

Foam::dragModels::Beetstra::Beetstra(const dictionary& dict)
:
    dragModel(typeName, dict)
{}


Foam::scalar Foam::dragModels::Beetstra::K
(
    const scalar d, const scalar eps, const scalar magSlip,
    const scalar rhof, const scalar muf
) const
{
    const scalar phi = max(1.0 - eps, 0.0);
    const scalar e = 1.0 - phi;
    const scalar Re = max(rhof*e*magSlip*d/muf, 1e-12);
    const scalar F =
        10.0*phi/sqr(e) + sqr(e)*(1.0 + 1.5*sqrt(phi))
      + 0.413*Re/(24.0*sqr(e))
       *(1.0/e + 3.0*phi*e + 8.4*pow(Re, -0.343))
       /(1.0 + pow(10.0, 3.0*phi)*pow(Re, -0.5*(1.0 + 4.0*phi)));
    return 3.0*constant::mathematical::pi*muf*d*e*F;
}
