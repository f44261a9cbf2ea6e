/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Locating the particles (steps 1 and 5 of demCoupling::evolve()),
    removing those outside the mesh, booked on their outlet patch or
    counted as lost, and the records of the removed particles
    (postProcessing/demOutlets).

\*---------------------------------------------------------------------------*/

#include "meshCloud.H"
#include "processorPolyPatch.H"
#include "OStringStream.H"
#include "OSspecific.H"
#include <fstream>
#include <vector>

using namespace Foam::demTools;

// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::meshCloud::meshCloud
(
    const fvMesh& mesh,
    demWorld& world,
    const particleLocator& locator,
    const demTools::periodicBox& box,
    particleDecomposition& decomposition,
    couplingState& state,
    const label maxLost
)
:
    mesh_(mesh),
    world_(world),
    locator_(locator),
    box_(box),
    decomposition_(decomposition),
    state_(state),
    maxLost_(maxLost)
{}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::meshCloud::addOutlets(const dictionary& dict)
{
    const polyBoundaryMesh& bm = mesh_.boundaryMesh();
    state_.lostPerPatch.setSize(bm.size(), 0);

    const wordList outlets
    (
        dict.getOrDefault<wordList>("outletPatches", wordList())
    );
    for (const word& name : outlets)
    {
        const label patchi = bm.findPatchID(name);
        if (patchi < 0)
        {
            FatalIOErrorInFunction(dict)
                << "outletPatches entry " << name << " in " << dict.name()
                << " is not a patch; patches: " << bm.names()
                << exit(FatalIOError);
        }
        int id;
        world_.check(dem_world_add_outlet(world_, &id), "dem_world_add_outlet");
        outletPatches_.append(patchi);
        outletIds_.append(id);
    }
}


Foam::label Foam::meshCloud::outletTotal(const label k, scalar& mass) const
{
    int64_t cnt = 0;
    double m = 0;
    world_.check
    (
        dem_world_outlet_totals(world_, outletIds_[k], &cnt, &m),
        "dem_world_outlet_totals"
    );
    mass = returnReduce(scalar(m), sumOp<scalar>());
    return returnReduce(label(cnt), sumOp<label>());
}


Foam::label Foam::meshCloud::lostTotal() const
{
    return returnReduce(state_.lostUnknown + sum(state_.lostPerPatch), sumOp<label>());
}


void Foam::meshCloud::locate(std::string& failure)
{
    dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);

    DynamicList<label> leaving;
    DynamicList<label> leavingFace;

    for (label i = 0; i < n; ++i)
    {
        int64_t& host = a.tag[hostTag][i];
        label exitFace = -1;
        const label c =
            locator_.locateOrCross(box_.wrapped(a.x, i), label(host), exitFace);
        host = c;
        if (c < 0)
        {
            leaving.append(i);
            leavingFace.append(exitFace);
        }
    }

    // decomposed: those in another processor's cells move there
    // (and the patch those that left through a processor face then left
    // the domain by on the other side)
    boolList taken(leaving.size(), false), stays(leaving.size(), false);
    labelList exitPatch(leaving.size(), -1);
    if (Pstream::parRun())
    {
        decomposition_.migrate(leaving, leavingFace, taken, stays, exitPatch);
        a = world_.arrays();
    }

    // removed in one call (one pass over the neighbour list for all of
    // them; as repeated removals from the highest index down)
    std::vector<size_t> gone;
    std::vector<int> goneOutlet;
    label nOut = 0, nLost = 0;
    for (label k = leaving.size() - 1; k >= 0; --k)
    {
        if (stays[k])
        {
            continue;
        }
        gone.push_back(size_t(leaving[k]));
        if (taken[k])
        {
            goneOutlet.push_back(-1);
            continue;
        }
        label patchi =
            exitPatch[k] >= 0 ? exitPatch[k]
          : leavingFace[k] >= 0 ? mesh_.boundaryMesh().whichPatch(leavingFace[k])
          : -1;
        if (patchi >= 0 && isA<processorPolyPatch>(mesh_.boundaryMesh()[patchi]))
        {
            // through a processor boundary into no processor's cells
            patchi = -1;
        }
        const label o = (patchi >= 0 ? outletPatches_.find(patchi) : -1);
        if (o >= 0)
        {
            ++nOut;
        }
        else
        {
            ++nLost;
            if (patchi >= 0) ++state_.lostPerPatch[patchi]; else ++state_.lostUnknown;
            const vector x(toVec(a.x, leaving[k]));
            OStringStream msg;
            msg << "particle " << label(a.id[leaving[k]]) << " at " << x
                << " left the mesh through "
                << (patchi >= 0 ? mesh_.boundaryMesh()[patchi].name() : word("an unknown patch"))
                << ", which is not an outlet; removed and counted as lost";
            if (Pstream::parRun())
            {
                // (Warning prints on the master only)
                Pout<< "--> FOAM Warning : " << msg.str().c_str() << endl;
            }
            else
            {
                WarningInFunction << msg.str().c_str() << endl;
            }
        }
        goneOutlet.push_back(o >= 0 ? outletIds_[o] : -1);
    }
    world_.check
    (
        dem_world_remove_particles
        (
            world_, gone.data(), goneOutlet.data(), gone.size()
        ),
        "dem_world_remove_particles"
    );
    reduce(nOut, sumOp<label>());
    reduce(nLost, sumOp<label>());
    if (nOut + nLost > 0)
    {
        Info<< "demCoupling: " << nOut << " particles left through outlets, "
            << nLost << " lost" << endl;
    }
    const label lost = nLost ? lostTotal() : 0;
    if (nLost && lost > maxLost_ && failure.empty())
    {
        OStringStream os;
        os  << lost << " particles lost in total (left the mesh through"
            << " patches that are not in outletPatches, see the warnings"
            << " above); constant/demProperties allows maxLostParticles "
            << maxLost_ << ". Make the patch an outlet (outletPatches), fix"
            << " the walls, lower the time steps, or raise maxLostParticles";
        failure = os.str();
    }
    if (nOut > 0)
    {
        writeRemovedRecords();
    }

    a = world_.arrays();
    host_.setSize(label(a.n_owned));
    forAll(host_, i)
    {
        host_[i] = label(a.tag[hostTag][i]);
    }
}


void Foam::meshCloud::writeRemovedRecords()
{
    const dem_removed_record* rec = nullptr;
    size_t nRec = 0;
    world_.check
    (
        dem_world_removed_records(world_, &rec, &nRec),
        "dem_world_removed_records"
    );
    OStringStream lines;
    lines.precision(10);
    for (size_t k = 0; k < nRec; ++k)
    {
        const label o = outletIds_.find(rec[k].outlet);
        const word patch =
            o >= 0
          ? mesh_.boundaryMesh()[outletPatches_[o]].name()
          : word("none");
        lines
            << mesh_.time().value() << ' ' << label(rec[k].id) << ' '
            << rec[k].diameter << ' ' << rec[k].density << ' '
            << patch << nl;
    }
    dem_world_clear_removed_records(world_);

    // decomposed: the master writes the records of all processors
    List<string> all(Pstream::nProcs());
    all[Pstream::myProcNo()] = lines.str();
    Pstream::gatherList(all);
    if (!Pstream::master()) return;

    const fileName dir
    (
        mesh_.time().globalPath()/"postProcessing"/"demOutlets"
       /mesh_.time().timeName(mesh_.time().startTime().value())
    );
    mkDir(dir);
    const fileName file(dir/"removed.dat");
    const bool fresh = !isFile(file);
    std::ofstream os(file.c_str(), std::ios::app);
    if (fresh)
    {
        os << "# time id d rho outletPatch\n";
    }
    for (const string& l : all)
    {
        os << l;
    }
}


// ************************************************************************* //
