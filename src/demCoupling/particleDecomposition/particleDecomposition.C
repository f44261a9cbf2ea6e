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
    ghosts are sent (processorGhosts.H).  This file: the restart state of a
    decomposed run, the first distribution and the migration.

    Walls: every processor adds the wall triangles of all processors (a
    particle near a processor boundary may touch a wall face of the
    neighbour).  Initial particles and settling: every processor creates and
    settles the whole set (same seed, same result), then keeps its own.

\*---------------------------------------------------------------------------*/

#include "particleDecomposition.H"
#include "processorPolyPatch.H"
#include "PstreamBuffers.H"
#include "OSspecific.H"
#include <chrono>
#include <vector>

using namespace Foam::demTools;

// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::particleDecomposition::particleDecomposition
(
    const fvMesh& mesh,
    demWorld& world,
    const particleLocator& locator,
    const demTools::periodicBox& box,
    scalar& commTime
)
:
    mesh_(mesh),
    world_(world),
    locator_(locator),
    box_(box),
    tComm_(commTime)
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
    serialState = haveSerial;
    return true;
}


Foam::labelList Foam::particleDecomposition::cellOwners() const
{
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


Foam::label Foam::particleDecomposition::patchBeyond
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


void Foam::particleDecomposition::migrate
(
    const DynamicList<label>& leaving,
    const DynamicList<label>& exitFace,
    boolList& taken,
    labelList& exitPatch,
    DynamicList<label>& hostById
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
        where[k] = box_.wrapped(a.x, leaving[k]);
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
                    idSlot(hostById, b.id[b.n_owned - 1]) = inCell[r][k];
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
