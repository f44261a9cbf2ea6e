/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Decomposed runs (mpirun -np N demFoam -parallel; docs/parallel.md).

    Each processor's DEM world owns the particles whose centres lie in its
    cells at the start of a fluid step.  Inside a fluid step a particle stays
    with its owner (it moves a small fraction of its diameter); every DEM
    step the owned particles that can touch a particle of another processor
    are sent to it as ghost copies between the drift and the force
    evaluation (dem_world_step_drift / dem_world_step_forces), so that each
    processor computes the full contact force on its own particles: a pair
    across processors is evaluated on both sides, each applying the force to
    its own particle, with its own copy of the tangential history (the core
    keeps owned-ghost history by id).  At the end of the fluid step the
    particles that left the processor's cells migrate with their contact
    history to the processor whose cells hold them; particles no processor
    holds left the domain (outlet or lost, booked by the processor they left).

    Which particles are sent where: when a new ghost set is chosen, each
    processor's box of its owned particle centres (the master's also covers
    the inlets, where it inserts), the largest particle radius and the skin
    are gathered; particle i goes to processor r if its distance to r's box
    (periodic images included) is below r_i + r_max + skin.  A contact
    partner j of i on r lies in r's box and |x_i - x_j| < r_i + r_j; until
    the next neighbour-list build each particle moves less than skin/2, so
    no contact is missed.  A new set is chosen at the start of each fluid
    step and whenever any processor's Verlet criterion asks for a list
    rebuild (an insertion does); in between only x, v and omega of the same
    ghosts are sent (forwardGhosts, dem_world_set_ghost_states).

    Walls: every processor adds the wall triangles of all processors (a
    particle near a processor boundary may touch a wall face of the
    neighbour).  Initial particles and settling: every processor creates and
    settles the whole set (same seed, same result), then keeps its own.

\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "demCouplingTools.H"
#include "PstreamBuffers.H"
#include "OStringStream.H"
#include "OSspecific.H"
#include "Map.H"
#include <chrono>
#include <vector>

using namespace Foam::demTools;

// * * * * * * * * * * * * * * * * Helpers * * * * * * * * * * * * * * * * //

namespace
{
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


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

Foam::vector Foam::demCoupling::wrapped(const dem_arrays& a, const label i) const
{
    vector x(toVec(a.x, i));
    for (direction k = 0; k < 3; ++k)
    {
        if (!periodic_[k]) continue;
        const scalar L = boxHi_[k] - boxLo_[k];
        if (x[k] >= boxHi_[k]) x[k] -= L;
        else if (x[k] < boxLo_[k]) x[k] += L;
    }
    return x;
}


Foam::fileName Foam::demCoupling::stateFile(const fileName& dir) const
{
    if (!Pstream::parRun())
    {
        return dir/"demState.bin";
    }
    return
        dir/
        (
            "demState-processor" + Foam::name(Pstream::myProcNo())
          + "of" + Foam::name(Pstream::nProcs()) + ".bin"
        );
}


bool Foam::demCoupling::restoreState(const fileName& dir, const bool initial)
{
    const fileName own(stateFile(dir));
    const fileName serial(dir/"demState.bin");

    // every processor must take the same branch
    const bool haveOwn = returnReduce(isFile(own), andOp<bool>());
    const bool haveSerial =
        Pstream::parRun() && !haveOwn
     && returnReduce(isFile(serial), andOp<bool>());

    if (!haveOwn && !haveSerial)
    {
        // a time of a decomposed run, reconstructed and restarted serially
        // (reconstructPar copies processor0's uniform directory)
        const fileNameList other(readDir(dir, fileName::FILE));
        for (const fileName& f : other)
        {
            if (f.hasExt("bin") && f.startsWith("demState-processor"))
            {
                FatalErrorInFunction
                    << dir << " holds " << f << ", the DEM state of one "
                    << "processor of a decomposed run, and no "
                    << own.name() << ": restart that time decomposed with "
                    << "the same number of processors (decomposePar is not "
                    << "needed: mpirun -np N demFoam -parallel), or start "
                    << "the serial run from a time written serially"
                    << exit(FatalError);
            }
        }
        if (initial)
        {
            return false;
        }
        // a later time without the particles: re-inserting a fresh bed
        // under that time's fluid would run silently wrong
        FatalErrorInFunction
            << "the start time " << dir.path() << " has no DEM state "
            << "(missing " << own << "): a start from any time but the "
            << "case's initial one continues the particles written there, "
            << "and only the initial time inserts them.  Start from a "
            << "time written by demFoam (its uniform/ holds "
            << own.name() << " and demCouplingState.bin), or, to put new "
            << "particles into a flow computed without them, make that "
            << "time the case's first time directory" << exit(FatalError);
    }

    const fileName state(haveOwn ? own : serial);
    Info<< "demCoupling: restoring the DEM state from "
        << (haveOwn ? own : serial)
        << (haveSerial ? " (serial state: each processor keeps its own)" : "")
        << endl;
    world_.check(dem_world_restore(world_, state.c_str()), "dem_world_restore");
    world_.check(dem_world_clear_ghosts(world_), "dem_world_clear_ghosts");
    if (haveSerial)
    {
        // the serial state brings its inlets to every processor: the
        // master alone inserts
        if (!Pstream::master())
        {
            world_.check(dem_world_clear_inlets(world_), "dem_world_clear_inlets");
        }
        distributeByCell();
    }
    const fileName cpl(dir/"demCouplingState.bin");
    if (!returnReduce(isFile(cpl), andOp<bool>()))
    {
        FatalErrorInFunction
            << "the start time " << dir.path() << " has the DEM state "
            << state.name() << " but no " << cpl << " (the coupling's "
            << "history: fluid velocity at the particles, time averages), "
            << "without which the restart is not exact; start from a time "
            << "written completely by demFoam" << exit(FatalError);
    }
    readCouplingState(cpl, haveSerial);
    return true;
}


Foam::labelList Foam::demCoupling::cellOwners() const
{
    const dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);
    const label none = Pstream::nProcs();
    labelList owner(n, none);
    for (label i = 0; i < n; ++i)
    {
        // the run's own test (particleLocator::inside), so that a particle
        // accepted here is found by the first locate and vice versa
        if (locator_.inside(wrapped(a, i)))
        {
            owner[i] = Pstream::myProcNo();
        }
    }
    if (Pstream::parRun())
    {
        Pstream::listCombineGather(owner, minEqOp<label>());
        Pstream::listCombineScatter(owner);
    }
    for (label& o : owner)
    {
        if (o == none) o = -1;
    }
    return owner;
}


void Foam::demCoupling::distributeByCell()
{
    if (!Pstream::parRun()) return;

    const labelList owner(cellOwners());
    const label me = Pstream::myProcNo();
    const label nAll = owner.size();
    // from the highest index down: removal swaps with the last
    for (label i = nAll - 1; i >= 0; --i)
    {
        const bool mine = owner[i] == me || (owner[i] < 0 && Pstream::master());
        if (!mine)
        {
            world_.check
            (
                dem_world_remove_particle(world_, size_t(i), -1),
                "dem_world_remove_particle"
            );
        }
    }
    const label nMine = label(dem_world_count(world_));
    const label nSum = returnReduce(nMine, sumOp<label>());
    if (nSum != nAll)
    {
        FatalErrorInFunction
            << "distributing " << nAll << " particles over the processors "
            << "gave " << nSum << " (the processors do not hold the same "
            << "particles); please report this" << exit(FatalError);
    }
    Info<< "demCoupling: " << nAll << " particles distributed over "
        << Pstream::nProcs() << " processors (fewest "
        << returnReduce(nMine, minOp<label>()) << ", most "
        << returnReduce(nMine, maxOp<label>()) << ")" << endl;
}


void Foam::demCoupling::exchangeGhosts()
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


void Foam::demCoupling::forwardGhosts()
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


dem_status Foam::demCoupling::stepDecomposed(const label m)
{
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
        failure_ = "DEM core: " + why[first] + " (processor "
          + std::to_string(first) + ")";
        return st != DEM_OK ? st : DEM_ERR_STATE;
    };
    // ghosts before the first drift too: it may rebuild the neighbour list
    // (after a migration), which must see them to keep the contact history
    // of pairs across processors
    exchangeGhosts();
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
            exchangeGhosts();
            world_.check
            (
                dem_world_invalidate_list(world_), "dem_world_invalidate_list"
            );
        }
        else
        {
            forwardGhosts();
        }
        st = agree(world_.tryForces());
        if (st != DEM_OK) return st;
    }
    return DEM_OK;
}


Foam::label Foam::demCoupling::patchBeyond
(
    const label from,
    const point& faceCentre,
    const point& p
) const
{
    // the face of this processor's patch to processor `from` at that centre
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    label seed = -1;
    scalar best = GREAT, tol = 0;
    for (const polyPatch& pp : pbm)
    {
        if (!pp.size() || locator_.processorBehind(pp.start()) != from) continue;
        forAll(pp, i)
        {
            const scalar d = magSqr(pp.faceCentres()[i] - faceCentre);
            if (d < best)
            {
                best = d;
                seed = pp.faceCells()[i];
                // the same face: its centre within 1e-6 of its size
                tol = 1e-12*mag(pp.faceAreas()[i]);
            }
        }
    }
    if (seed < 0 || best > tol) return -1;
    // walk on from there (no global search: p is in no cell here)
    label exitFace = -1;
    if (locator_.locate(p, seed, exitFace, false) >= 0 || exitFace < 0)
    {
        return -1;
    }
    const label patchi = pbm.whichPatch(exitFace);
    return isA<processorPolyPatch>(pbm[patchi]) ? -1 : patchi;
}


void Foam::demCoupling::migrate
(
    const DynamicList<label>& leaving,
    const DynamicList<label>& exitFace,
    boolList& taken,
    labelList& exitPatch
)
{
    const auto t0 = std::chrono::steady_clock::now();
    const label nProcs = Pstream::nProcs();
    const label me = Pstream::myProcNo();
    taken.setSize(leaving.size());
    taken = false;
    exitPatch.setSize(leaving.size());
    exitPatch = -1;

    // the ghosts go first: a ghost may become owned here
    world_.check(dem_world_clear_ghosts(world_), "dem_world_clear_ghosts");

    // pack the leaving particles with their history
    const dem_arrays a = world_.arrays();
    std::vector<char> out;
    labelList sizes(leaving.size());
    List<point> where(leaving.size());
    // the centre of the processor face the walk left through (else a
    // point no face has)
    List<point> through(leaving.size(), point::max);
    forAll(leaving, k)
    {
        const size_t i = size_t(leaving[k]);
        size_t sz = 0;
        world_.check
        (
            dem_world_pack_particle(world_, i, nullptr, &sz),
            "dem_world_pack_particle"
        );
        out.resize(out.size() + sz);
        world_.check
        (
            dem_world_pack_particle(world_, i, out.data() + out.size() - sz, &sz),
            "dem_world_pack_particle"
        );
        sizes[k] = label(sz);
        where[k] = wrapped(a, leaving[k]);
        if (exitFace[k] >= 0 && locator_.processorBehind(exitFace[k]) >= 0)
        {
            through[k] = mesh_.faceCentres()[exitFace[k]];
        }
    }
    labelList counts(nProcs, 0);
    counts[me] = leaving.size();
    Pstream::gatherList(counts);
    Pstream::scatterList(counts);
    labelList offset(nProcs + 1, 0);
    forAll(counts, r) offset[r + 1] = offset[r] + counts[r];
    if (offset[nProcs] > 0)
    {
        // to every processor: the position tells who holds it
        PstreamBuffers pBufs(Pstream::commsTypes::nonBlocking);
        if (leaving.size())
        {
            for (label r = 0; r < nProcs; ++r)
            {
                if (r == me) continue;
                UOPstream os(r, pBufs);
                os << sizes << where << through;
                os.write(out.data(), std::streamsize(out.size()));
            }
        }
        pBufs.finishedSends();

        labelList owner(offset[nProcs], nProcs);
        labelList outPatch(offset[nProcs], -1);
        List<std::vector<char>> in(nProcs);
        List<labelList> inSizes(nProcs);
        List<labelList> inCell(nProcs);
        for (label r = 0; r < nProcs; ++r)
        {
            if (r == me || !counts[r]) continue;
            UIPstream is(r, pBufs);
            List<point> inWhere, inThrough;
            is >> inSizes[r] >> inWhere >> inThrough;
            in[r].resize(sum(inSizes[r]));
            is.read(in[r].data(), std::streamsize(in[r].size()));
            inCell[r].setSize(counts[r], -1);
            forAll(inWhere, k)
            {
                label exitFace = -1;
                inCell[r][k] = locator_.locate(inWhere[k], -1, exitFace);
                if (inCell[r][k] >= 0)
                {
                    owner[offset[r] + k] = me;
                }
                else if (inThrough[k] != point::max)
                {
                    outPatch[offset[r] + k] =
                        patchBeyond(r, inThrough[k], inWhere[k]);
                }
            }
        }
        Pstream::listCombineGather(owner, minEqOp<label>());
        Pstream::listCombineScatter(owner);
        Pstream::listCombineGather(outPatch, maxEqOp<label>());
        Pstream::listCombineScatter(outPatch);

        forAll(leaving, k)
        {
            taken[k] = owner[offset[me] + k] < nProcs;
            exitPatch[k] = outPatch[offset[me] + k];
        }

        // take the particles whose centre is in this processor's cells
        // (appended: the indices in leaving stay valid)
        for (label r = 0; r < nProcs; ++r)
        {
            if (r == me || !counts[r]) continue;
            label off = 0;
            forAll(inSizes[r], k)
            {
                if (owner[offset[r] + k] == me)
                {
                    world_.check
                    (
                        dem_world_unpack_particle
                        (
                            world_, in[r].data() + off, size_t(inSizes[r][k]), 0
                        ),
                        "dem_world_unpack_particle"
                    );
                    const dem_arrays b = world_.arrays();
                    idSlot(hostById_, b.id[b.n_owned - 1]) = inCell[r][k];
                }
                off += inSizes[r][k];
            }
        }
    }
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
}


// ************************************************************************* //
