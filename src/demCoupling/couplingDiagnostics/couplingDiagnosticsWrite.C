/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    The particle cloud at write times (lagrangian/demCloud): positions, d,
    rho, U, omega, id and the results of the last coupling step (drag,
    pressure-gradient force, eta, coordination, the extra forces), fetched
    from the processor that computed them when a particle migrated since.

\*---------------------------------------------------------------------------*/

#include "couplingDiagnostics.H"
#include "passiveParticleCloud.H"
#include "IOField.H"
#include "PstreamBuffers.H"

// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::couplingDiagnostics::writeCloud() const
{
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

    contacts_.write();
}


// Results of the last coupling step of the particles slots (indices into
// id and the output fields) from the processors that held them then
// (outIndex: this processor's index of state_.outIds by id); returns how many
// no processor had.  Collective: every processor calls it with its own
// request (possibly empty).
Foam::label Foam::couplingDiagnostics::resultsOf
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


// ************************************************************************* //
