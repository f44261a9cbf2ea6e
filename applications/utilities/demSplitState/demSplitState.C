/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Application
    demSplitState

Description
    Splits the particle state of a serially written time over the
    processors that decomposePar made of it, so that the decomposed run
    that continues from that time reads only its own particles
    (docs/parallel.md, "From serial to parallel").

    Without it every processor reads the whole serial
    <time>/uniform/demState.bin and keeps the particles in its cells: O(N)
    time and memory per processor.  demSplitState does that once, in one
    process, as demFoam would: a particle belongs to the lowest-numbered
    processor whose cells contain it (particleLocator::inside, the run's
    own test), one outside every processor's cells to processor 0; inlets
    stay with processor 0.  It writes per processor
        processorN/<time>/uniform/demState-processorNofP.bin
        processorN/<time>/uniform/demCouplingState.bin
    the latter with the processor's cells of the fluid velocity of the last
    step (cellProcAddressing), which the whole-state path drops, so the
    extra forces' du/dt continues exactly.  decomposePar's copy (or link)
    of the serial uniform/ becomes a directory of the processor's own,
    without the serial demState.bin; the completion marker is written last.

    Usage, in the serial case:
        decomposePar -time T
        demSplitState -time T
        mpirun -np P demFoam -parallel

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "polyMesh.H"
#include "labelIOList.H"
#include "OSspecific.H"
#include "demWorld.H"
#include "particleLocator.H"
#include "couplingStateFile.H"
#include "demCouplingTools.H"
#include "timeCompletion.H"
#include <vector>

using namespace Foam;

// The uniform/ of a processor's time as a directory of its own: decomposePar
// links it to (or copies) the serial one; the DEM and coupling states are
// written by the caller, the rest is copied from the serial directory
static void ownUniform(const fileName& dir, const fileName& serial)
{
    if (Foam::type(dir, false) == fileName::LINK)
    {
        Foam::rm(dir);
    }
    if (!isDir(dir) && !mkDir(dir))
    {
        FatalErrorInFunction
            << "cannot create " << dir << exit(FatalError);
    }
    for (const word& f : {word("demState.bin"), timeCompletion::markerName()})
    {
        Foam::rm(dir/f);
    }
    fileNameList entries(readDir(serial, fileName::FILE));
    entries.append(readDir(serial, fileName::DIRECTORY));
    for (const fileName& f : entries)
    {
        if
        (
            f == "demState.bin" || f == "demCouplingState.bin"
         || f == timeCompletion::markerName() || isFile(dir/f) || isDir(dir/f)
        )
        {
            continue;
        }
        if (!Foam::cp(serial/f, dir))
        {
            FatalErrorInFunction
                << "cannot copy " << serial/f << " to " << dir
                << exit(FatalError);
        }
    }
}


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Split the DEM state of a serial time over the processor"
        " directories decomposePar made of it: each processor of the"
        " continued run then reads its own particles only"
    );
    argList::noParallel();
    argList::addOption
    (
        "time",
        "T",
        "the time to split (default: the latest time whose uniform/ holds"
        " demState.bin)"
    );
    #include "setRootCase.H"
    #include "createTime.H"

    label nProcs = 0;
    while (isDir(args.path()/("processor" + Foam::name(nProcs))))
    {
        ++nProcs;
    }
    if (nProcs == 0)
    {
        FatalErrorInFunction
            << "no processor directories in " << args.path()
            << ": decomposePar -time T first" << exit(FatalError);
    }

    // the serial time
    const instantList times(runTime.times());
    const fileName local("uniform"/fileName("demState.bin"));
    label ti = -1;
    if (args.found("time"))
    {
        scalar tv = 0;
        if (!readScalar(args["time"], tv))
        {
            FatalErrorInFunction
                << "-time " << args["time"].c_str() << ": allowed a written"
                << " time" << exit(FatalError);
        }
        ti = Time::findClosestTimeIndex(times, tv);
        if
        (
            ti < 0 || times[ti].name() == runTime.constant()
         || mag(times[ti].value() - tv) > 1e-9*max(1, mag(tv))
        )
        {
            FatalErrorInFunction
                << "-time " << args["time"].c_str() << ": no such time"
                << " directory in " << runTime.path() << exit(FatalError);
        }
    }
    else
    {
        for (label i = times.size() - 1; i >= 0 && ti < 0; --i)
        {
            if (isFile(runTime.path()/times[i].name()/local)) ti = i;
        }
        if (ti < 0)
        {
            FatalErrorInFunction
                << "no time directory of " << runTime.path() << " holds "
                << local << " (a time written serially by demFoam)"
                << exit(FatalError);
        }
    }
    const word timeName(times[ti].name());
    const fileName serialUniform(runTime.path()/timeName/"uniform");
    for (const word f : {"demState.bin", "demCouplingState.bin"})
    {
        if (!isFile(serialUniform/f))
        {
            FatalErrorInFunction
                << serialUniform/f << " not found: -time " << timeName
                << " needs a time written serially by demFoam, complete"
                << exit(FatalError);
        }
    }
    if (!timeCompletion::isComplete(runTime.path()/timeName))
    {
        FatalErrorInFunction
            << runTime.path()/timeName << " is incomplete (no uniform/"
            << timeCompletion::markerName() << "): split a complete time"
            << exit(FatalError);
    }

    demWorld world;
    const fileName stateFile(serialUniform/"demState.bin");
    world.check(dem_world_restore(world, stateFile.c_str()), "dem_world_restore");
    world.check(dem_world_clear_ghosts(world), "dem_world_clear_ghosts");
    void* saved = nullptr;
    size_t capacity = 0, size = 0;
    world.check
    (
        dem_world_save_memory(world, &saved, &capacity, &size),
        "dem_world_save_memory"
    );
    dem_config cfg;
    world.check(dem_world_get_config(world, &cfg), "dem_world_get_config");
    demTools::periodicBox box;
    for (direction k = 0; k < 3; ++k)
    {
        box.periodic[k] = cfg.periodic[k];
        box.lo[k] = cfg.domain_lo[k];
        box.hi[k] = cfg.domain_hi[k];
    }

    couplingState serialCpl;
    readCouplingStateFile(serialUniform/"demCouplingState.bin", serialCpl);

    // owners: the lowest processor whose cells contain the particle
    const dem_arrays a = world.arrays();
    const label n = label(a.n_owned);
    labelList owner(n, -1);
    List<labelList> cellAddr(nProcs);
    for (label p = 0; p < nProcs; ++p)
    {
        const fileName procCase(args.caseName()/("processor" + Foam::name(p)));
        if (!isDir(args.rootPath()/procCase/timeName/"uniform"))
        {
            FatalErrorInFunction
                << args.rootPath()/procCase/timeName/"uniform" << " not found:"
                << " decomposePar -time " << timeName << " first"
                << exit(FatalError);
        }
        Time procTime(Time::controlDictName, args.rootPath(), procCase);
        procTime.setTime(times[ti], ti);
        const polyMesh mesh
        (
            IOobject
            (
                polyMesh::defaultRegion, procTime.timeName(), procTime,
                IOobject::MUST_READ
            )
        );
        cellAddr[p] = labelIOList
        (
            IOobject
            (
                "cellProcAddressing", mesh.facesInstance(),
                polyMesh::meshSubDir, mesh, IOobject::MUST_READ,
                IOobject::NO_WRITE, false
            )
        );
        const particleLocator locator(mesh);
        boundBox bb(mesh.points(), false);
        bb.inflate(1e-9);
        for (label i = 0; i < n; ++i)
        {
            if (owner[i] >= 0) continue;
            const point x(box.wrapped(a.x, i));
            if (bb.contains(x) && locator.inside(x)) owner[i] = p;
        }
    }
    label nOutside = 0;
    for (label& o : owner)
    {
        if (o < 0) { o = 0; ++nOutside; }
    }
    if (nOutside)
    {
        WarningInFunction
            << nOutside << " particles of " << stateFile << " lie in no"
            << " processor's cells; processor 0 keeps them, as demFoam"
            << " does" << endl;
    }

    labelList nHere(nProcs, 0);
    for (label p = 0; p < nProcs; ++p)
    {
        world.check
        (
            dem_world_restore_memory(world, saved, size),
            "dem_world_restore_memory"
        );
        // as demFoam's restart of the whole state: inlets on processor 0,
        // the others' particles removed (dem_world_remove_unkept)
        world.check(dem_world_clear_ghosts(world), "dem_world_clear_ghosts");
        if (p != 0)
        {
            world.check(dem_world_clear_inlets(world), "dem_world_clear_inlets");
        }
        std::vector<unsigned char> keep(n);
        forAll(owner, i)
        {
            keep[i] = owner[i] == p;
        }
        world.check
        (
            dem_world_remove_unkept(world, keep.data()),
            "dem_world_remove_unkept"
        );
        nHere[p] = label(dem_world_count(world));

        const fileName procTimeDir
        (
            args.path()/("processor" + Foam::name(p))/timeName
        );
        const fileName dir(procTimeDir/"uniform");
        ownUniform(dir, serialUniform);
        const fileName own
        (
            dir/
            (
                "demState-processor" + Foam::name(p) + "of"
              + Foam::name(nProcs) + ".bin"
            )
        );
        world.check(dem_world_save(world, own.c_str()), "dem_world_save");

        // the coupling state with this processor's cells of Uprev
        couplingState cpl;
        cpl.indexUprev = serialCpl.indexUprev;
        cpl.G = serialCpl.G;
        cpl.rampStart = serialCpl.rampStart;
        const labelList& addr = cellAddr[p];
        if (serialCpl.Uprev.size())
        {
            cpl.Uprev.setSize(addr.size());
            forAll(addr, celli)
            {
                if (addr[celli] < 0 || addr[celli] >= serialCpl.Uprev.size())
                {
                    FatalErrorInFunction
                        << "processor" << p << "'s cellProcAddressing does"
                        << " not fit the " << serialCpl.Uprev.size()
                        << " cells of " << serialUniform/"demCouplingState.bin"
                        << exit(FatalError);
                }
                cpl.Uprev[celli] = serialCpl.Uprev[addr[celli]];
            }
        }
        writeCouplingStateFile(dir/"demCouplingState.bin", cpl);
        // last: the time is complete again
        if (!Foam::cp(serialUniform/timeCompletion::markerName(), dir))
        {
            FatalErrorInFunction
                << "cannot copy " << serialUniform/timeCompletion::markerName()
                << " to " << dir << exit(FatalError);
        }
        Info<< "demSplitState: processor" << p << ": " << nHere[p]
            << " particles -> " << own << endl;
    }
    free(saved);

    Info<< nl << "demSplitState: " << n << " particles of time " << timeName
        << " split over " << nProcs << " processors (fewest " << min(nHere)
        << ", most " << max(nHere) << "); fluid velocity of the last step "
        << (serialCpl.Uprev.size() ? "carried over" : "none in the state")
        << nl << "\nEnd\n" << endl;
    return 0;
}
