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
      - progress(): one log line at progressInterval (wall seconds) or every
        progressSteps fluid steps.

\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "OStringStream.H"
#include <cmath>
#include <cstdlib>

namespace
{
    std::string hms(const Foam::scalar s)
    {
        const long t = long(s + 0.5);
        char buf[32];
        std::snprintf
        (
            buf, sizeof buf, "%ld:%02ld:%02ld", t/3600, (t/60) % 60, t % 60
        );
        return buf;
    }
}


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
    snapVec_.setSize(3);
    snapVec_[0] = F_.primitiveField();
    snapVec_[1] = source_.primitiveField();
    snapVec_[2] = Ucoup_.primitiveField();
    snapScalar_.setSize(2);
    snapScalar_[0] = Kc_.primitiveField();
    snapScalar_[1] = eta_.primitiveField();
    tCoupling_ += std::chrono::duration<scalar>
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
    const int64_t piece = 1000;
    for (int64_t done = 0; done < nSettle; )
    {
        const int64_t m = std::min(piece, nSettle - done);
        world_.step(m, "dem_world_step (settling, before the fluid starts)");
        done += m;
        const scalar wall = std::chrono::duration<scalar>
        (
            std::chrono::steady_clock::now() - w0
        ).count();
        bool due = done < nSettle && wall - wallLast >= progressInterval_;
        Pstream::scatter(due);
        if (due)
        {
            wallLast = wall;
            Info<< "progress: settling (DEM only), t = "
                << dem_world_time(world_) << " s of "
                << mesh_.time().value() << " (" << label(100*done/nSettle)
                << " % of the settling), wall " << hms(wall).c_str()
                << ", to its end ~"
                << hms(wall*(nSettle - done)/done).c_str() << endl;
        }
    }
}


void Foam::demCoupling::progress(const bool force)
{
    const scalar wall = std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - wallStart_
    ).count();
    bool due =
        force
     || (progressSteps_ > 0 && nSteps_ % progressSteps_ == 0)
     || (progressSteps_ == 0 && wall - wallLastProgress_ >= progressInterval_);
    // decomposed: the master's clock decides (the line needs all processors)
    Pstream::scatter(due);
    if (!due) return;
    wallLastProgress_ = wall;

    const Time& runTime = mesh_.time();
    const scalar t = runTime.value();
    const scalar tEnd = runTime.endTime().value();
    const scalar done = t - startTime_;
    const scalar eta =
        done > 0 ? wall*max(tEnd - t, scalar(0))/done : scalar(0);

    dem_stats st;
    world_.check(dem_world_stats(world_, &st), "dem_world_stats");
    const label nAll =
        returnReduce(label(dem_world_count(world_)), sumOp<label>());
    // (decomposed: every processor created the initial particles, the
    // master alone inserts; its count is the total)
    label nInserted = label(st.inserted);
    Pstream::scatter(nInserted);
    const scalar maxOverlap =
        returnReduce(scalar(st.max_overlap_ratio), maxOp<scalar>());
    const label lost = cloud_.lostTotal();
    const labelList& outletPatches = cloud_.outletPatches();
    List<label> outCounts(outletPatches.size());
    forAll(outletPatches, k)
    {
        scalar mass = 0;
        outCounts[k] = cloud_.outletTotal(k, mass);
    }

    const scalar tComm = returnReduce(tComm_, maxOp<scalar>());
    const scalar total = max(tDem_ + tCoupling_ + tFluid_ + tComm_, VSMALL);
    // percent done, rounded down; 100 only at the last step (the time
    // summed from the steps may end a rounding error below endTime)
    const bool last = tEnd - t < 0.5*runTime.deltaTValue();
    const label percent =
        last ? 100
      : min(label(100*(t - startTime_)/max(tEnd - startTime_, VSMALL)), 99);
    OStringStream os;
    os  << "progress: t = " << t << " s of " << tEnd << " ("
        << percent << " %), wall " << hms(wall).c_str() << ", to the end ~"
        << hms(eta).c_str()
        << ", particles " << nAll
        << " (inserted " << nInserted << ", removed";
    forAll(outletPatches, k)
    {
        os  << " " << mesh_.boundaryMesh()[outletPatches[k]].name() << " "
            << outCounts[k];
    }
    if (outletPatches.empty()) os << " 0";
    os  << ", lost " << lost << ")"
        << ", max overlap " << 0.001*std::round(1e5*maxOverlap)
        << " % of d"
        << ", time DEM " << label(100*tDem_/total + 0.5)
        << " % coupling " << label(100*tCoupling_/total + 0.5)
        << " % fluid " << label(100*tFluid_/total + 0.5) << " %";
    if (Pstream::parRun())
    {
        os  << " communication " << label(100*tComm_/total + 0.5)
            << " % (most on one processor " << label(100*tComm/total + 0.5)
            << " %), particle volume across processors "
            << int64_t(returnReduce(map_.haloParticleSteps(), sumOp<scalar>()))
            << " particle-steps";
    }
    Info<< os.str().c_str() << endl;
}


// ************************************************************************* //
