/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "voidageModel.H"

namespace Foam
{
    defineTypeNameAndDebug(voidageModel, 0);
    defineRunTimeSelectionTable(voidageModel, dictionary);
}


Foam::voidageModel::voidageModel
(
    const word& type,
    const dictionary& dict,
    const fvMesh& mesh,
    const particleLocator& locator
)
:
    mesh_(mesh),
    locator_(locator),
    coeffs_(dict.subOrEmptyDict(type + "Coeffs"))
{}


Foam::autoPtr<Foam::voidageModel> Foam::voidageModel::New
(
    const dictionary& dict,
    const fvMesh& mesh,
    const particleLocator& locator
)
{
    const word modelType(dict.getOrDefault<word>("voidageModel", "divided"));

    Info<< "Selecting voidage model " << modelType << endl;

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(modelType);

    if (!cstrIter.found())
    {
        FatalIOErrorInFunction(dict)
            << "Unknown voidageModel " << modelType
            << " (keyword voidageModel in " << dict.name() << ")" << nl << nl
            << "Valid voidageModel names:" << nl
            << dictionaryConstructorTablePtr_->sortedToc()
            << exit(FatalIOError);
    }

    return autoPtr<voidageModel>(cstrIter()(dict, mesh, locator));
}
