/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include <fstream>
#include "passiveParticleCloud.H"
#include "IOField.H"
#include "Map.H"
#include "PstreamBuffers.H"
#include "OSspecific.H"
#include "mathematicalConstants.H"

void Foam::demCoupling::report(const bool full) const
{
    // (before the first step both are 0)
    const scalar rel =
        balanceParticle_ > 0 ? balanceFluid_/balanceParticle_ : scalar(0);
    Info<< "demCoupling: particles "
        << returnReduce(label(dem_world_count(world_)), sumOp<label>())
        << ", DEM steps " << nSubCycles_
        << ", momentum balance: fluid " << balanceFluidVec_
        << " particles " << balanceParticleVec_
        << " relErr " << rel << endl;

    if (!full) return;

    Info<< "demCoupling: sum of particle drag " << sumDrag_
        << ", of pressure-gradient forces " << sumGradP_
        << ", of viscous forces " << sumTau_ << endl;

    // (mesh + the part still ramping in = particles)
    Info<< "demCoupling: solid volume: mesh " << solidVolumeMesh_
        << " particles " << solidVolumeParticles_
        << " relDiff "
        << mag(solidVolumeMesh_ + solidVolumeRamp_ - solidVolumeParticles_)
          /max(solidVolumeParticles_, VSMALL);
    if (rampTime_ > 0)
    {
        Info<< " (ramping in " << solidVolumeRamp_ << ", "
            << label(state_.rampStart.size()) << " particles)";
    }
    Info<< nl;
    bed_.report();
    if (state_.bedEta.n)
    {
        Info<< "demCoupling: bed-average eta " << state_.bedEta.mean << " % ("
            << state_.bedEta.n << " of " << state_.bedEta.all << " particles: those "
            << "whose fluid force is at least " << 100*etaMinForceRatio
            << " % of their weight)" << endl;
    }
    else
    {
        Info<< "demCoupling: bed-average eta: none (no particle's fluid "
            << "force is " << 100*etaMinForceRatio << " % of its weight)"
            << endl;
    }

    if
    (
        formulation_->assumesNoFluidAcceleration()
     && state_.bedEta.n
     && state_.bedEta.mean > etaWarning_
    )
    {
        WarningInFunction
            << "set III with bed-average eta " << state_.bedEta.mean
            << " % above etaWarning " << etaWarning_ << " %: set III assumes "
            << "negligible fluid acceleration ([Z] 2.10); use setI or setII"
            << endl;
    }

    const labelList& outletPatches = cloud_.outletPatches();
    forAll(outletPatches, k)
    {
        scalar mass = 0;
        const label cnt = cloud_.outletTotal(k, mass);
        Info<< "demCoupling: outlet "
            << mesh_.boundaryMesh()[outletPatches[k]].name() << ": "
            << cnt << " particles, " << mass << " kg" << endl;
    }
    // summed over the processors (the patches before the processor
    // patches are the same on all; exits through processor patches are
    // booked as unknown)
    labelList lost
    (
        SubList<label>(state_.lostPerPatch, mesh_.boundaryMesh().nNonProcessor())
    );
    Pstream::listCombineGather(lost, plusEqOp<label>());
    forAll(lost, patchi)
    {
        if (lost[patchi])
        {
            Info<< "demCoupling: lost through "
                << mesh_.boundaryMesh()[patchi].name() << ": "
                << lost[patchi] << endl;
        }
    }
    // list builds and wall contacts of the last force evaluation (the
    // restart tests check that their window has both)
    dem_stats st;
    world_.check(dem_world_stats(world_, &st), "dem_world_stats");
    Info<< "demCoupling: DEM neighbour-list builds "
        << returnReduce(label(st.list_builds), maxOp<label>())
        << (Pstream::parRun() ? " (most on one processor)" : "")
        << ", wall contacts "
        << returnReduce(label(st.wall_contacts), sumOp<label>()) << endl;
    Info<< "demCoupling: lost particles in total " << cloud_.lostTotal()
        << " (global searches "
        << returnReduce(locator_.nGlobal(), sumOp<label>()) << ")" << endl;
}


void Foam::demCoupling::write() const
{
    report(true);

    const dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);
    const word cloudName("demCloud");

    passiveParticleCloud cloud(mesh_, cloudName, IDLList<passiveParticle>());
    for (label i = 0; i < n; ++i)
    {
        cloud.addParticle
        (
            new passiveParticle(mesh_, box_.wrapped(a.x, i), cloud_.host()[i])
        );
    }

    // per-particle results of the last coupling step, by id
    Map<label> outIndex(2*state_.outIds.size() + 1);
    forAll(state_.outIds, j)
    {
        outIndex.insert(label(state_.outIds[j]), j);
    }

    IOField<scalar> d(cloud.fieldIOobject("d", IOobject::NO_READ), n);
    IOField<scalar> rho(cloud.fieldIOobject("rho", IOobject::NO_READ), n);
    IOField<vector> U(cloud.fieldIOobject("U", IOobject::NO_READ), n);
    IOField<vector> omega(cloud.fieldIOobject("omega", IOobject::NO_READ), n);
    IOField<vector> Fdrag(cloud.fieldIOobject("Fdrag", IOobject::NO_READ), n);
    IOField<vector> FgradP(cloud.fieldIOobject("FgradP", IOobject::NO_READ), n);
    IOField<scalar> eta(cloud.fieldIOobject("eta", IOobject::NO_READ), n);
    IOField<label> coordination
    (
        cloud.fieldIOobject("coordination", IOobject::NO_READ), n
    );
    IOField<label> id(cloud.fieldIOobject("id", IOobject::NO_READ), n);

    // Results of the last coupling step, by id.  In a decomposed run a
    // particle that changed processor after that step (section 5 of
    // evolve: locate, then migrate) has them on the processor it left:
    // they are fetched from there (collective).  A serial run has all.
    // A particle without results on any processor would be a defect: it
    // keeps zeros and coordination -1, and the log says so.
    Fdrag = Zero;
    FgradP = Zero;
    eta = 0;
    coordination = -1;
    List<vectorField> Fextra(extraForces_.size(), vectorField(n, Zero));
    DynamicList<label> missing;
    for (label i = 0; i < n; ++i)
    {
        d[i] = 2*a.radius[i];
        rho[i] = a.density[i];
        U[i] = vector(a.v[3*i], a.v[3*i+1], a.v[3*i+2]);
        omega[i] = vector(a.omega[3*i], a.omega[3*i+1], a.omega[3*i+2]);
        id[i] = label(a.id[i]);
        const auto iter = outIndex.cfind(id[i]);
        if (!iter.found())
        {
            missing.append(i);
            continue;
        }
        Fdrag[i] = state_.fDrag[*iter];
        FgradP[i] = state_.fGradP[*iter];
        eta[i] = state_.etaP[*iter];
        coordination[i] = state_.coordP[*iter];
        forAll(Fextra, k)
        {
            Fextra[k][i] = state_.fExtra[k][*iter];
        }
    }

    label nMissing = missing.size();
    if (Pstream::parRun() && returnReduce(nMissing, sumOp<label>()))
    {
        nMissing = resultsOf
        (
            outIndex, missing, id, Fdrag, FgradP, eta, coordination, Fextra
        );
    }
    if (nMissing)
    {
        Pout<< "demCoupling: " << nMissing << " particles have no results of "
            << "the last coupling step on any processor: written with Fdrag, "
            << "FgradP, eta 0 and coordination -1" << endl;
    }

    cloud.write();
    if (n)
    {
        d.write(); rho.write(); U.write(); omega.write(); Fdrag.write();
        FgradP.write(); eta.write(); coordination.write(); id.write();
    }

    // extra forces f'' (extraForces): F<type>, time average over the step
    forAll(extraForces_, k)
    {
        IOField<vector> f
        (
            cloud.fieldIOobject("F" + extraForces_[k].type(), IOobject::NO_READ),
            Fextra[k]
        );
        if (n) f.write();
    }

    // DEM state for restarts
    const fileName dir(mesh_.time().timePath()/"uniform");
    mkDir(dir);
    const fileName state(decomposition_.stateFile(dir));
    world_.check(dem_world_save(world_, state.c_str()), "dem_world_save");
    writeCouplingState(dir/"demCouplingState.bin");
}


// Results of the last coupling step of the particles slots (indices into
// id and the output fields) from the processors that held them then
// (outIndex: this processor's index of state_.outIds by id); returns how many
// no processor had.  Collective: every processor calls it with its own
// request (possibly empty).
Foam::label Foam::demCoupling::resultsOf
(
    const Map<label>& outIndex,
    const labelUList& slots,
    const labelUList& id,
    vectorField& Fdrag,
    vectorField& FgradP,
    scalarField& eta,
    labelList& coordination,
    List<vectorField>& Fextra
) const
{
    labelList ids(slots.size());
    forAll(slots, m)
    {
        ids[m] = id[slots[m]];
    }
    const label nProcs = Pstream::nProcs();
    const label me = Pstream::myProcNo();
    List<labelList> wanted(nProcs);
    wanted[me] = ids;
    Pstream::gatherList(wanted);
    Pstream::scatterList(wanted);

    const label nExtra = extraForces_.size();

    PstreamBuffers pBufs(Pstream::commsTypes::nonBlocking);
    for (label proci = 0; proci < nProcs; ++proci)
    {
        if (proci == me) continue;
        DynamicList<label> aIds, aCo;
        DynamicList<vector> aFd, aFgp;
        DynamicList<scalar> aEt;
        List<DynamicList<vector>> aFx(nExtra);
        for (const label pid : wanted[proci])
        {
            const auto iter = outIndex.cfind(pid);
            if (!iter.found()) continue;
            const label j = *iter;
            aIds.append(pid);
            aFd.append(state_.fDrag[j]);
            aFgp.append(state_.fGradP[j]);
            aEt.append(state_.etaP[j]);
            aCo.append(state_.coordP[j]);
            forAll(aFx, k)
            {
                aFx[k].append(state_.fExtra[k][j]);
            }
        }
        UOPstream os(proci, pBufs);
        os << aIds << aFd << aFgp << aEt << aCo;
        forAll(aFx, k)
        {
            os << aFx[k];
        }
    }
    pBufs.finishedSends();

    Map<label> pos(2*ids.size() + 1);
    forAll(ids, m)
    {
        pos.insert(ids[m], m);
    }
    label nFound = 0;
    for (label proci = 0; proci < nProcs; ++proci)
    {
        if (proci == me) continue;
        UIPstream is(proci, pBufs);
        labelList aIds, aCo;
        List<vector> aFd, aFgp;
        scalarList aEt;
        is >> aIds >> aFd >> aFgp >> aEt >> aCo;
        List<List<vector>> aFx(nExtra);
        forAll(aFx, k)
        {
            is >> aFx[k];
        }
        forAll(aIds, r)
        {
            const auto iter = pos.cfind(aIds[r]);
            if (!iter.found()) continue;
            const label m = *iter;
            const label i = slots[m];
            Fdrag[i] = aFd[r];
            FgradP[i] = aFgp[r];
            eta[i] = aEt[r];
            coordination[i] = aCo[r];
            forAll(Fextra, k)
            {
                Fextra[k][i] = aFx[k][r];
            }
            ++nFound;
        }
    }
    return ids.size() - nFound;
}

bool Foam::demCoupling::restoreState(const fileName& dir, const bool initial)
{
    bool serialState = false;
    if (!decomposition_.restore(dir, initial, serialState))
    {
        return false;
    }
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


// The coupling's own history for an exact restart: the fluid velocity of
// the last step (du/dt of the extra forces), the periodic driving
// gradient G and the insertion ramps.  Binary, native: "DEMCPL2\0",
// nCells, time index of Uprev, G, Uprev, then (since insertionRampTime;
// absent in older files: no ramps) the number of ramps and per ramp the
// particle id and its start time.
void Foam::demCoupling::writeCouplingState(const fileName& file) const
{
    std::ofstream os(file.c_str(), std::ios::binary);
    const char magic[8] = {'D', 'E', 'M', 'C', 'P', 'L', '2', '\0'};
    const int64_t n = state_.Uprev.size();
    os.write(magic, sizeof magic);
    os.write(reinterpret_cast<const char*>(&n), sizeof n);
    const int64_t index = state_.indexUprev;
    os.write(reinterpret_cast<const char*>(&index), sizeof index);
    os.write(reinterpret_cast<const char*>(state_.G.cdata()), 3*sizeof(scalar));
    if (n)
    {
        os.write(reinterpret_cast<const char*>(state_.Uprev.cdata()), 3*n*sizeof(scalar));
    }
    const int64_t nRamp = state_.rampStart.size();
    os.write(reinterpret_cast<const char*>(&nRamp), sizeof nRamp);
    for (const auto& r : state_.rampStart)
    {
        os.write(reinterpret_cast<const char*>(&r.first), sizeof r.first);
        os.write(reinterpret_cast<const char*>(&r.second), sizeof r.second);
    }
    if (!os.good())
    {
        FatalErrorInFunction
            << "cannot write " << file << exit(FatalError);
    }
}


void Foam::demCoupling::readCouplingState
(
    const fileName& file,
    const bool serialState
)
{
    std::ifstream is(file.c_str(), std::ios::binary);
    char magic[8];
    int64_t n = -1;
    is.read(magic, sizeof magic);
    is.read(reinterpret_cast<char*>(&n), sizeof n);
    // a serial state restarted decomposed: the per-cell fluid velocity of
    // the last step does not fit this processor's cells; it is dropped (the
    // extra forces' du/dt restarts from the next step)
    const bool otherMesh = serialState && n != 0 && n != mesh_.nCells();
    if
    (
        !is.good() || std::string(magic, 7) != "DEMCPL2"
     || (n != 0 && n != mesh_.nCells() && !otherMesh)
    )
    {
        FatalErrorInFunction
            << file << " is not a demFoam coupling state for this mesh ("
            << mesh_.nCells() << " cells)" << exit(FatalError);
    }
    int64_t index = -2;
    is.read(reinterpret_cast<char*>(&index), sizeof index);
    state_.indexUprev = label(index);
    is.read(reinterpret_cast<char*>(state_.G.data()), 3*sizeof(scalar));
    state_.Uprev.setSize(n);
    if (n)
    {
        is.read(reinterpret_cast<char*>(state_.Uprev.data()), 3*n*sizeof(scalar));
    }
    state_.rampStart.clear();
    if (is.good() && is.peek() == std::ifstream::traits_type::eof())
    {
        is.clear();     // a file from before the ramps: none
    }
    else if (is.good())
    {
        int64_t nRamp = -1;
        is.read(reinterpret_cast<char*>(&nRamp), sizeof nRamp);
        for (int64_t k = 0; k < nRamp && is.good(); ++k)
        {
            int64_t id;
            scalar t0;
            is.read(reinterpret_cast<char*>(&id), sizeof id);
            is.read(reinterpret_cast<char*>(&t0), sizeof t0);
            state_.rampStart[id] = t0;
        }
    }
    if (otherMesh)
    {
        state_.Uprev.clear();
        state_.indexUprev = -2;
        Info<< "demCoupling: " << file << " is of the serial mesh: the fluid "
            << "velocity of the last step is not carried over" << endl;
    }
    if (!is.good())
    {
        FatalErrorInFunction
            << file << " is truncated" << exit(FatalError);
    }
}
