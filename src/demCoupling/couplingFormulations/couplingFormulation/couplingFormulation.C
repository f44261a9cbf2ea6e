/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "couplingFormulation.H"

namespace Foam
{
    defineTypeNameAndDebug(couplingFormulation, 0);
    defineRunTimeSelectionTable(couplingFormulation, dictionary);
}


Foam::autoPtr<Foam::couplingFormulation>
Foam::couplingFormulation::New(const dictionary& dict)
{
    const word modelType(dict.get<word>("formulation"));

    Info<< "Selecting coupling formulation " << modelType << endl;

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(modelType);

    if (!cstrIter.found())
    {
        FatalIOErrorInFunction(dict)
            << "Unknown formulation " << modelType
            << " (keyword formulation in " << dict.name() << ")" << nl << nl
            << "Valid formulation names:" << nl
            << dictionaryConstructorTablePtr_->sortedToc()
            << exit(FatalIOError);
    }

    return autoPtr<couplingFormulation>(cstrIter()(dict));
}
