/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "extraForce.H"

namespace Foam
{
    defineTypeNameAndDebug(extraForce, 0);
    defineRunTimeSelectionTable(extraForce, dictionary);
}


Foam::extraForce::extraForce(const word& type, const dictionary& dict)
:
    coeffs_(dict.subOrEmptyDict(type + "Coeffs"))
{}


void Foam::extraForce::badCoeff
(
    const word& keyword,
    const scalar value,
    const string& allowed
) const
{
    FatalIOErrorInFunction(coeffs_)
        << keyword << " " << value << " in " << coeffs_.name()
        << ": allowed " << allowed.c_str() << exit(FatalIOError);
}


Foam::autoPtr<Foam::extraForce> Foam::extraForce::New
(
    const word& type,
    const dictionary& dict
)
{
    auto cstrIter = dictionaryConstructorTablePtr_->cfind(type);

    if (!cstrIter.found())
    {
        FatalIOErrorInFunction(dict)
            << "Unknown force " << type << " in the list extraForces in "
            << dict.name() << nl << nl
            << "Valid extraForces entries:" << nl
            << dictionaryConstructorTablePtr_->sortedToc()
            << exit(FatalIOError);
    }

    return autoPtr<extraForce>(cstrIter()(dict));
}


Foam::PtrList<Foam::extraForce> Foam::extraForce::NewList
(
    const dictionary& dict
)
{
    const wordList names
    (
        dict.getOrDefault<wordList>("extraForces", wordList())
    );
    PtrList<extraForce> forces(names.size());
    forAll(names, i)
    {
        for (label j = 0; j < i; ++j)
        {
            if (names[j] == names[i])
            {
                FatalIOErrorInFunction(dict)
                    << "extraForces in " << dict.name() << " lists "
                    << names[i] << " twice; give each force once"
                    << exit(FatalIOError);
            }
        }
        forces.set(i, New(names[i], dict));
    }
    if (names.size())
    {
        Info<< "Selecting extra particle-fluid forces " << names << endl;
    }
    return forces;
}
