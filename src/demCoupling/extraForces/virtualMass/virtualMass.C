/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "virtualMass.H"
#include "addToRunTimeSelectionTable.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace extraForces
{
    defineTypeNameAndDebug(virtualMass, 0);
    addToRunTimeSelectionTable(extraForce, virtualMass, dictionary);
    addCoeffKeys(virtualMass);
}
}


Foam::List<Foam::keySpec> Foam::extraForces::virtualMass::coeffKeys()
{
    using kind = keySpec::kind;
    const double inf = HUGE_VAL;
    return List<keySpec>
    ({
        keySpec::num("Cvm", kind::Scalar, 0, inf, false, false)
    });
}


Foam::extraForces::virtualMass::virtualMass(const dictionary& dict)
:
    extraForce(typeName, dict),
    Cvm_(coeffs_.getOrDefault<scalar>("Cvm", 0.5))
{
    if (!(Cvm_ >= 0))
    {
        badCoeff("Cvm", Cvm_, ">= 0 (0.5 for a sphere)");
    }
}


Foam::scalar Foam::extraForces::virtualMass::addedMass
(
    const scalar d,
    const scalar rhof,
    const scalar eps
) const
{
    return Cvm_*rhof*constant::mathematical::pi*pow3(d)/6.0;
}


Foam::vector Foam::extraForces::virtualMass::force
(
    const particleState& s
) const
{
    return addedMass(s.d, s.rhof, s.eps)*s.DuDt;
}
