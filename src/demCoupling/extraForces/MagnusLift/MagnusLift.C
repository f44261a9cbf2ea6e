/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "MagnusLift.H"
#include "addToRunTimeSelectionTable.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace extraForces
{
    defineTypeNameAndDebug(MagnusLift, 0);
    addToRunTimeSelectionTable(extraForce, MagnusLift, dictionary);
    addCoeffKeys(MagnusLift);
}
}


Foam::List<Foam::keySpec> Foam::extraForces::MagnusLift::coeffKeys()
{
    return List<keySpec>
    ({
        keySpec::choice("lift", wordList({"RubinowKeller", "OesterleBuiDinh"}))
    });
}


Foam::extraForces::MagnusLift::MagnusLift(const dictionary& dict)
:
    extraForce(typeName, dict),
    OesterleBuiDinh_(false)
{
    const word lift(coeffs_.getOrDefault<word>("lift", "RubinowKeller"));
    if (lift == "OesterleBuiDinh")
    {
        OesterleBuiDinh_ = true;
    }
    else if (lift != "RubinowKeller")
    {
        FatalIOErrorInFunction(coeffs_)
            << "lift " << lift << " in " << coeffs_.name()
            << ": allowed RubinowKeller (default) or OesterleBuiDinh"
            << exit(FatalIOError);
    }
}


Foam::vector Foam::extraForces::MagnusLift::force
(
    const particleState& s
) const
{
    const scalar c = 0.125*constant::mathematical::pi*s.rhof;
    const vector slip(s.u - s.v);
    const vector Omega(0.5*s.vorticity - s.omega);
    if (!OesterleBuiDinh_)
    {
        return c*pow3(s.d)*(Omega ^ slip);
    }
    const scalar magO = mag(Omega);
    if (magO < VSMALL)
    {
        return Zero;
    }
    const scalar magSlip = mag(slip);
    const scalar Rer = s.rhof*sqr(s.d)*magO/s.muf;
    const scalar Rep = s.rhof*s.d*magSlip/s.muf;
    const scalar e = exp(-0.05684*pow(Rer, 0.4)*pow(Rep, 0.3));
    const scalar CLslip = 0.45*magSlip + (s.d*magO - 0.45*magSlip)*e;
    return c*sqr(s.d)*CLslip*(Omega ^ slip)/magO;
}
