/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    The particles that enter the DEM world, set up once by demCoupling's
    constructor: the inlets (patches with an insertion rate), the initial
    particles (a list, or a box or cylinder filled with a number of
    particles) and their distributions; the insertion ramp, per fluid step.

\*---------------------------------------------------------------------------*/

#include "particleInsertion.H"
#include "insertionRegion.H"
#include "demCouplingTools.H"

using namespace Foam::demTools;

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


// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::particleInsertion::particleInsertion
(
    const fvMesh& mesh,
    demWorld& world,
    const particleLocator& locator,
    const dictionary& dict,
    const HashTable<label>& materialIds,
    couplingState& state
)
:
    mesh_(mesh),
    world_(world),
    locator_(locator),
    dict_(dict),
    materialIds_(materialIds),
    state_(state),
    rampTime_(dict.getOrDefault<scalar>("insertionRampTime", 0)),
    rampNow_(mesh.time().value()),
    inletBoxes_(),
    inletRadius_(0)
{}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::particleInsertion::addInlets()
{
    const polyBoundaryMesh& bm = mesh_.boundaryMesh();
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
        t.material = materialId(materialIds_, d.get<word>("material"), d);

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


void Foam::particleInsertion::addInitialParticles()
{
    if (!dict_.found("initialParticles")) return;
    const dictionary& all = dict_.subDict("initialParticles");
    for (const entry& e : all)
    {
        if (!e.isDict()) continue;
        const dictionary& d = e.dict();
        const word type(d.get<word>("type"));
        const int mat = materialId(materialIds_, d.get<word>("material"), d);
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
            const word arrangement
            (
                d.getOrDefault<word>("arrangement", "random")
            );
            // lattice and randomBlocks: each particle computed from its
            // index, so a processor keeps only those near it
            const bool indexed = arrangement != "random";
            const bool blocks = arrangement == "randomBlocks";
            dem_status s = DEM_OK;
            // the same arguments for both
            const auto boxFill =
                blocks ? &dem_world_fill_blocks_box : &dem_world_fill_lattice_box;
            const auto cylinderFill =
                blocks
              ? &dem_world_fill_blocks_cylinder
              : &dem_world_fill_lattice_cylinder;
            if (indexed && type == "box")
            {
                s = boxFill
                (
                    world_, lo.cdata(), hi.cdata(), size_t(n), &t, &inserted
                );
            }
            else if (indexed)
            {
                const point base(d.get<point>("base"));
                const vector axis(d.get<vector>("axis"));
                s = cylinderFill
                (
                    world_, base.cdata(), axis.cdata(),
                    d.get<scalar>("radius"), d.get<scalar>("length"),
                    size_t(n), &t, &inserted
                );
            }
            else
            {
                if (Pstream::parRun() && n >= 100000)
                {
                    // the sequential draw is the one part of the set-up
                    // that every processor repeats whole
                    Info<< "demCoupling: " << e.keyword() << ": every "
                        << "processor draws all " << n << " particles of "
                        << "this random fill; arrangement randomBlocks "
                        << "draws only those near each processor "
                        << "(docs/demProperties.md)" << endl;
                }
                s = dem_world_fill_box
                (
                    world_, lo.cdata(), hi.cdata(), &insertionRegion::inside,
                    const_cast<insertionRegion*>(&region), size_t(n), &t,
                    &inserted
                );
            }
            if (s == DEM_ERR_FULL)
            {
                FatalIOErrorInFunction(d)
                    << "initialParticles/" << e.keyword() << " in "
                    << d.name() << ": "
                    << (indexed ? std::string("not all ") : "only " + Foam::name(label(inserted)) + " of ").c_str()
                    << n << " particles fit into the "
                    << region.describe().c_str()
                    << (
                           !indexed ? std::string()
                         : std::string(" (arrangement ") + arrangement
                         + (blocks ? ": " : ": one cubic cell of the largest diameter each; ")
                         + world_.lastError() + ")"
                       ).c_str()
                    << "; enlarge the region or lower number"
                    << exit(FatalIOError);
            }
            world_.check
            (
                s,
                !indexed ? "dem_world_fill_box"
              : blocks ? "dem_world_fill_blocks" : "dem_world_fill_lattice"
            );
            Info<< "demCoupling: " << e.keyword() << ": " << label(inserted)
                << " particles in " << region.describe().c_str()
                << (indexed ? std::string(" (") + arrangement + ")" : std::string()).c_str()
                << endl;
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


Foam::scalar Foam::particleInsertion::initialDiameterMax() const
{
    scalar dMax = 0;
    if (!dict_.found("initialParticles")) return dMax;
    for (const entry& e : dict_.subDict("initialParticles"))
    {
        if (!e.isDict()) continue;
        PtrList<scalarField> store;
        dMax = max(dMax, distributionMax(readDistribution(e.dict(), "diameter", store)));
    }
    return dMax;
}


dem_distribution Foam::particleInsertion::readDistribution
(
    const dictionary& parent,
    const word& key,
    PtrList<scalarField>& store
)
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


void Foam::particleInsertion::rampAt(const scalar t)
{
    // a particle inserted at t0 counts with the weight (t - t0)/rampTime_
    // until rampTime_ has passed, so that the fluid sees its volume arrive
    // over rampTime_ instead of in one step
    for (auto it = state_.rampStart.begin(); it != state_.rampStart.end(); )
    {
        if (t - it->second >= rampTime_) it = state_.rampStart.erase(it);
        else ++it;
    }
    rampNow_ = t;
}


Foam::scalar Foam::particleInsertion::rampWeight(const int64_t id) const
{
    if (state_.rampStart.empty())
    {
        return 1;
    }
    const auto it = state_.rampStart.find(id);
    return
        it == state_.rampStart.end()
      ? 1
      : min(max(rampNow_ - it->second, 0)/rampTime_, 1);
}


void Foam::particleInsertion::startRamp(const DynamicList<int64_t>& inserted)
{
    if (rampTime_ <= 0)
    {
        return;
    }
    // (decomposed: the master inserts; new particles may migrate to another
    // processor before their ramp ends, so every processor keeps all ids)
    List<List<int64_t>> all(Pstream::nProcs());
    all[Pstream::myProcNo()] = inserted;
    if (Pstream::parRun())
    {
        Pstream::gatherList(all);
        Pstream::scatterList(all);
    }
    const scalar t0 = mesh_.time().value() - mesh_.time().deltaTValue();
    for (const List<int64_t>& ids : all)
    {
        for (const int64_t id : ids)
        {
            state_.rampStart[id] = t0;
        }
    }
}


// ************************************************************************* //
