/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "DiFelice.H"
#include "addToRunTimeSelectionTable.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace dragModels
{
    defineTypeNameAndDebug(DiFelice, 0);
    addToRunTimeSelectionTable(dragModel, DiFelice, dictionary);
}
}

Foam::dragModels::DiFelice::DiFelice(const dictionary& dict)
:
    dragModel(typeName, dict)
{}


Foam::scalar Foam::dragModels::DiFelice::K
(
    const scalar d, const scalar eps, const scalar magSlip,
    const scalar rhof, const scalar muf
) const
{
    const scalar Re = max(rhof*d*eps*magSlip/muf, 1e-12);
    // C_d0 |u - v| = (0.63 sqrt(|u-v|) + 4.8 sqrt(mu/(rho d eps)))^2:
    // finite for |u - v| -> 0
    const scalar a = 0.63*sqrt(magSlip) + 4.8*sqrt(muf/(rhof*d*eps));
    const scalar Cd0Slip = sqr(a);
    const scalar chi = 3.7 - 0.65*exp(-0.5*sqr(1.5 - log10(Re)));
    return 0.125*Cd0Slip*rhof*constant::mathematical::pi*sqr(d)
        *pow(eps, 2.0 - chi);
}
