/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Clean failure and progress of a run (docs/demProperties.md,
    "Clean failure and progress"):
      - checkpoint()/restoreCheckpoint(): the state at the start of a fluid
        step kept in memory, so that a step that fails (non-finite particle
        state, runaway overlap, lost particles, non-finite fluid) can be
        undone and the last good state written (demFoam writeLastGood.H);
      - nonFinite(): scan of the fluid state;
      - settle(): the DEM alone before the start time, with progress lines
        (decomposed: each processor its own particles, with ghosts and
        migration as in the coupled steps);
      - progress(): one log line at progressInterval (wall seconds) or every
        progressSteps fluid steps (couplingDiagnostics).

\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "OStringStream.H"
#include <cmath>
#include <cstdlib>

Foam::demCoupling::~demCoupling()
{
    std::free(snapBuf_);
}


void Foam::demCoupling::checkpoint()
{
    const auto t0 = std::chrono::steady_clock::now();
    world_.check
    (
        dem_world_save_memory(world_, &snapBuf_, &snapCapacity_, &snapSize_),
        "dem_world_save_memory"
    );
    saved_ = state_;
    snapVec_.setSize(4);
    snapVec_[0] = F_.primitiveField();
    snapVec_[1] = source_.primitiveField();
    snapVec_[2] = Ucoup_.primitiveField();
    snapVec_[3] = KUcoup_.primitiveField();
    snapScalar_.setSize(2);
    snapScalar_[0] = Kc_.primitiveField();
    snapScalar_[1] = eta_.primitiveField();
    diag_.time().coupling += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
}


void Foam::demCoupling::restoreCheckpoint()
{
    if (!snapBuf_)
    {
        return;
    }
    world_.check
    (
        dem_world_restore_memory(world_, snapBuf_, snapSize_),
        "dem_world_restore_memory"
    );
    state_ = saved_;
    F_.primitiveFieldRef() = snapVec_[0];
    source_.primitiveFieldRef() = snapVec_[1];
    Ucoup_.primitiveFieldRef() = snapVec_[2];
    KUcoup_.primitiveFieldRef() = snapVec_[3];
    Kc_.primitiveFieldRef() = snapScalar_[0];
    eta_.primitiveFieldRef() = snapScalar_[1];

    // the checkpointed particles were all located: nothing leaves here
    const std::string why(failure_);
    cloud_.locate(failure_);
    computeWeights();
    computeVoidage();
    failure_ = why;
}


std::string Foam::demCoupling::nonFinite
(
    const volVectorField& U,
    const volScalarField& p
)
{
    const fvMesh& mesh = U.mesh();
    OStringStream os;
    // decomposed: the first processor with a non-finite value tells all
    auto agree = [&](const std::string& mine)
    {
        if (!Pstream::parRun()) return mine;
        List<string> all(Pstream::nProcs());
        all[Pstream::myProcNo()] = mine;
        Pstream::gatherList(all);
        Pstream::scatterList(all);
        forAll(all, r)
        {
            if (!all[r].empty())
            {
                return all[r] + " (processor " + std::to_string(r) + ")";
            }
        }
        return std::string();
    };
    forAll(U, c)
    {
        const vector& u = U[c];
        if (!std::isfinite(u.x() + u.y() + u.z()))
        {
            os  << "non-finite fluid velocity " << U.name() << " = " << u
                << " in cell " << c << " at " << mesh.C()[c];
            return agree(os.str());
        }
        if (!std::isfinite(p[c]))
        {
            os  << "non-finite pressure " << p.name() << " = " << p[c]
                << " in cell " << c << " at " << mesh.C()[c];
            return agree(os.str());
        }
    }
    return agree("");
}


Foam::label Foam::demCoupling::injectedStep(const word& kind)
{
    const char* env = std::getenv("DEMFOAM_DEBUG_INJECT");
    if (!env) return -1;
    const std::string s(env);
    const std::string::size_type at = s.find('@');
    if (at == std::string::npos || s.substr(0, at) != kind) return -1;
    return label(std::atol(s.c_str() + at + 1));
}


void Foam::demCoupling::settle(const int64_t nSettle)
{
    // in pieces, with a progress line every progressInterval of wall time
    // (the fluid's clock: the settling ends at the start time)
    const auto w0 = std::chrono::steady_clock::now();
    scalar wallLast = 0;
    if (!Pstream::parRun())
    {
        const int64_t piece = 1000;
        for (int64_t done = 0; done < nSettle; )
        {
            const int64_t m = std::min(piece, nSettle - done);
            world_.step(m, "dem_world_step (settling, before the fluid starts)");
            done += m;
            diag_.settling(done, nSettle, w0, wallLast);
        }
        return;
    }

    // decomposed: each processor its own particles, as in the coupled
    // steps (ghosts from the DEM partners; a particle stays with its
    // processor for a fluid step's worth of DEM steps, then moves to the
    // processor whose cells hold it: docs/parallel.md)
    const int64_t piece = subSteps(mesh_.time().deltaTValue());
    label moved = 0;
    for (int64_t done = 0; done < nSettle; )
    {
        const int64_t m = std::min(piece, nSettle - done);
        ghosts_.step(label(m));
        std::string why;
        if (ghosts_.agree(why) != DEM_OK)
        {
            FatalErrorInFunction
                << "dem_world_step (settling, before the fluid starts) at DEM "
                << "time " << dem_world_time(world_) << " s: " << why.c_str()
                << exit(FatalError);
        }
        moved += decomposition_.moveToOwners();
        done += m;
        diag_.settling(done, nSettle, w0, wallLast);
    }
    Info<< "demCoupling: settled decomposed: "
        << returnReduce(moved, sumOp<label>())
        << " moves of particles between processors" << endl;
}


void Foam::demCoupling::progress(const bool force)
{
    diag_.progress(nSteps_, force);
}


// ************************************************************************* //
