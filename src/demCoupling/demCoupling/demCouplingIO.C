/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Output at write times and the restart of a run: the report and the
    particle cloud (couplingDiagnostics), the DEM state (one file per
    processor, particleDecomposition::stateFile) and the coupling's own
    history (uniform/demCouplingState.bin), and reading both back.

\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "OSspecific.H"
#include "couplingStateFile.H"

// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::demCoupling::report(const bool full) const
{
    diag_.report(full, nSubCycles_);
}


void Foam::demCoupling::write() const
{
    report(true);
    if (Pstream::parRun())
    {
        // this processor's ghost exchange so far (docs/parallel.md,
        // "Neighbour-only communication")
        Pout<< ghosts_.summary().c_str() << endl;
    }
    diag_.writeCloud();

    // DEM state for restarts
    const fileName dir(mesh_.time().timePath()/"uniform");
    mkDir(dir);
    const fileName state(decomposition_.stateFile(dir));
    world_.check(dem_world_save(world_, state.c_str()), "dem_world_save");
    writeCouplingState(dir/"demCouplingState.bin");
}


bool Foam::demCoupling::restoreState(const fileName& dir, const bool initial)
{
    // the world as set up from constant/demProperties, to compare with the
    // restored state (a continued run keeps the state's materials and walls)
    void* input = nullptr;
    size_t capacity = 0, size = 0;
    world_.check
    (
        dem_world_save_memory(world_, &input, &capacity, &size),
        "dem_world_save_memory"
    );
    bool serialState = false;
    if (!decomposition_.restore(dir, initial, serialState))
    {
        free(input);
        return false;
    }
    checkRestoredSetup(input, size, dir);
    free(input);
    const fileName cpl(dir/"demCouplingState.bin");
    if (!returnReduce(isFile(cpl), andOp<bool>()))
    {
        const fileName state
        (
            serialState ? dir/"demState.bin" : decomposition_.stateFile(dir)
        );
        FatalErrorInFunction
            << "the start time " << dir.path() << " has the DEM state "
            << state.name() << " but no " << cpl << " (the coupling's "
            << "history: fluid velocity at the particles, time averages), "
            << "without which the restart is not exact; start from a time "
            << "written completely by demFoam" << exit(FatalError);
    }
    readCouplingState(cpl, serialState);
    return true;
}



void Foam::demCoupling::checkRestoredSetup
(
    const void* input,
    const size_t size,
    const fileName& dir
) const
{
    dem_world* w = nullptr;
    world_.check(dem_world_create(&w), "dem_world_create");
    const dem_status st = dem_world_restore_memory(w, input, size);
    char what[512];
    const int differ =
        st == DEM_OK ? dem_world_setup_diff(w, world_, what, sizeof what) : 0;
    dem_world_destroy(&w);
    world_.check(st, "dem_world_restore_memory (the input's setup)");
    if (!differ)
    {
        return;
    }
    // material ids are the order of constant/demProperties materials
    OStringStream names;
    for (const word& n : materialIds_.sortedToc())
    {
        names << ' ' << materialIds_[n] << ' ' << n;
    }
    FatalErrorInFunction
        << dict_.instance()/dict_.name()
        << " does not match the DEM state written at "
        << dir.path().name() << ": " << what << " (materials:"
        << names.str().c_str() << ").  A continued run keeps the contact "
        << "law, materials, material pairs, walls, inlets and outlets it was "
        << "written with (only the dem timeStep, gravity and limits may "
        << "change); restore the entries or start a new run from the initial "
        << "time" << exit(FatalError);
}

// The coupling's own history for an exact restart (couplingStateFile.H)
void Foam::demCoupling::writeCouplingState(const fileName& file) const
{
    writeCouplingStateFile(file, state_);
}


void Foam::demCoupling::readCouplingState
(
    const fileName& file,
    const bool serialState
)
{
    readCouplingStateFile(file, state_);
    const label n = state_.Uprev.size();
    // a serial state restarted decomposed (not split by demSplitState): the
    // per-cell fluid velocity of the last step does not fit this
    // processor's cells; it is dropped (the extra forces' du/dt restarts
    // from the next step)
    const bool otherMesh = serialState && n != 0 && n != mesh_.nCells();
    if (n != 0 && n != mesh_.nCells() && !otherMesh)
    {
        FatalErrorInFunction
            << file << " is not a demFoam coupling state for this mesh ("
            << mesh_.nCells() << " cells; it has " << n << ")"
            << exit(FatalError);
    }
    if (otherMesh)
    {
        state_.Uprev.clear();
        state_.indexUprev = -2;
        Info<< "demCoupling: " << file << " is of the serial mesh: the fluid "
            << "velocity of the last step is not carried over (demSplitState "
            << "after decomposePar carries it over)" << endl;
    }
}
