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
    label nPair = 0, nWall = 0, nLost = 0;
    for (label k = 0; k < nAll; ++k)
    {
        const dem_contact& ck = c[k];
        const vector p(box_.wrapped(xc.data(), k));
        const label celli = mesh_.findCell(p);
        if (celli < 0)
        {
            // an owned-ghost pair whose point is on the other processor is
            // written there; any other contact should be here
            if (!ck.ghost) ++nLost;
            continue;
        }
        cloud.addParticle(new passiveParticle(mesh_, p, celli));
        idA.append(label(ck.id_a));
        idB.append(ck.wall ? -1 : label(ck.id_b));
        wallId.append(ck.wall ? label(ck.id_b) : -1);
        overlap.append(ck.overlap);
        normal.append(vector(ck.normal[0], ck.normal[1], ck.normal[2]));
        Fn.append(vector(ck.force_n[0], ck.force_n[1], ck.force_n[2]));
        Ft.append(vector(ck.force_t[0], ck.force_t[1], ck.force_t[2]));
        ++(ck.wall ? nWall : nPair);
    }

    bool known = world_.contactsKnown();
    reduce(known, andOp<bool>());
    reduce(nPair, sumOp<label>());
    reduce(nWall, sumOp<label>());
    reduce(nLost, sumOp<label>());
    if (known)
    {
        Info<< "demCoupling: contacts of the last DEM step: "
            << nPair + nWall << " (particle-particle " << nPair
            << ", particle-wall " << nWall << ") written to lagrangian/"
            << cloud.name() << endl;
    }
    else
    {
        Info<< "demCoupling: contacts of the last DEM step not known (no "
            << "recorded DEM step since the start or the last restore): "
            << "lagrangian/" << cloud.name() << " written empty" << endl;
    }
    if (nLost)
    {
        WarningInFunction
            << nLost << " contacts have their contact point outside the "
            << "mesh and are not written" << endl;
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
