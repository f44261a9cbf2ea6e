/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Application
    demDecompose

Description
    A decomposition that balances the particles as well as the cells
    (docs/parallel.md, "Load balance by particles").

    Counts the particles per cell, gives every cell the weight
        1 + particleWeight * (particles in the cell)
    (particleWeight: the cost of one particle relative to one fluid cell
    per fluid step, option -particleWeight) and calls the decomposition
    method of system/decomposeParDict (simple, hierarchical, scotch, ...)
    with these weights.  Writes the result as a manual decomposition:
        constant/cellDecomposition           labelList, processor per cell
        system/decomposeParDict.particles    the same dictionary with
                                             method manual
    so that
        decomposePar -decomposeParDict system/decomposeParDict.particles
    uses it.  Prints the particles per processor of the method without
    weights (what plain decomposePar does) and with them.  With method
    manual it only prints how that decomposition splits the particles.

    The particles are those the run will have: by default the initial
    particles of constant/demProperties (initialParticles entries of type
    list); with -time T those of the cloud demCloud written at time T (a
    serial or reconstructed time, e.g. after the settling, from which the
    decomposed run then starts).  Each particle is located with the
    library's particleLocator, as demFoam does.

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "polyMesh.H"
#include "IOdictionary.H"
#include "labelIOList.H"
#include "decompositionMethod.H"
#include "passiveParticleCloud.H"
#include "particleLocator.H"
#include "OSspecific.H"

using namespace Foam;

// Particles and cells per processor of a decomposition; prints one line
// and returns the imbalance max/mean - 1 of the particles
static scalar report
(
    const string& what,
    const labelList& decomp,
    const labelList& nInCell,
    const label nProcs
)
{
    labelList nParticles(nProcs, 0), nCells(nProcs, 0);
    forAll(decomp, celli)
    {
        nParticles[decomp[celli]] += nInCell[celli];
        ++nCells[decomp[celli]];
    }
    const label n = sum(nParticles);
    const scalar imbalance =
        n > 0 ? scalar(max(nParticles))*nProcs/n - 1 : 0;
    Info<< "demDecompose: " << what.c_str() << ": particles per processor "
        << nParticles << ", cells per processor " << nCells
        << ", particle imbalance (largest/mean - 1) "
        << 100*imbalance << " %" << endl;
    return imbalance;
}


// Whether dir holds a cloud: demFoam writes coordinates and positions,
// decomposePar and reconstructPar coordinates only
static bool hasCloud(const fileName& dir)
{
    return isFile(dir/"coordinates") || isFile(dir/"positions");
}


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Decomposition weighted by the particles: cell weight 1 + w *"
        " (particles in the cell), decomposed with the method of"
        " system/decomposeParDict, written as a manual decomposition"
        " (constant/cellDecomposition, system/decomposeParDict.particles)"
    );
    argList::noParallel();
    argList::addOption
    (
        "decomposeParDict",
        "file",
        "the dictionary whose method is weighted"
        " (default system/decomposeParDict); method manual: report the"
        " split of that decomposition only"
    );
    argList::addOption
    (
        "time",
        "T",
        "the particles of the cloud demCloud written at time T (serial or"
        " reconstructed; 'latest': the latest time with one) instead of the"
        " initialParticles of constant/demProperties"
    );
    argList::addOption
    (
        "particleWeight",
        "w",
        "cost of one particle per fluid step relative to one fluid cell"
        " (default 1, measured in zhouFluidisedBed and fluidisedBed;"
        " docs/parallel.md, \"Load balance by particles\")"
    );
    argList::addBoolOption
    (
        "noWrite",
        "print the particles per processor only, write nothing"
    );

    #include "setRootCase.H"
    #include "createTime.H"

    scalar w = 1;
    if (args.readIfPresent("particleWeight", w) && !(w >= 0 && w < GREAT))
    {
        FatalErrorInFunction
            << "-particleWeight " << args["particleWeight"].c_str()
            << ": allowed a number >= 0 (0: cells only)" << exit(FatalError);
    }

    // the time of the particles: the mesh is read there as well
    string source("initialParticles of constant/demProperties");
    const fileName cloudDir(cloud::prefix/"demCloud");
    if (args.found("time"))
    {
        const word t(args["time"]);
        const instantList times(runTime.times());
        label ti = -1;
        if (t == "latest")
        {
            for (label i = times.size() - 1; i >= 0 && ti < 0; --i)
            {
                if
                (
                    times[i].name() != runTime.constant()
                 && hasCloud(runTime.path()/times[i].name()/cloudDir)
                )
                {
                    ti = i;
                }
            }
            if (ti < 0)
            {
                FatalErrorInFunction
                    << "-time latest: no time directory of " << runTime.path()
                    << " holds " << cloudDir/"coordinates" << " or positions"
                    << " (decomposed times: reconstructPar first)"
                    << exit(FatalError);
            }
        }
        else
        {
            scalar tv = 0;
            if (!readScalar(t, tv))
            {
                FatalErrorInFunction
                    << "-time " << t << ": allowed a written time or latest"
                    << exit(FatalError);
            }
            ti = Time::findClosestTimeIndex(times, tv);
            if
            (
                ti < 0 || times[ti].name() == runTime.constant()
             || mag(times[ti].value() - tv) > 1e-9*max(1, mag(tv))
            )
            {
                wordList written;
                for (const instant& i : times)
                {
                    if (i.name() != runTime.constant())
                    {
                        written.append(i.name());
                    }
                }
                FatalErrorInFunction
                    << "-time " << t << ": no such time directory in "
                    << runTime.path() << "; written: " << written
                    << exit(FatalError);
            }
        }
        runTime.setTime(times[ti], ti);
        source = "cloud demCloud of time " + runTime.timeName();
    }

    #include "createPolyMesh.H"

    DynamicList<point> positions;
    if (args.found("time"))
    {
        const fileName dir(runTime.timePath()/cloudDir);
        if (!hasCloud(dir))
        {
            FatalErrorInFunction
                << dir/"coordinates" << " (or positions) not found: -time "
                << args["time"]
                << " needs a serial or reconstructed time written by demFoam"
                << " (decomposed: reconstructPar -time " << runTime.timeName()
                << " first)" << exit(FatalError);
        }
        passiveParticleCloud c(mesh, "demCloud");
        for (const passiveParticle& p : c)
        {
            positions.append(p.position());
        }
    }
    else
    {
        IOdictionary demProps
        (
            IOobject
            (
                "demProperties",
                runTime.constant(),
                mesh,
                IOobject::MUST_READ,
                IOobject::NO_WRITE
            )
        );
        if (!demProps.isDict("initialParticles"))
        {
            FatalIOErrorInFunction(demProps)
                << "no initialParticles in " << demProps.objectPath()
                << ": give the particles with -time T (a time written by"
                << " demFoam)" << exit(FatalIOError);
        }
        const dictionary& all = demProps.subDict("initialParticles");
        for (const entry& e : all)
        {
            if (!e.isDict()) continue;
            const dictionary& d = e.dict();
            const word type(d.get<word>("type"));
            if (type != "list")
            {
                // box and cylinder fills are drawn by the DEM core at
                // start-up: their positions exist only in a written time
                FatalIOErrorInFunction(d)
                    << "initialParticles/" << e.keyword() << "/type " << type
                    << " in " << demProps.objectPath() << ": demDecompose reads"
                    << " the positions of type list only; for box and"
                    << " cylinder fills run demFoam serially to a first"
                    << " write time and give it with -time T"
                    << exit(FatalIOError);
            }
            positions.append(d.get<List<point>>("positions"));
        }
    }
    if (positions.empty())
    {
        FatalErrorInFunction
            << "no particles in the " << source.c_str()
            << exit(FatalError);
    }

    // particles per cell: located as demFoam locates them (walks from the
    // previous particle's cell, global search as fall-back)
    const particleLocator locator(mesh);
    labelList nInCell(mesh.nCells(), 0);
    label seed = -1, nOutside = 0;
    for (const point& p : positions)
    {
        const label celli = locator.locate(p, seed);
        if (celli < 0)
        {
            ++nOutside;
            continue;
        }
        ++nInCell[celli];
        seed = celli;
    }
    Info<< "demDecompose: " << positions.size() << " particles from the "
        << source.c_str() << ", " << positions.size() - nOutside
        << " in " << mesh.nCells() << " cells, particle weight " << w
        << nl << endl;
    if (nOutside)
    {
        WarningInFunction
            << nOutside << " particles of the " << source.c_str()
            << " lie outside the mesh and are not weighed" << endl;
    }

    const fileName dictFile
    (
        args.getOrDefault<fileName>("decomposeParDict", "")
    );
    IOdictionary decompDict
    (
        IOobject::selectIO
        (
            IOobject
            (
                "decomposeParDict",
                runTime.system(),
                mesh,
                IOobject::MUST_READ,
                IOobject::NO_WRITE,
                false
            ),
            dictFile
        )
    );
    const word method(decompDict.get<word>("method"));
    autoPtr<decompositionMethod> decomposer =
        decompositionMethod::New(decompDict);
    const label nProcs = decomposer->nDomains();
    const pointField& cc = mesh.cellCentres();
    if (method == "manual")
    {
        // nothing to weigh: how an existing decomposition (e.g. an earlier
        // demDecompose's) splits these particles
        report
        (
            "manual (" + decompDict.name() + ")",
            decomposer->decompose(mesh, cc), nInCell, nProcs
        );
        Info<< "\nmethod manual: the split of " << decompDict.name()
            << " only, nothing written\nEnd\n" << endl;
        return 0;
    }

    // as plain decomposePar (no weights)
    report
    (
        string(method + ", cells only"), decomposer->decompose(mesh, cc),
        nInCell, nProcs
    );

    scalarField weights(mesh.nCells());
    forAll(weights, celli)
    {
        weights[celli] = 1 + w*nInCell[celli];
    }
    labelIOList decomp
    (
        IOobject
        (
            "cellDecomposition",
            mesh.facesInstance(),
            mesh,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            false
        ),
        decomposer->decompose(mesh, cc, weights)
    );
    report(string(method + ", particle-weighted"), decomp, nInCell, nProcs);

    if (args.found("noWrite"))
    {
        Info<< "\n-noWrite: nothing written\nEnd\n" << endl;
        return 0;
    }

    decomp.note() = "processor of each cell; demDecompose, " + source;
    decomp.write();

    // the dictionary for decomposePar: the same with method manual
    IOdictionary manualDict
    (
        IOobject
        (
            "decomposeParDict.particles",
            runTime.system(),
            mesh,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            false
        ),
        decompDict
    );
    manualDict.set("method", word("manual"));
    manualDict.remove("coeffs");
    manualDict.remove("manualCoeffs");
    dictionary coeffs;
    coeffs.add("dataFile", fileName("cellDecomposition"));
    manualDict.add("coeffs", coeffs);
    manualDict.note() =
        "written by demDecompose from "
      + fileName(decompDict.objectPath()).name()
      + ": decomposePar -decomposeParDict system/decomposeParDict.particles";
    manualDict.regIOobject::write();

    Info<< "\nWrote " << decomp.objectPath() << " and "
        << manualDict.objectPath() << nl
        << "Use: decomposePar -decomposeParDict "
        << "system/decomposeParDict.particles" << nl << "\nEnd\n" << endl;

    return 0;
}
