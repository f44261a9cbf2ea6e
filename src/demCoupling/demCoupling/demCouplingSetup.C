/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Setup of the DEM world from constant/demProperties (docs/demProperties.md),
    called once by the constructor: core parameters, materials and periodic
    box (configureWorld) and walls (patchWalls); the particles that enter
    and their size and density distributions are particleInsertion's.

\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "timeCompletion.H"
#include "dictionaryFileCheck.H"
#include "patchWalls.H"
#include "demCouplingTools.H"
#include "OStringStream.H"
#include <limits>
#include "fvc.H"
#include "fvm.H"
#include "cyclicPolyPatch.H"
#include "processorPolyPatch.H"
#include "processorCyclicPolyPatch.H"
#include "mathematicalConstants.H"
#include "OSspecific.H"
#include <fstream>

using namespace Foam::constant::mathematical;
using namespace Foam::demTools;

// * * * * * * * * * * * * * * * Setup * * * * * * * * * * * * * * * * * * //

Foam::label Foam::demCoupling::materialId
(
    const word& name,
    const dictionary& d
) const
{
    return demTools::materialId(materialIds_, name, d);
}


void Foam::demCoupling::configureWorld()
{
    const dictionary& d = dict_.subDict("dem");

    dem_config c;
    dem_config_default(&c);

    const word law(d.getOrDefault<word>("contactLaw", "hertzMindlin"));
    if (dem_contact_law_from_name(law.c_str(), &c.contact_law) != DEM_OK)
    {
        wordList valid;
        for (int l = 0; l < DEM_CONTACT_LAW_COUNT; ++l)
        {
            const char* nm = dem_contact_law_name(dem_contact_law(l));
            if (nm) valid.append(word(nm));
        }
        FatalIOErrorInFunction(d)
            << "contactLaw " << law << " in " << d.name()
            << ": allowed " << valid << exit(FatalIOError);
    }

    c.dt = demDt_;
    for (direction k = 0; k < 3; ++k) c.gravity[k] = g_[k];

    const boundBox& bb = mesh_.bounds();
    const scalar margin =
        d.getOrDefault<scalar>("domainMargin", 0.05*cmptMax(bb.span()));
    for (direction k = 0; k < 3; ++k)
    {
        c.domain_lo[k] = bb.min()[k] - margin;
        c.domain_hi[k] = bb.max()[k] + margin;
        c.periodic[k] = 0;
    }

    // cyclic patches -> periodic axes (translational, axis-aligned).
    // Decomposed, a cyclic's faces may lie on processorCyclic patches (its
    // halves on different processors): the area of each cyclic is summed
    // over its own faces and those, over all processors
    const polyBoundaryMesh& bm = mesh_.boundaryMesh();
    List<vector> cycArea(bm.size(), Zero);
    labelList cycFaces(bm.size(), 0);
    for (const polyPatch& pp : bm)
    {
        label ci = -1;
        if (isA<processorCyclicPolyPatch>(pp))
        {
            ci = refCast<const processorCyclicPolyPatch>(pp).referPatchID();
        }
        else if (isA<cyclicPolyPatch>(pp))
        {
            ci = pp.index();
        }
        if (ci >= 0)
        {
            cycArea[ci] += sum(pp.faceAreas());
            cycFaces[ci] += pp.size();
        }
    }
    for (label patchi = 0; patchi < bm.nNonProcessor(); ++patchi)
    {
        const polyPatch& pp = bm[patchi];
        if (!isA<cyclicPolyPatch>(pp)) continue;
        if (!returnReduce(cycFaces[patchi], sumOp<label>())) continue;
        vector n = returnReduce(cycArea[patchi], sumOp<vector>());
        n /= mag(n);
        const direction k = findMax(cmptMag(n));
        if (mag(n[k]) < 1 - 1e-6)
        {
            FatalErrorInFunction
                << "cyclic patch " << pp.name() << " is not normal to a "
                << "coordinate axis (normal " << n << "); only "
                << "axis-aligned translational cyclics become DEM "
                << "periodic boundaries" << exit(FatalError);
        }
        c.periodic[k] = 1;
        c.domain_lo[k] = bb.min()[k];
        c.domain_hi[k] = bb.max()[k];
        box_.periodic[k] = true;
        box_.lo[k] = bb.min()[k];
        box_.hi[k] = bb.max()[k];
        Info<< "demCoupling: cyclic patch " << pp.name()
            << " -> DEM periodic along " << vector::componentNames[k]
            << endl;
    }

    c.skin = d.getOrDefault<scalar>("skin", -1);
    if (Pstream::parRun() && c.skin <= 0)
    {
        // the core's automatic skin (0.2 of the largest diameter present)
        // could differ between processors; the decomposed Verlet scheme
        // needs one skin: 0.2 of the largest diameter in demProperties
        scalar dMax = 0;
        for (const word& scope : {word("initialParticles"), word("inlets")})
        {
            if (!dict_.isDict(scope)) continue;
            for (const entry& e : dict_.subDict(scope))
            {
                if (!e.isDict()) continue;
                PtrList<scalarField> store;
                const dem_distribution dia
                (
                    particleInsertion::readDistribution
                    (
                        e.dict(), "diameter", store
                    )
                );
                dMax = max(dMax, distributionMax(dia));
            }
        }
        if (dMax > 0)
        {
            c.skin = 0.2*dMax;
            Info<< "demCoupling: decomposed: dem/skin " << c.skin
                << " m (0.2 of the largest diameter)" << endl;
        }
    }
    c.max_dt_fraction = d.getOrDefault<scalar>("maxDtFraction", c.max_dt_fraction);
    c.max_overlap_ratio =
        d.getOrDefault<scalar>("maxOverlapRatio", c.max_overlap_ratio);
    c.seed = uint64_t(d.getOrDefault<label>("seed", 1));
    c.impact_speed = d.getOrDefault<scalar>("impactSpeed", c.impact_speed);
    c.damping_predicted = d.getOrDefault<bool>("dampingPredicted", false);

    world_.check(dem_world_configure(world_, &c), "dem_world_configure");
    config_ = c;

    // materials (in the order given)
    auto readMaterial = [](const dictionary& md, const word& name)
    {
        dem_material m;
        m.youngs_modulus = md.getOrDefault<scalar>("youngsModulus", 0);
        m.poisson_ratio = md.getOrDefault<scalar>("poissonRatio", 0.3);
        m.stiffness_n = md.getOrDefault<scalar>("stiffnessN", 0);
        m.stiffness_t = md.getOrDefault<scalar>("stiffnessT", -1);
        m.friction = md.getOrDefault<scalar>("friction", 0.4);
        m.rolling_friction = md.getOrDefault<scalar>("rollingFriction", 0);
        m.restitution = md.getOrDefault<scalar>("restitution", -1);
        m.damping = md.getOrDefault<scalar>("damping", -1);
        if (md.getOrDefault<bool>("rigid", false))
        {
            // a wall that does not deform (dem.h, DEM_RIGID)
            m.youngs_modulus = DEM_RIGID;
            m.stiffness_n = DEM_RIGID;
            m.stiffness_t = DEM_RIGID;
        }
        if (m.restitution < 0 && m.damping < 0)
        {
            FatalIOErrorInFunction(md)
                << name << " in " << md.name()
                << ": give restitution (0 < e <= 1) or damping (>= 0)"
                << exit(FatalIOError);
        }
        return m;
    };

    const dictionary& mats = dict_.subDict("materials");
    for (const entry& e : mats)
    {
        if (!e.isDict()) continue;
        const dem_material m = readMaterial(e.dict(), "material " + e.keyword());
        int id;
        world_.check(dem_world_add_material(world_, &m, &id), "dem_world_add_material");
        materialIds_.insert(e.keyword(), id);
    }

    // per-pair overrides, e.g. a particle-wall stiffness ([S] Table 1)
    if (dict_.found("materialPairs"))
    {
        const dictionary& pairs = dict_.subDict("materialPairs");
        for (const entry& e : pairs)
        {
            if (!e.isDict()) continue;
            const dictionary& pd = e.dict();
            const wordList names(pd.get<wordList>("materials"));
            if (names.size() != 2)
            {
                FatalIOErrorInFunction(pd)
                    << "materialPairs/" << e.keyword() << "/materials in "
                    << pd.name() << ": give two material names"
                    << exit(FatalIOError);
            }
            const dem_material m =
                readMaterial(pd, "materialPairs/" + e.keyword());
            world_.check
            (
                dem_world_set_pair
                (
                    world_, materialId(names[0], pd), materialId(names[1], pd), &m
                ),
                "dem_world_set_pair"
            );
            Info<< "demCoupling: material pair " << e.keyword() << " ("
                << names[0] << ", " << names[1] << ") replaces the combined"
                << " parameters:";
            if (m.youngs_modulus > 0)
            {
                Info<< " E " << m.youngs_modulus << " Pa,";
            }
            if (m.stiffness_n > 0)
            {
                Info<< " k_n " << m.stiffness_n << " N/m,";
            }
            Info<< " friction " << m.friction
                << ", rolling friction " << m.rolling_friction << " m, "
                << (m.restitution > 0 ? "restitution " : "damping ")
                << (m.restitution > 0 ? m.restitution : m.damping) << nl;
        }
    }
    if (materialIds_.empty())
    {
        FatalIOErrorInFunction(mats)
            << "no material in " << mats.name() << exit(FatalIOError);
    }
}


void Foam::demCoupling::addWalls()
{
    const int mat = materialId(dict_.get<word>("wallMaterial"), dict_);
    patchWalls::add
    (
        world_,
        mesh_,
        dict_.getOrDefault<wordList>("wallPatches", wordList()),
        mat
    );
}


// ************************************************************************* //
