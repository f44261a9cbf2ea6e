/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "Gidaspow.H"
#include "addToRunTimeSelectionTable.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace dragModels
{
    defineTypeNameAndDebug(Gidaspow, 0);
    addToRunTimeSelectionTable(dragModel, Gidaspow, dictionary);
    addCoeffKeys(Gidaspow);
}
}

Foam::List<Foam::keySpec> Foam::dragModels::Gidaspow::coeffKeys()
{
    using kind = keySpec::kind;
    const double inf = HUGE_VAL;
    return List<keySpec>
    ({
        keySpec::num("epsSwitch", kind::Scalar, 0, 1, true, true),
        keySpec::num("WenYuExponent", kind::Scalar, 0, inf, false, false)
    });
}


Foam::dragModels::Gidaspow::Gidaspow(const dictionary& dict)
:
    dragModel(typeName, dict),
    epsSwitch_(coeffs_.getOrDefault<scalar>("epsSwitch", 0.8)),
    n_(coeffs_.getOrDefault<scalar>("WenYuExponent", 2.65))
{}


Foam::scalar Foam::dragModels::Gidaspow::K
(
    const scalar d, const scalar eps, const scalar magSlip,
    const scalar rhof, const scalar muf
) const
{
    const scalar Vp = constant::mathematical::pi*pow3(d)/6.0;
    const scalar epss = 1.0 - eps;
    scalar betaByEpss;
    if (eps <= epsSwitch_)
    {
        betaByEpss = 150.0*epss*muf/(eps*sqr(d)) + 1.75*rhof*magSlip/d;
    }
    else
    {
        const scalar Re = max(d*rhof*magSlip*eps/muf, 1e-12);
        // C_D |u - v| written so that it stays finite as |u - v| -> 0
        const scalar CdSlip =
            Re < 1000
          ? 24.0*(1.0 + 0.15*pow(Re, 0.687))*muf/(d*rhof*eps)
          : 0.44*magSlip;
        betaByEpss = 0.75*CdSlip*eps*rhof*pow(eps, -n_)/d;
    }
    return Vp*betaByEpss;
}
