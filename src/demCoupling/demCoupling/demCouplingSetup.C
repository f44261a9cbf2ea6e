/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Setup of the DEM world from constant/demProperties (docs/demProperties.md),
    called once by the constructor: core parameters, materials and periodic
    box (configureWorld), walls (patchWalls), outlets and inlets, and the
    initial particles.

\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "timeCompletion.H"
#include "dictionaryFileCheck.H"
#include "insertionRegion.H"
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

// * * * * * * * * * * * * * * * * Helpers * * * * * * * * * * * * * * * * //

namespace
{
    // Largest value a distribution draws (normal: mean + 3 sd)
    Foam::scalar distributionMax(const dem_distribution& d)
    {
        switch (d.kind)
        {
            case DEM_DIST_UNIFORM: return d.b;
            case DEM_DIST_NORMAL: return d.a + 3*d.b;
            case DEM_DIST_DISCRETE:
            {
                Foam::scalar m = 0;
                for (size_t k = 0; k < d.n; ++k) m = Foam::max(m, d.values[k]);
                return m;
            }
            default: return d.a;
        }
    }
}


// * * * * * * * * * * * * * * * Setup * * * * * * * * * * * * * * * * * * //

Foam::label Foam::demCoupling::materialId
(
    const word& name,
    const dictionary& d
) const
{
    if (!materialIds_.found(name))
    {
        FatalIOErrorInFunction(d)
            << "material " << name << " in " << d.name()
            << " is not defined in materials; defined: "
            << materialIds_.sortedToc() << exit(FatalIOError);
    }
    return materialIds_[name];
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
        periodic_[k] = true;
        boxLo_[k] = bb.min()[k];
        boxHi_[k] = bb.max()[k];
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
                dMax = max(dMax, distributionMax(readDistribution(e.dict(), "diameter", store)));
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


namespace
{
    // Convex hull (monotone chain) of 2-D points, counter-clockwise
    Foam::labelList convexHull(const Foam::List<Foam::vector2D>& p)
    {
        using namespace Foam;
        labelList idx(identity(p.size()));
        std::sort
        (
            idx.begin(), idx.end(),
            [&](label a, label b)
            {
                return p[a].x() < p[b].x()
                    || (p[a].x() == p[b].x() && p[a].y() < p[b].y());
            }
        );
        auto cross = [&](label o, label a, label b)
        {
            return (p[a].x() - p[o].x())*(p[b].y() - p[o].y())
                 - (p[a].y() - p[o].y())*(p[b].x() - p[o].x());
        };
        DynamicList<label> h;
        for (const label i : idx)
        {
            while (h.size() >= 2 && cross(h[h.size()-2], h.last(), i) <= 0)
            {
                h.remove();
            }
            h.append(i);
        }
        const label lower = h.size() + 1;
        for (label k = idx.size() - 2; k >= 0; --k)
        {
            const label i = idx[k];
            while (h.size() >= lower && cross(h[h.size()-2], h.last(), i) <= 0)
            {
                h.remove();
            }
            h.append(i);
        }
        h.remove();
        return labelList(h);
    }
}


void Foam::demCoupling::addOutletsAndInlets()
{
    const polyBoundaryMesh& bm = mesh_.boundaryMesh();
    state_.lostPerPatch.setSize(bm.size(), 0);

    const wordList outlets
    (
        dict_.getOrDefault<wordList>("outletPatches", wordList())
    );
    for (const word& name : outlets)
    {
        const label patchi = bm.findPatchID(name);
        if (patchi < 0)
        {
            FatalIOErrorInFunction(dict_)
                << "outletPatches entry " << name << " in " << dict_.name()
                << " is not a patch; patches: " << bm.names()
                << exit(FatalIOError);
        }
        int id;
        world_.check(dem_world_add_outlet(world_, &id), "dem_world_add_outlet");
        outletPatches_.append(patchi);
        outletIds_.append(id);
    }

    if (!dict_.found("inlets")) return;

    const dictionary& inl = dict_.subDict("inlets");
    for (const entry& e : inl)
    {
        if (!e.isDict()) continue;
        const dictionary& d = e.dict();
        const word patchName(d.get<word>("patch"));
        const label patchi = bm.findPatchID(patchName);
        if (patchi < 0 || !returnReduce(bm[patchi].size(), sumOp<label>()))
        {
            FatalIOErrorInFunction(d)
                << "inlets/" << e.keyword() << "/patch " << patchName
                << " in " << d.name() << " is not a non-empty patch; patches: "
                << bm.names() << exit(FatalIOError);
        }
        const polyPatch& pp = bm[patchi];
        // polygon: convex hull of the patch points in the patch plane
        // (decomposed: of the points of all processors)
        vector n = gSum(pp.faceAreas());
        n /= mag(n);
        const point c0 =
            gSum(pp.faceCentres())/returnReduce(pp.size(), sumOp<label>());
        const pointField lp(joinAll(pp.localPoints()));
        vector e1 = lp[0] - c0;
        e1 -= (e1 & n)*n;
        e1 /= mag(e1);
        const vector e2 = n ^ e1;
        List<vector2D> p2(lp.size());
        forAll(lp, i)
        {
            p2[i] = vector2D((lp[i] - c0) & e1, (lp[i] - c0) & e2);
        }
        PtrList<scalarField> store;
        dem_particle_template t;
        t.diameter = readDistribution(d, "diameter", store);
        t.density = readDistribution(d, "density", store);
        t.material = materialId(d.get<word>("material"), d);

        const scalar dMax = distributionMax(t.diameter);

        // polygon: convex hull of the patch points in the patch plane,
        // moved into the domain by 0.6 of the largest diameter so that new
        // particles start inside the mesh, and shrunk about its centroid so
        // that every edge moves inwards by at least 0.55 d_max: new spheres
        // do not touch the walls that bound the patch
        const labelList hull(convexHull(p2));
        vector2D cen(Zero);
        for (const label h : hull) cen += p2[h];
        cen /= hull.size();
        scalar rIn = GREAT;
        forAll(hull, k)
        {
            const vector2D a = p2[hull[k]];
            const vector2D b = p2[hull[(k + 1) % hull.size()]];
            const vector2D t = (b - a)/max(mag(b - a), VSMALL);
            const vector2D r = cen - a;
            rIn = min(rIn, mag(r - (r & t)*t));
        }
        const scalar inset = 0.55*dMax;
        if (rIn <= inset)
        {
            FatalIOErrorInFunction(d)
                << "inlets/" << e.keyword() << ": patch " << patchName
                << " is too small for particles of diameter " << dMax
                << " (inradius " << rIn << " m)" << exit(FatalIOError);
        }
        const scalar shrink = (rIn - inset)/rIn;
        List<double> poly(3*hull.size());
        forAll(hull, k)
        {
            const vector2D q = cen + shrink*(p2[hull[k]] - cen);
            const point x = c0 + q.x()*e1 + q.y()*e2 - 0.6*dMax*n;
            for (direction j = 0; j < 3; ++j) poly[3*k+j] = x[j];
        }
        const vector v(d.getOrDefault<vector>("velocity", Zero));
        for (direction j = 0; j < 3; ++j) t.velocity[j] = v[j];

        const word kind(d.getOrDefault<word>("rateType", "number"));
        if (kind != "number" && kind != "mass")
        {
            FatalIOErrorInFunction(d)
                << "rateType " << kind << " in " << d.name()
                << ": allowed number, mass" << exit(FatalIOError);
        }
        // decomposed: the master inserts (new particles migrate to their
        // processor at the end of the fluid step); ghosts near the inlet
        // are sent to it for the overlap test of the insertion
        inletRadius_ = max(inletRadius_, 0.5*dMax);
        if (!Pstream::master()) continue;
        if (Pstream::parRun())
        {
            boundBox ib(boundBox::invertedBox);
            forAll(hull, k)
            {
                ib.add(point(poly[3*k], poly[3*k+1], poly[3*k+2]));
            }
            ib.min() -= vector::one*dMax;
            ib.max() += vector::one*dMax;
            inletBoxes_.append(ib);
        }
        int id;
        world_.check
        (
            dem_world_add_inlet
            (
                world_, hull.size(), poly.cdata(),
                kind == "mass" ? DEM_RATE_MASS : DEM_RATE_NUMBER,
                d.get<scalar>("rate"),
                d.getOrDefault<scalar>("start", 0),
                d.getOrDefault<scalar>("end", GREAT),
                &t, &id
            ),
            "dem_world_add_inlet"
        );
        Info<< "demCoupling: inlet " << e.keyword() << " on patch "
            << patchName << endl;
    }
}


dem_distribution Foam::demCoupling::readDistribution
(
    const dictionary& parent,
    const word& key,
    PtrList<scalarField>& store
) const
{
    dem_distribution dist;
    dist.n = 0;
    dist.values = nullptr;
    dist.weights = nullptr;
    dist.a = dist.b = 0;

    if (!parent.isDict(key))
    {
        dist.kind = DEM_DIST_FIXED;
        dist.a = parent.get<scalar>(key);
        return dist;
    }
    const dictionary& d = parent.subDict(key);
    const word type(d.get<word>("type"));
    if (type == "fixed")
    {
        dist.kind = DEM_DIST_FIXED;
        dist.a = d.get<scalar>("value");
    }
    else if (type == "uniform")
    {
        dist.kind = DEM_DIST_UNIFORM;
        dist.a = d.get<scalar>("min");
        dist.b = d.get<scalar>("max");
    }
    else if (type == "normal")
    {
        dist.kind = DEM_DIST_NORMAL;
        dist.a = d.get<scalar>("mean");
        dist.b = d.get<scalar>("stdDev");
    }
    else if (type == "discrete")
    {
        dist.kind = DEM_DIST_DISCRETE;
        // store is sized by the caller's needs; keep data alive there
        store.append(new scalarField(d.get<scalarField>("values")));
        store.append(new scalarField(d.get<scalarField>("weights")));
        const scalarField& vals = store[store.size()-2];
        const scalarField& wts = store[store.size()-1];
        if (vals.size() != wts.size() || vals.empty())
        {
            FatalIOErrorInFunction(d)
                << key << " in " << d.name() << ": values and weights must "
                << "have the same non-zero length" << exit(FatalIOError);
        }
        dist.n = vals.size();
        dist.values = vals.cdata();
        dist.weights = wts.cdata();
    }
    else
    {
        FatalIOErrorInFunction(d)
            << key << "/type " << type << " in " << d.name()
            << ": allowed fixed, uniform, normal, discrete"
            << exit(FatalIOError);
    }
    return dist;
}


void Foam::demCoupling::addInitialParticles()
{
    if (!dict_.found("initialParticles")) return;
    const dictionary& all = dict_.subDict("initialParticles");
    for (const entry& e : all)
    {
        if (!e.isDict()) continue;
        const dictionary& d = e.dict();
        const word type(d.get<word>("type"));
        const int mat = materialId(d.get<word>("material"), d);
        const vector v(d.getOrDefault<vector>("velocity", Zero));

        if (type == "list")
        {
            const List<point> pos(d.get<List<point>>("positions"));
            const scalar dia = d.get<scalar>("diameter");
            const scalar rho = d.get<scalar>("density");
            const vector w(d.getOrDefault<vector>("angularVelocity", Zero));
            List<dem_particle> ps(pos.size());
            forAll(pos, i)
            {
                dem_particle& p = ps[i];
                p.id = -1;
                for (direction k = 0; k < 3; ++k)
                {
                    p.x[k] = pos[i][k];
                    p.v[k] = v[k];
                    p.omega[k] = w[k];
                }
                p.radius = 0.5*dia;
                p.density = rho;
                p.material = mat;
            }
            world_.check
            (
                dem_world_add_particles(world_, ps.size(), ps.cdata()),
                "dem_world_add_particles"
            );
            Info<< "demCoupling: " << e.keyword() << ": " << ps.size()
                << " particles from a list" << endl;
        }
        else if (type == "box" || type == "cylinder")
        {
            // box or cylinder, optionally cut to the mesh (insertionRegion)
            const label n = d.get<label>("number");
            PtrList<scalarField> store;
            dem_particle_template t;
            t.diameter = readDistribution(d, "diameter", store);
            t.density = readDistribution(d, "density", store);
            t.material = mat;
            for (direction k = 0; k < 3; ++k) t.velocity[k] = v[k];
            const insertionRegion region
            (
                d, locator_, 0.5*distributionMax(t.diameter)
            );
            const point lo(region.bounds().min()), hi(region.bounds().max());
            size_t inserted = 0;
            const dem_status s = dem_world_fill_box
            (
                world_, lo.cdata(), hi.cdata(), &insertionRegion::inside,
                const_cast<insertionRegion*>(&region), size_t(n), &t,
                &inserted
            );
            if (s == DEM_ERR_FULL)
            {
                FatalIOErrorInFunction(d)
                    << "initialParticles/" << e.keyword() << " in "
                    << d.name() << ": only " << label(inserted) << " of "
                    << n << " particles fit into the "
                    << region.describe().c_str()
                    << "; enlarge the region or lower number"
                    << exit(FatalIOError);
            }
            world_.check(s, "dem_world_fill_box");
            Info<< "demCoupling: " << e.keyword() << ": " << label(inserted)
                << " particles in " << region.describe().c_str() << endl;
        }
        else
        {
            FatalIOErrorInFunction(d)
                << "initialParticles/" << e.keyword() << "/type " << type
                << " in " << d.name() << ": allowed box, cylinder, list"
                << exit(FatalIOError);
        }
    }
}


// ************************************************************************* //
