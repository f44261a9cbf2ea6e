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

    Which particles are sent where, and to whom: processorGhosts (each
    processor talks only to its DEM partners, the processors within contact
    reach of its box; a pair chooses its ghost sets again when either
    side's particles moved too far or its particles changed).  The
    migration, too, goes to the DEM partners only.  This file: the restart
    state of a decomposed run, the first distribution and the migration.

    Walls: every processor adds the wall triangles of all processors (a
    particle near a processor boundary may touch a wall face of the
    neighbour).  Initial particles: every processor draws the whole set
    (same seed, same result) but stores only the particles near its mesh
    (keepNear: the core's keep filter), checks them and keeps its own; the
    settling is then decomposed like the coupled DEM steps (ghosts, and
    moveToOwners after every fluid step's worth of DEM steps).

\*---------------------------------------------------------------------------*/

#include "particleDecomposition.H"
#include "processorPolyPatch.H"
#include "OSspecific.H"
#include <array>
#include <chrono>
#include <cstring>
#include <unordered_map>
#include <vector>

using namespace Foam::demTools;

// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::particleDecomposition::particleDecomposition
(
    const fvMesh& mesh,
    demWorld& world,
    const particleLocator& locator,
    const demTools::periodicBox& box,
    processorGhosts& ghosts,
    scalar& commTime
)
:
    mesh_(mesh),
    world_(world),
    locator_(locator),
    box_(box),
    ghosts_(ghosts),
    tComm_(commTime),
    near_(false),
    nTotal_(0)
{}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

Foam::fileName Foam::particleDecomposition::stateFile(const fileName& dir) const
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


bool Foam::particleDecomposition::restore
(
    const fileName& dir,
    const bool initial,
    bool& serialState
)
{
    serialState = false;
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
        << (haveSerial ? " (serial state: each processor keeps its own;"
            " demSplitState after decomposePar splits it once)" : "")
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
    serialState = haveSerial;
    return true;
}


bool Foam::particleDecomposition::inBox
(
    const boundBox& bb,
    const double x[3]
) const
{
    return bb.contains(box_.wrapped(x, 0)) || bb.contains(toVec(x, 0));
}


int Foam::particleDecomposition::keepNearFn(const double x[3], void* self)
{
    const particleDecomposition& d = *static_cast<particleDecomposition*>(self);
    return d.inBox(d.nearBox_, x);
}


void Foam::particleDecomposition::keepNear(const scalar reach)
{
    if (!Pstream::parRun()) return;
    // a pair that overlaps has one centre in some processor's cells and the
    // other within one largest diameter of it
    const scalar grow = reach*(1 + 1e-6);
    nearBox_ = boundBox(mesh_.points(), false);
    nearBox_.min() -= vector::uniform(grow);
    nearBox_.max() += vector::uniform(grow);
    nearBoxes_.setSize(Pstream::nProcs());
    nearBoxes_[Pstream::myProcNo()] = nearBox_;
    Pstream::gatherList(nearBoxes_);
    Pstream::scatterList(nearBoxes_);
    world_.check
    (
        dem_world_set_keep_filter(world_, &keepNearFn, this),
        "dem_world_set_keep_filter"
    );
    // the box itself for lattice fills (they then compute only the cells
    // near it); not with periodic axes, where a wrapped image may be kept
    if (!box_.periodic[0] && !box_.periodic[1] && !box_.periodic[2])
    {
        world_.check
        (
            dem_world_set_keep_box
            (
                world_, nearBox_.min().cdata(), nearBox_.max().cdata()
            ),
            "dem_world_set_keep_box"
        );
    }
    near_ = true;
}


void Foam::particleDecomposition::keepNearEnd()
{
    if (!near_) return;
    dem_stats st;
    world_.check(dem_world_stats(world_, &st), "dem_world_stats");
    nTotal_ = label(st.inserted);
    world_.check
    (
        dem_world_set_keep_filter(world_, nullptr, nullptr),
        "dem_world_set_keep_filter"
    );
    const label nHere = label(dem_world_count(world_));
    Info<< "demCoupling: initial set of " << nTotal_ << " particles, each "
        << "processor stores those near its mesh (fewest "
        << returnReduce(nHere, minOp<label>()) << ", most "
        << returnReduce(nHere, maxOp<label>()) << ")" << endl;
}


Foam::labelList Foam::particleDecomposition::nearOwners() const
{
    const dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);
    const label me = Pstream::myProcNo();
    labelList owner(n, -1);
    std::unordered_map<int64_t, label> index;
    List<std::vector<int64_t>> claims(Pstream::nProcs());
    for (label i = 0; i < n; ++i)
    {
        index[a.id[i]] = i;
        if (!locator_.inside(box_.wrapped(a.x, i))) continue;
        owner[i] = me;
        forAll(nearBoxes_, q)
        {
            if (q != me && inBox(nearBoxes_[q], a.x + 3*i))
            {
                claims[q].push_back(a.id[i]);
            }
        }
    }
    // once, at set-up: one message to every other processor (most empty)
    const int tag = 7321;
    const label req0 = UPstream::nRequests();
    forAll(claims, q)
    {
        if (q == me) continue;
        processorGhosts::sendBytes
        (
            q, tag, reinterpret_cast<const char*>(claims[q].data()),
            claims[q].size()*sizeof(int64_t)
        );
    }
    DynamicList<char> buf;
    forAll(claims, q)
    {
        if (q == me) continue;
        processorGhosts::receiveBytes(q, tag, buf);
        const label m = label(size_t(buf.size())/sizeof(int64_t));
        for (label k = 0; k < m; ++k)
        {
            int64_t id;
            std::memcpy(&id, buf.cdata() + k*sizeof(int64_t), sizeof id);
            const auto it = index.find(id);
            if (it == index.end()) continue;
            label& o = owner[it->second];
            if (o < 0 || q < o) o = q;
        }
    }
    UPstream::waitRequests(req0);
    return owner;
}


Foam::labelList Foam::particleDecomposition::cellOwners() const
{
    if (near_)
    {
        return nearOwners();
    }
    const dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);
    const label none = Pstream::nProcs();
    labelList owner(n, none);
    for (label i = 0; i < n; ++i)
    {
        // the run's own test (particleLocator::inside), so that a particle
        // accepted here is found by the first locate and vice versa
        if (locator_.inside(box_.wrapped(a.x, i)))
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


void Foam::particleDecomposition::distributeByCell()
{
    if (!Pstream::parRun()) return;

    const labelList owner(cellOwners());
    const label me = Pstream::myProcNo();
    // (nearOnly: the processor holds the particles near it, the whole set
    // has total(); a particle in no processor's cells stopped the run in
    // demCoupling::checkInitialState)
    const bool near = near_;
    const label nAll = near ? nTotal_ : owner.size();
    near_ = false;
    // the others' particles in one pass (one dem_world_remove_particle per
    // particle scanned the whole list each time: O(N^2) here)
    std::vector<unsigned char> keep(owner.size());
    forAll(owner, i)
    {
        keep[i] =
            owner[i] == me || (owner[i] < 0 && Pstream::master() && !near);
    }
    world_.check
    (
        dem_world_remove_unkept(world_, keep.data()),
        "dem_world_remove_unkept"
    );
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


Foam::label Foam::particleDecomposition::moveToOwners()
{
    const dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);
    DynamicList<label> leaving, exitFace;
    for (label i = 0; i < n; ++i)
    {
        int64_t& host = a.tag[hostTag][i];
        label f = -1;
        host = locator_.locateOrCross(box_.wrapped(a.x, i), label(host), f);
        if (host < 0)
        {
            leaving.append(i);
            exitFace.append(f);
        }
    }
    boolList taken, stays;
    labelList exitPatch;
    migrate(leaving, exitFace, taken, stays, exitPatch);
    // in one call (one pass over the neighbour list for all)
    std::vector<size_t> given;
    forAll(leaving, k)
    {
        if (taken[k]) given.push_back(size_t(leaving[k]));
    }
    world_.check
    (
        dem_world_remove_particles(world_, given.data(), nullptr, given.size()),
        "dem_world_remove_particles"
    );
    return label(given.size());
}


Foam::label Foam::particleDecomposition::offeredCell
(
    const label from,
    const label patchFace,
    const point& faceCentre,
    const point& p,
    label& beyond
) const
{
    beyond = -1;
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    label exitFace = -1;
    if (patchFace >= 0)
    {
        // the patches of a processor pair list their common faces in the
        // same order on both sides
        label seed = -1;
        for (const polyPatch& pp : pbm)
        {
            if
            (
                pp.size() && locator_.processorBehind(pp.start()) == from
             && patchFace < pp.size()
             && magSqr(pp.faceCentres()[patchFace] - faceCentre)
             <= 1e-12*mag(pp.faceAreas()[patchFace])
            )
            {
                seed = pp.faceCells()[patchFace];
                break;
            }
        }
        if (seed < 0)
        {
            FatalErrorInFunction
                << "processor " << from << " sent a particle through face "
                << patchFace << " of its patch to processor "
                << Pstream::myProcNo() << " at " << faceCentre
                << ", which is no face of this processor's patch to it;"
                << " please report this" << exit(FatalError);
        }
        const label c = locator_.locate(p, seed, exitFace, false);
        if (c >= 0)
        {
            return c;
        }
    }
    // not found from the face (a non-convex cell, or a point beyond a
    // boundary that the mesh holds elsewhere) or not crossed to here
    label f = -1;
    const label c = locator_.locate(p, -1, f);
    if (c < 0 && exitFace >= 0 && locator_.processorBehind(exitFace) < 0)
    {
        beyond = pbm.whichPatch(exitFace);
    }
    return c;
}


void Foam::particleDecomposition::migrate
(
    const DynamicList<label>& leaving,
    const DynamicList<label>& exitFace,
    boolList& taken,
    boolList& stays,
    labelList& exitPatch
)
{
    const auto t0 = std::chrono::steady_clock::now();
    taken.setSize(leaving.size());
    taken = false;
    stays.setSize(leaving.size());
    stays = false;
    exitPatch.setSize(leaving.size());
    exitPatch = -1;

    // the ghosts go first: a ghost may become owned here, and a leaving
    // particle is packed without its contacts with ghosts.  Only when a
    // particle leaves or arrives (below): without either, the ghosts and
    // the neighbour list stay, and the next DEM sub-steps need not renew
    // the ghost sets (processorGhosts::step)
    bool cleared = false;
    auto clearGhosts = [&]()
    {
        if (cleared) return;
        world_.check(dem_world_clear_ghosts(world_), "dem_world_clear_ghosts");
        cleared = true;
    };
    if (leaving.size())
    {
        clearGhosts();
    }

    // pack the leaving particles with their history
    const dem_arrays a = world_.arrays();
    std::vector<char> out;
    labelList sizes(leaving.size());
    List<point> where(leaving.size());
    // the centre of the processor face the walk left through (else a
    // point no face has)
    List<point> through(leaving.size(), point::max);
    // the processor behind that face and the face's index in the patch to
    // it (-1, -1 if none)
    List<std::array<int64_t, 2>> crossed(leaving.size(), {{-1, -1}});
    // all of them in one pass over the neighbour list (docs/demCore.md)
    std::vector<size_t> sz(leaving.size());
    {
        std::vector<size_t> idx(leaving.begin(), leaving.end());
        size_t bytes = 0;
        world_.check
        (
            dem_world_pack_particles
            (
                world_, idx.data(), idx.size(), nullptr, &bytes, sz.data()
            ),
            "dem_world_pack_particles"
        );
        out.resize(bytes);
        world_.check
        (
            dem_world_pack_particles
            (
                world_, idx.data(), idx.size(), out.data(), &bytes, nullptr
            ),
            "dem_world_pack_particles"
        );
    }
    forAll(leaving, k)
    {
        sizes[k] = label(sz[k]);
        where[k] = box_.wrapped(a.x, leaving[k]);
        const label behind =
            exitFace[k] >= 0 ? locator_.processorBehind(exitFace[k]) : -1;
        if (behind >= 0)
        {
            through[k] = mesh_.faceCentres()[exitFace[k]];
            const polyPatch& pp =
                mesh_.boundaryMesh()[mesh_.boundaryMesh().whichPatch(exitFace[k])];
            crossed[k] = {{behind, exitFace[k] - pp.start()}};
        }
    }
    // to every DEM partner only: a particle that left this processor's
    // cells lies within one largest radius of its box (processorGhosts
    // stops the run otherwise), so the cells that hold it are a partner's.
    // Three rounds of one message per partner: the offer; each partner's
    // answer (holds it, the patch beyond a processor face); the particles
    // each partner takes (the lowest processor that holds one)
    const labelList& partners = ghosts_.partners();
    const label np = partners.size();
    const label nOut = leaving.size();
    const int tagOffer = 7311, tagAnswer = 7312, tagTake = 7313;
    const auto& receive = processorGhosts::receiveBytes;
    auto send = [](const label r, const int tag, const std::vector<char>& b)
    {
        processorGhosts::sendBytes(r, tag, b.data(), b.size());
    };
    auto put = [](std::vector<char>& b, const void* p, const size_t sz)
    {
        const char* c = static_cast<const char*>(p);
        b.insert(b.end(), c, c + sz);
    };
    const label req0 = UPstream::nRequests();

    // the offer: count, sizes, where and through (6 doubles), the
    // processor behind the face crossed and its index in the patch to it
    // (2 int64), the packed particles
    std::vector<char> offer;
    {
        const int64_t cnt = nOut;
        put(offer, &cnt, sizeof cnt);
        forAll(leaving, k)
        {
            const int64_t sz = sizes[k];
            put(offer, &sz, sizeof sz);
        }
        forAll(leaving, k)
        {
            const double wt[6] =
            {
                where[k].x(), where[k].y(), where[k].z(),
                through[k].x(), through[k].y(), through[k].z()
            };
            put(offer, wt, sizeof wt);
        }
        forAll(leaving, k)
        {
            put(offer, crossed[k].data(), sizeof crossed[k]);
        }
        put(offer, out.data(), out.size());
    }
    for (const label r : partners) send(r, tagOffer, offer);

    // the partners' offers: which particles this processor's cells hold
    List<std::vector<char>> in(np);
    List<std::vector<int64_t>> inSizes(np);
    List<labelList> inCell(np);
    List<std::vector<char>> answer(np);
    DynamicList<char> buf;
    for (label k = 0; k < np; ++k)
    {
        const label r = partners[k];
        receive(r, tagOffer, buf);
        const char* c = buf.cdata();
        int64_t cnt = 0;
        std::memcpy(&cnt, c, sizeof cnt);
        c += sizeof cnt;
        inSizes[k].resize(size_t(cnt));
        std::memcpy(inSizes[k].data(), c, size_t(cnt)*sizeof(int64_t));
        c += size_t(cnt)*sizeof(int64_t);
        std::vector<double> wt(6*size_t(cnt));
        std::memcpy(wt.data(), c, wt.size()*sizeof(double));
        c += wt.size()*sizeof(double);
        std::vector<int64_t> cr(2*size_t(cnt));
        std::memcpy(cr.data(), c, cr.size()*sizeof(int64_t));
        c += cr.size()*sizeof(int64_t);
        in[k].assign(c, buf.cdata() + buf.size());
        inCell[k].setSize(label(cnt), -1);
        for (int64_t j = 0; j < cnt; ++j)
        {
            const point inWhere(wt[6*j], wt[6*j + 1], wt[6*j + 2]);
            const point inThrough(wt[6*j + 3], wt[6*j + 4], wt[6*j + 5]);
            const bool toMe = cr[2*j] == Pstream::myProcNo();
            label beyond = -1;
            inCell[k][j] = offeredCell
            (
                r, toMe ? label(cr[2*j + 1]) : -1, inThrough, inWhere, beyond
            );
            const int64_t ans[2] = {inCell[k][j] >= 0, beyond};
            put(answer[k], ans, sizeof ans);
        }
        send(r, tagAnswer, answer[k]);
    }

    // the answers: the lowest partner that holds a particle takes it; the
    // patch beyond a processor face from the partner behind it
    labelList owner(nOut, -1);
    for (label k = 0; k < np; ++k)
    {
        const label r = partners[k];
        receive(r, tagAnswer, buf);
        if (size_t(buf.size()) != 2*sizeof(int64_t)*size_t(nOut))
        {
            FatalErrorInFunction
                << "processor " << r << " answered the migration of "
                << nOut << " particles with " << label(buf.size())
                << " bytes; please report this" << exit(FatalError);
        }
        const int64_t* ans = reinterpret_cast<const int64_t*>(buf.cdata());
        for (label j = 0; j < nOut; ++j)
        {
            if (ans[2*j] && (owner[j] < 0 || r < owner[j])) owner[j] = r;
            exitPatch[j] = max(exitPatch[j], label(ans[2*j + 1]));
        }
    }
    List<std::vector<char>> take(np);
    forAll(leaving, j)
    {
        taken[j] = owner[j] >= 0;
        if (taken[j])
        {
            const int64_t idx = j;
            put(take[partners.find(owner[j])], &idx, sizeof idx);
        }
    }
    for (label k = 0; k < np; ++k) send(partners[k], tagTake, take[k]);

    // take the particles this processor was given (appended: the indices
    // in leaving stay valid)
    for (label k = 0; k < np; ++k)
    {
        receive(partners[k], tagTake, buf);
        const label nTake = label(size_t(buf.size())/sizeof(int64_t));
        const int64_t* idx = reinterpret_cast<const int64_t*>(buf.cdata());
        std::vector<size_t> off(inSizes[k].size() + 1, 0);
        for (size_t j = 0; j < inSizes[k].size(); ++j)
        {
            off[j + 1] = off[j] + size_t(inSizes[k][j]);
        }
        for (label t = 0; t < nTake; ++t)
        {
            clearGhosts();
            const size_t j = size_t(idx[t]);
            world_.check
            (
                dem_world_unpack_particle
                (
                    world_, in[k].data() + off[j], size_t(inSizes[k][j]), 0
                ),
                "dem_world_unpack_particle"
            );
            const dem_arrays b = world_.arrays();
            b.tag[hostTag][b.n_owned - 1] = inCell[k][label(j)];
        }
    }
    UPstream::waitRequests(req0);

    // those left through a processor face that no partner took: searched
    // for here (locateOrCross skipped it), e.g. around a corner of the cut
    {
        const dem_arrays b = world_.arrays();
        forAll(leaving, j)
        {
            if (taken[j] || crossed[j][0] < 0) continue;
            label f = -1;
            const label c = locator_.locate(where[j], -1, f);
            if (c >= 0)
            {
                stays[j] = true;
                b.tag[hostTag][leaving[j]] = c;
            }
        }
    }
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
}


// ************************************************************************* //
