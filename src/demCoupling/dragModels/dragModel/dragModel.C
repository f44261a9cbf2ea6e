/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "dragModel.H"

namespace Foam
{
    defineTypeNameAndDebug(dragModel, 0);
    defineRunTimeSelectionTable(dragModel, dictionary);
}


Foam::dragModel::dragModel(const word& type, const dictionary& dict)
:
    coeffs_(dict.subOrEmptyDict(type + "Coeffs"))
{}


Foam::autoPtr<Foam::dragModel> Foam::dragModel::New(const dictionary& dict)
{
    const word modelType(dict.get<word>("dragModel"));

    Info<< "Selecting drag model " << modelType << endl;

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(modelType);

    if (!cstrIter.found())
    {
        FatalIOErrorInFunction(dict)
            << "Unknown dragModel " << modelType
            << " (keyword dragModel in " << dict.name() << ")" << nl << nl
            << "Valid dragModel names:" << nl
            << dictionaryConstructorTablePtr_->sortedToc()
            << exit(FatalIOError);
    }

    return autoPtr<dragModel>(cstrIter()(dict));
}
