/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Ghost copies of particles across processor boundaries (docs/parallel.md):
    which owned particles go to which processor, their packing, and the
    DEM steps of a decomposed run with the ghosts refreshed between the
    drift and the force evaluation.

\*---------------------------------------------------------------------------*/

#include "processorGhosts.H"
#include "demCouplingTools.H"
#include "PstreamBuffers.H"
#include "Map.H"
#include <chrono>
#include <vector>

using namespace Foam::demTools;

// * * * * * * * * * * * * * * * * Helpers * * * * * * * * * * * * * * * * //

// MPI's profiling hook, a no-op unless a profiling library is loaded
// (bin/tools/mpiMessageCount counts the messages between the marks)
extern "C" int MPI_Pcontrol(const int level, ...) __attribute__((weak));

namespace
{
    // Marks the DEM sub-steps for a profiling library: MPI_Pcontrol(2, m)
    // on entry (m DEM steps follow), MPI_Pcontrol(1) on exit
    struct subStepMark
    {
        explicit subStepMark(const int m)
        {
            if (MPI_Pcontrol) MPI_Pcontrol(2, m);
        }
        ~subStepMark()
        {
            if (MPI_Pcontrol) MPI_Pcontrol(1);
        }
    };

    // Distance from x to the interval [lo, hi] of one axis; a periodic axis
    // (period L) takes the nearest image
    Foam::scalar axisGap
    (
        const Foam::scalar x,
        const Foam::scalar lo,
        const Foam::scalar hi,
        const bool periodic,
        const Foam::scalar L
    )
    {
        auto gap = [&](const Foam::scalar y)
        {
            return y < lo ? lo - y : (y > hi ? y - hi : Foam::scalar(0));
        };
        Foam::scalar g = gap(x);
        if (periodic)
        {
            g = Foam::min(g, Foam::min(gap(x - L), gap(x + L)));
        }
        return g;
    }
}


// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::processorGhosts::processorGhosts
(
    demWorld& world,
    const FixedList<bool, 3>& periodic,
    const vector& boxLo,
    const vector& boxHi,
    const List<boundBox>& inletBoxes,
    const scalar& inletRadius,
    scalar& commTime
)
:
    world_(world),
    periodic_(periodic),
    boxLo_(boxLo),
    boxHi_(boxHi),
    inletBoxes_(inletBoxes),
    inletRadius_(inletRadius),
    tComm_(commTime),
    ghostSize_(0),
    sendIds_(),
    sendIdx_(),
    sendReorder_(-1),
    recvFirst_(),
    recvCount_()
{}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::processorGhosts::exchange()
{
    const auto t0 = std::chrono::steady_clock::now();
    world_.check(dem_world_clear_ghosts(world_), "dem_world_clear_ghosts");

    const label nProcs = Pstream::nProcs();
    const label me = Pstream::myProcNo();
    dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);

    // box of the owned centres (+ the inlets on the master), largest
    // radius, skin
    typedef FixedList<scalar, 8> boxInfo;
    boxInfo mine;
    for (direction k = 0; k < 3; ++k)
    {
        mine[k] = GREAT;
        mine[3 + k] = -GREAT;
    }
    mine[6] = inletRadius_;
    mine[7] = dem_world_skin(world_);
    auto grow = [&](const point& x)
    {
        for (direction k = 0; k < 3; ++k)
        {
            mine[k] = min(mine[k], x[k]);
            mine[3 + k] = max(mine[3 + k], x[k]);
        }
    };
    for (label i = 0; i < n; ++i)
    {
        grow(toVec(a.x, i));
        mine[6] = max(mine[6], a.radius[i]);
    }
    for (const boundBox& bb : inletBoxes_)
    {
        grow(bb.min());
        grow(bb.max());
    }
    List<boxInfo> boxes(nProcs);
    boxes[me] = mine;
    Pstream::gatherList(boxes);
    Pstream::scatterList(boxes);
    scalar rMax = 0, skinMin = GREAT, skin = 0;
    for (const boxInfo& b : boxes)
    {
        rMax = max(rMax, b[6]);
        if (b[0] <= b[3])
        {
            skinMin = min(skinMin, b[7]);
            skin = max(skin, b[7]);
        }
    }
    if (skin > skinMin*(1 + 1e-12))
    {
        FatalErrorInFunction
            << "the DEM skin differs between processors (" << skinMin
            << " to " << skin << " m): the automatic skin follows the "
            << "largest particle of each processor; set dem/skin in "
            << "constant/demProperties (e.g. 0.2 of the largest diameter)"
            << exit(FatalError);
    }

    // pack the owned particles each processor needs (all packed ghosts
    // have one size: no contact history)
    if (!ghostSize_ && n)
    {
        world_.check
        (
            dem_world_pack_ghost(world_, 0, nullptr, &ghostSize_),
            "dem_world_pack_ghost"
        );
    }
    // within reach until the next list build: particles move less than
    // skin/2 each before it
    const size_t gs = ghostSize_;
    List<std::vector<char>> send(nProcs);
    sendIds_.setSize(nProcs);
    for (DynamicList<int64_t>& ids : sendIds_) ids.clear();
    for (label i = 0; i < n; ++i)
    {
        const scalar reach = a.radius[i] + rMax + skin;
        for (label r = 0; r < nProcs; ++r)
        {
            const boxInfo& b = boxes[r];
            if (r == me || b[0] > b[3]) continue;
            scalar d2 = 0;
            for (direction k = 0; k < 3 && d2 < sqr(reach); ++k)
            {
                d2 += sqr
                (
                    axisGap
                    (
                        a.x[3*i + k], b[k], b[3 + k], periodic_[k],
                        boxHi_[k] - boxLo_[k]
                    )
                );
            }
            if (d2 >= sqr(reach)) continue;
            sendIds_[r].append(a.id[i]);
            std::vector<char>& buf = send[r];
            buf.resize(buf.size() + gs);
            size_t sz = gs;
            world_.check
            (
                dem_world_pack_ghost(world_, size_t(i), buf.data() + buf.size() - gs, &sz),
                "dem_world_pack_ghost"
            );
        }
    }

    PstreamBuffers pBufs(Pstream::commsTypes::nonBlocking);
    forAll(send, r)
    {
        if (r == me || send[r].empty()) continue;
        UOPstream os(r, pBufs);
        os << label(gs) << label(send[r].size()/gs);
        os.write(send[r].data(), std::streamsize(send[r].size()));
    }
    labelList recvSizes;
    pBufs.finishedSends(recvSizes);
    std::vector<char> buf;
    recvFirst_.setSize(nProcs);
    recvCount_.setSize(nProcs);
    recvCount_ = 0;
    label nGhosts = 0;
    forAll(recvSizes, r)
    {
        recvFirst_[r] = nGhosts;
        if (r == me || !recvSizes[r]) continue;
        UIPstream is(r, pBufs);
        label rgs = 0, nGhost = 0;
        is >> rgs >> nGhost;
        recvCount_[r] = nGhost;
        nGhosts += nGhost;
        buf.resize(size_t(rgs)*nGhost);
        is.read(buf.data(), std::streamsize(buf.size()));
        for (size_t off = 0; off + rgs <= buf.size(); off += rgs)
        {
            world_.check
            (
                dem_world_unpack_particle(world_, buf.data() + off, rgs, 1),
                "dem_world_unpack_particle (ghost)"
            );
        }
    }
    sendReorder_ = -1;
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
}


void Foam::processorGhosts::forward()
{
    const auto t0 = std::chrono::steady_clock::now();
    const label nProcs = Pstream::nProcs();
    const dem_arrays a = world_.arrays();

    // storage indices of the ids sent (the core re-sorts at list builds)
    const int64_t reorders = dem_world_reorder_count(world_);
    if (reorders != sendReorder_)
    {
        Map<label> index(2*a.n_owned + 1);
        for (label i = 0; i < label(a.n_owned); ++i)
        {
            index.insert(label(a.id[i]), i);
        }
        sendIdx_.setSize(nProcs);
        forAll(sendIds_, r)
        {
            sendIdx_[r].setSize(sendIds_[r].size());
            forAll(sendIds_[r], k)
            {
                const auto it = index.cfind(label(sendIds_[r][k]));
                if (!it.found())
                {
                    FatalErrorInFunction
                        << "ghost particle " << label(sendIds_[r][k])
                        << " for processor " << r << " is no longer owned "
                        << "here between list builds; please report this"
                        << exit(FatalError);
                }
                sendIdx_[r][k] = *it;
            }
        }
        sendReorder_ = reorders;
    }

    PstreamBuffers pBufs(Pstream::commsTypes::nonBlocking);
    std::vector<double> out;
    forAll(sendIdx_, r)
    {
        if (sendIdx_[r].empty()) continue;
        out.resize(9*sendIdx_[r].size());
        forAll(sendIdx_[r], k)
        {
            const label i = sendIdx_[r][k];
            for (direction j = 0; j < 3; ++j)
            {
                out[9*k + j] = a.x[3*i + j];
                out[9*k + 3 + j] = a.v[3*i + j];
                out[9*k + 6 + j] = a.omega[3*i + j];
            }
        }
        UOPstream os(r, pBufs);
        os.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()*sizeof(double)));
    }
    pBufs.finishedSends();
    std::vector<double> in;
    forAll(recvCount_, r)
    {
        if (!recvCount_[r]) continue;
        UIPstream is(r, pBufs);
        in.resize(9*recvCount_[r]);
        is.read(reinterpret_cast<char*>(in.data()), std::streamsize(in.size()*sizeof(double)));
        world_.check
        (
            dem_world_set_ghost_states
            (
                world_, size_t(recvFirst_[r]), size_t(recvCount_[r]), in.data()
            ),
            "dem_world_set_ghost_states"
        );
    }
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
}


dem_status Foam::processorGhosts::step(const label m, std::string& failure)
{
    const subStepMark mark(static_cast<int>(m));

    // the first failure on any processor stops all of them at the same
    // point, each with that processor's message
    auto agree = [&](const dem_status st) -> dem_status
    {
        label first = st != DEM_OK ? Pstream::myProcNo() : Pstream::nProcs();
        reduce(first, minOp<label>());
        if (first == Pstream::nProcs()) return DEM_OK;
        List<string> why(Pstream::nProcs());
        if (st != DEM_OK)
        {
            why[Pstream::myProcNo()] =
                std::string(dem_status_string(st)) + ": " + world_.lastError();
        }
        Pstream::gatherList(why);
        Pstream::scatterList(why);
        failure = "DEM core: " + why[first] + " (processor "
          + std::to_string(first) + ")";
        return st != DEM_OK ? st : DEM_ERR_STATE;
    };
    // ghosts before the first drift too: it may rebuild the neighbour list
    // (after a migration), which must see them to keep the contact history
    // of pairs across processors
    exchange();
    for (label s = 0; s < m; ++s)
    {
        dem_status st = agree(world_.tryDrift());
        if (st != DEM_OK) return st;
        // a new ghost set when any processor rebuilds its neighbour list
        // (so do all), else the same ghosts with their new state
        bool stale = dem_world_list_stale(world_);
        reduce(stale, orOp<bool>());
        if (stale)
        {
            exchange();
            world_.check
            (
                dem_world_invalidate_list(world_), "dem_world_invalidate_list"
            );
        }
        else
        {
            forward();
        }
        st = agree(world_.tryForces());
        if (st != DEM_OK) return st;
    }
    // the contacts of the last step while the ghosts are there
    world_.captureContacts();
    return DEM_OK;
}


// ************************************************************************* //
