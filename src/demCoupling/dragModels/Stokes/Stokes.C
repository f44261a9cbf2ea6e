/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "Stokes.H"
#include "addToRunTimeSelectionTable.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace dragModels
{
    defineTypeNameAndDebug(Stokes, 0);
    addToRunTimeSelectionTable(dragModel, Stokes, dictionary);
    addCoeffKeys(Stokes);
}
}

Foam::List<Foam::keySpec> Foam::dragModels::Stokes::coeffKeys()
{
    using kind = keySpec::kind;
    const double inf = HUGE_VAL;
    return List<keySpec>
    ({
        keySpec::num("voidageExponent", kind::Scalar, -inf, inf, false, false)
    });
}


Foam::dragModels::Stokes::Stokes(const dictionary& dict)
:
    dragModel(typeName, dict),
    n_(coeffs_.getOrDefault<scalar>("voidageExponent", 1.0))
{}


Foam::scalar Foam::dragModels::Stokes::K
(
    const scalar d, const scalar eps, const scalar,
    const scalar, const scalar muf
) const
{
    return 3.0*constant::mathematical::pi*muf*d*pow(eps, 1.0 - n_);
}
