/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "SchillerNaumann.H"
#include "addToRunTimeSelectionTable.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace dragModels
{
    defineTypeNameAndDebug(SchillerNaumann, 0);
    addToRunTimeSelectionTable(dragModel, SchillerNaumann, dictionary);
    addCoeffKeys(SchillerNaumann);
}
}

Foam::List<Foam::keySpec> Foam::dragModels::SchillerNaumann::coeffKeys()
{
    using kind = keySpec::kind;
    const double inf = HUGE_VAL;
    return List<keySpec>
    ({
        keySpec::num("voidageExponent", kind::Scalar, -inf, inf, false, false)
    });
}


Foam::dragModels::SchillerNaumann::SchillerNaumann(const dictionary& dict)
:
    dragModel(typeName, dict),
    n_(coeffs_.getOrDefault<scalar>("voidageExponent", 1.0))
{}


Foam::scalar Foam::dragModels::SchillerNaumann::K
(
    const scalar d, const scalar eps, const scalar magSlip,
    const scalar rhof, const scalar muf
) const
{
    const scalar pi = constant::mathematical::pi;
    const scalar epsRe = (n_ == 1.0 ? 1.0 : eps);
    const scalar Re = rhof*d*magSlip*epsRe/muf;
    const scalar corr = pow(eps, 1.0 - n_);
    if (Re < 1000)
    {
        return 3.0*pi*muf*d*(1.0 + 0.15*pow(Re, 0.687))*corr;
    }
    return 0.125*pi*0.44*rhof*sqr(d)*magSlip*corr;
}
