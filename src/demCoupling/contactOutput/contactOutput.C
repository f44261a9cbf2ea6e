/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Per-contact output at write times (lagrangian/demContacts).

\*---------------------------------------------------------------------------*/

#include "contactOutput.H"
#include "passiveParticleCloud.H"
#include "IOField.H"
#include "PstreamBuffers.H"

namespace
{
    // one field of the contact cloud
    template<class Type>
    void writeField
    (
        const Foam::passiveParticleCloud& cloud,
        const Foam::word& name,
        const Foam::UList<Type>& values
    )
    {
        Foam::IOField<Type> f
        (
            cloud.fieldIOobject(name, Foam::IOobject::NO_READ), values
        );
        f.write();
    }
}

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::contactOutput::contactOutput
(
    const fvMesh& mesh,
    demWorld& world,
    const demTools::periodicBox& box,
    const dictionary& dict
)
:
    mesh_(mesh),
    world_(world),
    box_(box),
    on_(dict.getOrDefault<bool>("writeContacts", false))
{
    if (on_)
    {
        world.keepContacts();
    }
}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::contactOutput::write() const
{
    if (!on_) return;

    const std::vector<dem_contact>& c = world_.contacts();
    const std::vector<double>& xc = world_.contactPoints();
    const label nAll = world_.contactsKnown() ? label(c.size()) : 0;

    passiveParticleCloud cloud
    (
        mesh_, word("demContacts"), IDLList<passiveParticle>()
    );
    DynamicList<label> idA(nAll), idB(nAll), wallId(nAll);
    DynamicList<scalar> overlap(nAll);
    DynamicList<vector> normal(nAll), Fn(nAll), Ft(nAll);
    label nPair = 0, nWall = 0;
    const auto add = [&]
    (
        const point& p, const label celli, const label a, const label b,
        const label w, const scalar delta, const vector& n, const vector& fn,
        const vector& ft
    )
    {
        cloud.addParticle(new passiveParticle(mesh_, p, celli));
        idA.append(a);
        idB.append(b);
        wallId.append(w);
        overlap.append(delta);
        normal.append(n);
        Fn.append(fn);
        Ft.append(ft);
        ++(w >= 0 ? nWall : nPair);
    };
    const auto vec = [](const double* v) { return vector(v[0], v[1], v[2]); };

    // contacts this processor evaluated alone (not owned-ghost pairs) whose
    // point lies in another processor's part of the mesh (a wall oblique to
    // a processor boundary, a non-convex part): sent to all the others
    DynamicList<point> sP;
    DynamicList<label> sA, sB, sW;
    DynamicList<scalar> sD;
    DynamicList<vector> sN, sFn, sFt;
    for (label k = 0; k < nAll; ++k)
    {
        const dem_contact& ck = c[k];
        const point p(box_.wrapped(xc.data(), k));
        const label a = label(ck.id_a);
        const label b = ck.wall ? -1 : label(ck.id_b);
        const label w = ck.wall ? label(ck.id_b) : -1;
        const label celli = mesh_.findCell(p);
        if (celli >= 0)
        {
            add
            (
                p, celli, a, b, w, ck.overlap, vec(ck.normal),
                vec(ck.force_n), vec(ck.force_t)
            );
        }
        else if (!ck.ghost)
        {
            // (an owned-ghost pair is written by the other processor)
            sP.append(p); sA.append(a); sB.append(b); sW.append(w);
            sD.append(ck.overlap); sN.append(vec(ck.normal));
            sFn.append(vec(ck.force_n)); sFt.append(vec(ck.force_t));
        }
    }
    label nLost = sP.size();
    const label nSent = returnReduce(nLost, sumOp<label>());
    if (Pstream::parRun() && nSent)
    {
        PstreamBuffers pBufs(Pstream::commsTypes::nonBlocking);
        for (label proci = 0; proci < Pstream::nProcs(); ++proci)
        {
            if (proci == Pstream::myProcNo()) continue;
            UOPstream os(proci, pBufs);
            os << sP << sA << sB << sW << sD << sN << sFn << sFt;
        }
        pBufs.finishedSends();
        nLost = 0;
        label nTaken = 0;
        for (label proci = 0; proci < Pstream::nProcs(); ++proci)
        {
            if (proci == Pstream::myProcNo()) continue;
            UIPstream is(proci, pBufs);
            List<point> rP;
            labelList rA, rB, rW;
            scalarList rD;
            List<vector> rN, rFn, rFt;
            is >> rP >> rA >> rB >> rW >> rD >> rN >> rFn >> rFt;
            nLost += rP.size();
            forAll(rP, j)
            {
                const label celli = mesh_.findCell(rP[j]);
                if (celli < 0) continue;
                add(rP[j], celli, rA[j], rB[j], rW[j], rD[j], rN[j], rFn[j], rFt[j]);
                ++nTaken;
            }
        }
        // every contact sent was received by nProcs - 1 processors
        nLost = returnReduce(nLost, sumOp<label>())/(Pstream::nProcs() - 1)
          - returnReduce(nTaken, sumOp<label>());
    }
    else
    {
        reduce(nLost, sumOp<label>());
    }

    bool known = world_.contactsKnown();
    reduce(known, andOp<bool>());
    reduce(nPair, sumOp<label>());
    reduce(nWall, sumOp<label>());
    if (known)
    {
        Info<< "demCoupling: contacts of the last DEM step: "
            << nPair + nWall << " (particle-particle " << nPair
            << ", particle-wall " << nWall << ") written to lagrangian/"
            << cloud.name() << endl;
        if (Pstream::parRun())
        {
            Info<< "demCoupling: contacts sent to the processor holding "
                << "their point: " << nSent << endl;
        }
    }
    else
    {
        Info<< "demCoupling: contacts of the last DEM step not known (no "
            << "DEM step since the start or a restore, or a frozen bed): "
            << "lagrangian/" << cloud.name() << " written empty" << endl;
    }
    if (nLost)
    {
        WarningInFunction
            << nLost << " contacts have their contact point in no "
            << "processor's part of the mesh: not written" << endl;
    }

    cloud.write();
    if (cloud.size())
    {
        writeField(cloud, "idA", idA);
        writeField(cloud, "idB", idB);
        writeField(cloud, "wallId", wallId);
        writeField(cloud, "overlap", overlap);
        writeField(cloud, "normal", normal);
        writeField(cloud, "Fn", Fn);
        writeField(cloud, "Ft", Ft);
    }
}


// ************************************************************************* //
