/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "SaffmanLift.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace extraForces
{
    defineTypeNameAndDebug(SaffmanLift, 0);
    addToRunTimeSelectionTable(extraForce, SaffmanLift, dictionary);
    addCoeffKeys(SaffmanLift);
}
}


Foam::List<Foam::keySpec> Foam::extraForces::SaffmanLift::coeffKeys()
{
    return List<keySpec>
    ({
        keySpec::choice("correction", wordList({"none", "Mei"}))
    });
}


Foam::extraForces::SaffmanLift::SaffmanLift(const dictionary& dict)
:
    extraForce(typeName, dict),
    Mei_(false)
{
    const word corr(coeffs_.getOrDefault<word>("correction", "none"));
    if (corr == "Mei")
    {
        Mei_ = true;
    }
    else if (corr != "none")
    {
        FatalIOErrorInFunction(coeffs_)
            << "correction " << corr << " in " << coeffs_.name()
            << ": allowed none (default) or Mei" << exit(FatalIOError);
    }
}


Foam::vector Foam::extraForces::SaffmanLift::force
(
    const particleState& s
) const
{
    const scalar magW = mag(s.vorticity);
    if (magW < VSMALL)
    {
        return Zero;
    }
    const vector slip(s.u - s.v);
    scalar C = 1;
    if (Mei_)
    {
        const scalar Rep = s.rhof*s.d*mag(slip)/s.muf;
        const scalar ReG = s.rhof*sqr(s.d)*magW/s.muf;
        if (Rep > 40)
        {
            C = 0.0524*sqrt(0.5*ReG);
        }
        else if (Rep > SMALL*ReG)
        {
            const scalar sb = sqrt(0.5*ReG/Rep);
            C = (1 - 0.3314*sb)*exp(-0.1*Rep) + 0.3314*sb;
        }
        // Rep -> 0: C -> 1 (and the force vanishes with the slip)
    }
    return
        1.615*sqr(s.d)*sqrt(s.rhof*s.muf/magW)*C*(slip ^ s.vorticity);
}
