/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "processorDirs.H"
#include "Pstream.H"
#include <regex>

void Foam::checkProcessorDirs(const Time& runTime)
{
    if (!Pstream::parRun()) return;

    const fileName root(runTime.rootPath()/runTime.globalCaseName());
    label nDirs = 0;
    bool collated = false;
    if (Pstream::master())
    {
        static const std::regex uncollated("processor[0-9]+");
        for (const fileName& d : readDir(root, fileName::DIRECTORY))
        {
            if (std::regex_match(d.c_str(), uncollated)) ++nDirs;
            else if (d.startsWith("processors")) collated = true;
        }
    }
    Pstream::scatter(nDirs);
    Pstream::scatter(collated);
    if (collated || nDirs == Pstream::nProcs()) return;

    FatalErrorInFunction
        << root << " has " << nDirs << " processor directories"
        << (nDirs ? " (processor0 to processor" + Foam::name(nDirs - 1) + ")"
                  : std::string()).c_str()
        << " and the run has " << Pstream::nProcs() << " processes; allowed: "
        << "one process per processor directory: mpirun -np " << nDirs
        << " demFoam -parallel, or decompose again for "
        << Pstream::nProcs() << " (numberOfSubdomains " << Pstream::nProcs()
        << " in system/decomposeParDict, then decomposePar -force)"
        << exit(FatalError);
}


// ************************************************************************* //
