/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "timeCompletion.H"
#include "dictionaryFileCheck.H"
#include "insertionRegion.H"
#include "demCouplingTools.H"
#include "OStringStream.H"
#include <limits>
#include "fvc.H"
#include "fvm.H"
#include "emptyPolyPatch.H"
#include "wallPolyPatch.H"
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
    Foam::IOobject fieldIO
    (
        const Foam::fvMesh& mesh,
        const Foam::word& name,
        const bool write
    )
    {
        return Foam::IOobject
        (
            name,
            mesh.time().timeName(),
            mesh,
            Foam::IOobject::NO_READ,
            write ? Foam::IOobject::AUTO_WRITE : Foam::IOobject::NO_WRITE
        );
    }

    // eps boundary types: constraint types kept, fixedValue 1 on the
    // fluidInletPatches (the given U there is the superficial velocity),
    // zeroGradient elsewhere
    Foam::wordList epsPatchTypes
    (
        const Foam::fvMesh& mesh,
        const Foam::dictionary& dict
    )
    {
        using namespace Foam;
        const wordList inlets
        (
            dict.getOrDefault<wordList>("fluidInletPatches", wordList())
        );
        const polyBoundaryMesh& bm = mesh.boundaryMesh();
        for (const word& name : inlets)
        {
            if (bm.findPatchID(name) < 0)
            {
                FatalIOErrorInFunction(dict)
                    << "fluidInletPatches entry " << name << " in "
                    << dict.name() << " is not a patch; patches: "
                    << bm.names() << exit(FatalIOError);
            }
        }
        wordList types(bm.size(), "zeroGradient");
        forAll(bm, patchi)
        {
            if (polyPatch::constraintType(bm[patchi].type()))
            {
                types[patchi] = bm[patchi].type();
            }
            else if (inlets.found(bm[patchi].name()))
            {
                types[patchi] = "fixedValue";
            }
        }
        return types;
    }

}


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

    // The lists of all processors joined in processor order (decomposed
    // runs); the list itself when serial
    template<class T>
    Foam::List<T> joinAll(const Foam::UList<T>& mine)
    {
        using namespace Foam;
        if (!Pstream::parRun()) return List<T>(mine);
        List<List<T>> all(Pstream::nProcs());
        all[Pstream::myProcNo()] = mine;
        Pstream::gatherList(all);
        Pstream::scatterList(all);
        label n = 0;
        for (const List<T>& l : all) n += l.size();
        List<T> joined(n);
        n = 0;
        for (const List<T>& l : all)
        {
            for (const T& x : l) joined[n++] = x;
        }
        return joined;
    }
}


// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::demCoupling::demCoupling
(
    const fvMesh& mesh,
    const uniformDimensionedVectorField& g,
    const scalar rhof,
    const bool checkOnly
)
:
    mesh_(mesh),
    readTraps_(),
    fileChecked_
    (
        dictionaryFileCheck
        (
            IOobject("demProperties", mesh.time().constant(), mesh)
        )
    ),
    dict_
    (
        IOobject
        (
            "demProperties",
            mesh.time().constant(),
            mesh,
            IOobject::MUST_READ_IF_MODIFIED,
            IOobject::NO_WRITE
        )
    ),
    inputChecked_
    (
        checkDictionary(dict_, dict_.instance()/dict_.name(), mesh)
    ),
    g_(g.value()),
    rhof_(rhof),
    world_(),
    locator_(mesh, dict_.getOrDefault<label>("maxWalkSteps", 50)),
    formulation_(couplingFormulation::New(dict_)),
    drag_(dragModel::New(dict_)),
    voidage_(voidageModel::New(dict_, mesh, locator_)),
    extraForces_(extraForce::NewList(dict_)),
    Uprev_(),
    indexUprev_(-2),
    cellMeanDrag_(false),
    frozen_(dict_.getOrDefault<bool>("frozen", false)),
    epsMin_(dict_.getOrDefault<scalar>("epsMin", 0.1)),
    etaWarning_(dict_.getOrDefault<scalar>("etaWarning", 20.0)),
    rampTime_(dict_.getOrDefault<scalar>("insertionRampTime", 0)),
    rampStart_(),
    voidageTime_(mesh.time().value()),
    demDt_(0),
    dragUpdateInterval_(0),
    nSubCycles_(0),
    driving_(dict_.found("periodicDriving")),
    UsTarget_(Zero),
    drivingRelax_(0.2),
    G_(Zero),
    lostUnknown_(0),
    haloSend_(),
    haloStart_(2, Zero),
    haloAny_(false),
    haloParticleSteps_(0),
    bedEta_{0, 0, 0},
    balanceFluid_(0),
    balanceParticle_(0),
    balanceFluidVec_(Zero),
    balanceParticleVec_(Zero),
    sumDrag_(Zero),
    sumGradP_(Zero),
    sumTau_(Zero),
    solidVolumeMesh_(0),
    solidVolumeParticles_(0),
    solidVolumeRamp_(0),
    eps_
    (
        fieldIO(mesh, "eps", true),
        mesh,
        dimensionedScalar("one", dimless, 1.0),
        epsPatchTypes(mesh, dict_)
    ),
    epsRaw_(fieldIO(mesh, "epsRaw", false), mesh, dimensionedScalar("one", dimless, 1.0)),
    Up_(fieldIO(mesh, "Up", true), mesh, dimensionedVector(dimVelocity, Zero),
        "zeroGradient"),
    Kc_(fieldIO(mesh, "Kdrag", true), mesh,
        dimensionedScalar(dimDensity/dimTime, Zero)),
    F_(fieldIO(mesh, "Fexchange", false), mesh,
       dimensionedVector(dimForce/dimVolume, Zero)),
    Ucoup_(fieldIO(mesh, "Ucoupling", false), mesh,
           dimensionedVector(dimVelocity, Zero)),
    source_(fieldIO(mesh, "demMomentumSource", true), mesh,
            dimensionedVector(dimForce/dimVolume, Zero)),
    eta_(fieldIO(mesh, "eta", true), mesh, dimensionedScalar(dimless, Zero)),
    pCoeff_(fieldIO(mesh, "pressureCoeff", false), mesh,
            dimensionedScalar("one", dimless, 1.0), "zeroGradient"),
    tauCoeff_(fieldIO(mesh, "viscousCoeff", false), mesh,
            dimensionedScalar("one", dimless, 1.0), "zeroGradient"),
    bed_(mesh, g.value())
{
    readTraps_.release();
    failure_.clear();
    maxLost_ = dict_.getOrDefault<label>("maxLostParticles", 0);
    snapBuf_ = nullptr;
    snapSize_ = 0;
    snapCapacity_ = 0;
    snapLostUnknown_ = 0;
    snapBedEta_ = bedEta_;
    snapIndexUprev_ = -2;
    snapG_ = Zero;
    wallStart_ = std::chrono::steady_clock::now();
    wallLastProgress_ = 0;
    tDem_ = tCoupling_ = tFluid_ = 0;
    progressInterval_ = dict_.getOrDefault<scalar>("progressInterval", 60);
    progressSteps_ = dict_.getOrDefault<label>("progressSteps", 0);
    nSteps_ = 0;
    writeRequested_ = -1;
    startTime_ = mesh.time().value();
    injectParticleNaN_ = injectedStep("particleNaN");

    // decomposed: the mesh's tet base points are computed with
    // communication on first use (findCell); here, on every processor, so
    // that a later findCell on one processor alone does not wait for others
    if (Pstream::parRun())
    {
        (void)mesh_.tetBasePtIs();
    }
    periodic_ = false;
    boxLo_ = Zero;
    boxHi_ = Zero;
    inletRadius_ = 0;
    ghostSize_ = 0;
    tComm_ = 0;
    sendReorder_ = -1;

    const word scheme(dict_.getOrDefault<word>("dragScheme", "perParticle"));
    if (scheme == "cellMean")
    {
        cellMeanDrag_ = true;
    }
    else if (scheme != "perParticle")
    {
        FatalIOErrorInFunction(dict_)
            << "dragScheme " << scheme << " in " << dict_.name()
            << ": allowed perParticle (default) or cellMean"
            << exit(FatalIOError);
    }
    if (epsMin_ <= 0 || epsMin_ >= 1)
    {
        FatalIOErrorInFunction(dict_)
            << "epsMin " << epsMin_ << " in " << dict_.name()
            << ": allowed 0 < epsMin < 1" << exit(FatalIOError);
    }

    if (driving_)
    {
        const dictionary& dd = dict_.subDict("periodicDriving");
        UsTarget_ = dd.get<vector>("superficialVelocity");
        drivingRelax_ = dd.getOrDefault<scalar>("relaxation", 0.2);
        G_ = dd.getOrDefault<vector>("initialGradient", Zero);
    }

    const dictionary& demDict = dict_.subDict("dem");
    demDt_ = demDict.get<scalar>("timeStep");
    dragUpdateInterval_ = demDict.getOrDefault<label>("dragUpdateInterval", 0);

    subSteps(mesh.time().deltaTValue());

    configureWorld();
    // the DEM clock is the fluid's (inlet start and end times, removal
    // times, messages); settling runs on it before the start time
    const scalar t0 = mesh.time().value();
    const bool initial = timeCompletion::isInitial(mesh.time());
    const scalar tSettle =
        initial ? dict_.getOrDefault<scalar>("settlingTime", 0) : 0;
    const int64_t nSettle = int64_t(tSettle/demDt_ + 0.5);
    world_.check
    (
        dem_world_set_time(world_, t0 - nSettle*demDt_), "dem_world_set_time"
    );
    addWalls();
    addOutletsAndInlets();

    if (!restoreState(mesh.time().timePath()/"uniform", initial))
    {
        // decomposed: every processor creates (and settles) the whole set,
        // then keeps the particles in its cells
        addInitialParticles();
        checkInitialState();
        if (checkOnly) return;
        if (nSettle > 0)
        {
            Info<< "demCoupling: settling " << nSettle << " DEM steps ("
                << tSettle << " s, DEM time " << t0 - nSettle*demDt_
                << " to " << t0 << ") without fluid"
                << (Pstream::parRun() ? " (every processor the whole set)" : "")
                << endl;
            settle(nSettle);
        }
        // exactly the fluid's (the sum of the steps may differ by round-off)
        world_.check(dem_world_set_time(world_, t0), "dem_world_set_time");
        distributeByCell();
    }
    else if (mag(dem_world_time(world_) - t0) > 0.5*demDt_)
    {
        // a state written before the clocks were one (it ran ahead by its
        // settling time); a state of this version is kept as it is, so that
        // the restart is exact
        Info<< "demCoupling: the DEM state's clock " << dem_world_time(world_)
            << " s is set to the fluid's " << t0 << " s" << endl;
        world_.check(dem_world_set_time(world_, t0), "dem_world_set_time");
    }
    if (checkOnly) return;

    eps_.oldTime();
    locateAll();
    computeWeights();
    computeVoidage();
    eps_.oldTime() == eps_;
    if (!failure_.empty())
    {
        FatalErrorInFunction
            << failure_.c_str() << " (before the first step)" << exit(FatalError);
    }

    // (the same line serial and decomposed: tutorials' post-processing
    // reads it)
    Info<< "demCoupling: "
        << returnReduce(label(dem_world_count(world_)), sumOp<label>())
        << " particles, "
        << "formulation " << dict_.get<word>("formulation")
        << ", drag " << dict_.get<word>("dragModel")
        << (cellMeanDrag_ ? " (cell-mean)" : " (per particle)")
        << ", solid volume " << solidVolumeParticles_ << " m3" << nl << endl;

    // the progress estimate counts the coupled steps only (not the
    // settling and set-up before them)
    wallStart_ = std::chrono::steady_clock::now();
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
    const word wallMat(dict_.get<word>("wallMaterial"));
    const int mat = materialId(wallMat, dict_);
    const double zeroVel[3] = {0, 0, 0};

    const wordList extraWalls
    (
        dict_.getOrDefault<wordList>("wallPatches", wordList())
    );

    // decomposed: every processor gets the walls of all (a particle near a
    // processor boundary may touch a wall face of the neighbour)
    for (const polyPatch& pp : mesh_.boundaryMesh())
    {
        if (isA<processorPolyPatch>(pp)) continue;
        if (!returnReduce(pp.size(), sumOp<label>())) continue;

        if (isA<emptyPolyPatch>(pp))
        {
            // one plane per distinct face plane (front and back of 2-D meshes)
            const List<vector> nAll
            (
                joinAll(vectorField(pp.faceAreas()/mag(pp.faceAreas())))
            );
            const List<point> cAll(joinAll(pp.faceCentres()));
            List<vector> ns;
            List<point> ps;
            forAll(nAll, i)
            {
                const vector& n = nAll[i];
                const point& c = cAll[i];
                bool known = false;
                forAll(ns, k)
                {
                    if ((ns[k] & n) > 1 - 1e-6 && mag((c - ps[k]) & n) < 1e-9)
                    {
                        known = true;
                        break;
                    }
                }
                if (!known)
                {
                    ns.append(n);
                    ps.append(c);
                }
            }
            forAll(ns, k)
            {
                // DEM plane normal points into the domain
                const vector nIn = -ns[k];
                int id;
                world_.check
                (
                    dem_world_add_plane
                    (
                        world_, ps[k].cdata(), nIn.cdata(), mat, zeroVel, &id
                    ),
                    "dem_world_add_plane"
                );
                Info<< "demCoupling: empty patch " << pp.name()
                    << " -> DEM plane at " << ps[k] << " normal " << nIn << endl;
            }
        }
        else if (isA<wallPolyPatch>(pp) || extraWalls.found(pp.name()))
        {
            // fan triangulation from the first vertex; faces where that
            // gives a degenerate triangle (collinear points, as on the
            // boundary of polyDualMesh meshes) are fanned about their centre
            // instead, skipping degenerate triangles
            const pointField& lp = pp.localPoints();
            const faceList& lf = pp.localFaces();
            DynamicList<double> verts(3*lp.size());
            for (const point& x : lp)
            {
                verts.append(x.x()); verts.append(x.y()); verts.append(x.z());
            }
            DynamicList<int> tris;
            auto triArea = [&](const point& a, const point& b, const point& c)
            {
                return 0.5*mag((b - a) ^ (c - a));
            };
            forAll(lf, facei)
            {
                const face& f = lf[facei];
                const scalar fArea = f.mag(lp);
                bool degenerate = false;
                for (label k = 1; k + 1 < f.size(); ++k)
                {
                    if (triArea(lp[f[0]], lp[f[k]], lp[f[k+1]]) <= 1e-10*fArea)
                    {
                        degenerate = true;
                    }
                }
                if (!degenerate)
                {
                    for (label k = 1; k + 1 < f.size(); ++k)
                    {
                        tris.append(f[0]); tris.append(f[k]); tris.append(f[k+1]);
                    }
                    continue;
                }
                const point c = f.centre(lp);
                const int ci = int(verts.size()/3);
                verts.append(c.x()); verts.append(c.y()); verts.append(c.z());
                forAll(f, k)
                {
                    const label a = f[k], b = f.nextLabel(k);
                    if (triArea(c, lp[a], lp[b]) > 1e-10*fArea)
                    {
                        tris.append(ci); tris.append(int(a)); tris.append(int(b));
                    }
                }
            }
            if (Pstream::parRun())
            {
                // vertex indices of each processor shifted by the vertices
                // of the processors before it
                labelList nv(Pstream::nProcs(), 0);
                nv[Pstream::myProcNo()] = verts.size()/3;
                Pstream::gatherList(nv);
                Pstream::scatterList(nv);
                label shift = 0;
                for (label r = 0; r < Pstream::myProcNo(); ++r) shift += nv[r];
                for (int& t : tris) t += int(shift);
                verts = joinAll(verts);
                tris = joinAll(tris);
            }
            int id;
            world_.check
            (
                dem_world_add_trimesh
                (
                    world_, verts.size()/3, verts.cdata(), tris.size()/3,
                    tris.cdata(), mat, zeroVel, &id
                ),
                "dem_world_add_trimesh"
            );
            Info<< "demCoupling: wall patch " << pp.name() << " -> DEM wall of "
                << tris.size()/3 << " triangles" << endl;
        }
    }
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
    lostPerPatch_.setSize(bm.size(), 0);

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


// * * * * * * * * * * * * * * Per-step work  * * * * * * * * * * * * * * * //

Foam::label Foam::demCoupling::subSteps(const scalar dt) const
{
    const label n = label(dt/demDt_ + 0.5);
    if (n < 1 || mag(n*demDt_ - dt) > 1e-6*dt)
    {
        FatalIOErrorInFunction(dict_.subDict("dem"))
            << "constant/demProperties: keyword dem/timeStep value "
            << demDt_ << ": the fluid time step deltaT " << dt
            << " s of system/controlDict is " << dt/demDt_ << " times it;"
            << " allowed: deltaT a whole multiple (>= 1) of dem/timeStep"
            << exit(FatalIOError);
    }
    return n;
}


Foam::label Foam::demCoupling::lostTotal() const
{
    return returnReduce(lostUnknown_ + sum(lostPerPatch_), sumOp<label>());
}


void Foam::demCoupling::locateAll()
{
    dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);

    DynamicList<label> leaving;
    DynamicList<label> leavingFace;

    for (label i = 0; i < n; ++i)
    {
        label& host = idSlot(hostById_, a.id[i]);
        label exitFace = -1;
        const label c = locator_.locate(wrapped(a, i), host, exitFace);
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
    boolList taken(leaving.size(), false);
    labelList exitPatch(leaving.size(), -1);
    if (Pstream::parRun())
    {
        migrate(leaving, leavingFace, taken, exitPatch);
        a = world_.arrays();
    }

    // remove from the highest index down (removal swaps with the last)
    label nOut = 0, nLost = 0;
    for (label k = leaving.size() - 1; k >= 0; --k)
    {
        if (taken[k])
        {
            world_.check
            (
                dem_world_remove_particle(world_, size_t(leaving[k]), -1),
                "dem_world_remove_particle"
            );
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
            if (patchi >= 0) ++lostPerPatch_[patchi]; else ++lostUnknown_;
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
        world_.check
        (
            dem_world_remove_particle
            (
                world_, size_t(leaving[k]), o >= 0 ? outletIds_[o] : -1
            ),
            "dem_world_remove_particle"
        );
    }
    reduce(nOut, sumOp<label>());
    reduce(nLost, sumOp<label>());
    if (nOut + nLost > 0)
    {
        Info<< "demCoupling: " << nOut << " particles left through outlets, "
            << nLost << " lost" << endl;
    }
    const label lost = nLost ? lostTotal() : 0;
    if (nLost && lost > maxLost_ && failure_.empty())
    {
        OStringStream os;
        os  << lost << " particles lost in total (left the mesh through"
            << " patches that are not in outletPatches, see the warnings"
            << " above); constant/demProperties allows maxLostParticles "
            << maxLost_ << ". Make the patch an outlet (outletPatches), fix"
            << " the walls, lower the time steps, or raise maxLostParticles";
        failure_ = os.str();
    }
    if (nOut > 0)
    {
        writeRemovedRecords();
    }

    a = world_.arrays();
    host_.setSize(label(a.n_owned));
    forAll(host_, i)
    {
        host_[i] = hostById_[a.id[i]];
    }
}


void Foam::demCoupling::writeRemovedRecords()
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


void Foam::demCoupling::computeWeights()
{
    dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);
    wStart_.setSize(n + 1);
    wCells_.clear();
    wValues_.clear();
    // decomposed: the parts in other processors' cells, by particle
    DynamicList<remoteSample> remote;
    DynamicList<label> remoteOwner;
    for (label i = 0; i < n; ++i)
    {
        wStart_[i] = wCells_.size();
        voidage_->addWeights
        (
            wrapped(a, i), a.radius[i], host_[i], wCells_, wValues_, remote
        );
        while (remoteOwner.size() < remote.size())
        {
            remoteOwner.append(i);
        }
    }
    wStart_[n] = wCells_.size();
    resolveRemote(remoteOwner, remote);
}


void Foam::demCoupling::computeVoidage()
{
    dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);
    const scalarField& V = mesh_.V();

    // insertion ramp: a particle inserted at t0 counts with the weight
    // (t - t0)/rampTime_ until rampTime_ has passed, so that the fluid
    // sees its volume arrive over rampTime_ instead of in one step
    const scalar tNow = mesh_.time().value();
    for (auto it = rampStart_.begin(); it != rampStart_.end(); )
    {
        if (tNow - it->second >= rampTime_) it = rampStart_.erase(it);
        else ++it;
    }
    voidageTime_ = tNow;

    scalarField solid(mesh_.nCells(), 0);
    vectorField mom(mesh_.nCells(), Zero);
    const label nHalo = haloStart_.last();
    scalarField solidHalo(nHalo, 0);
    vectorField momHalo(nHalo, Zero);
    solidVolumeParticles_ = 0;
    solidVolumeRamp_ = 0;
    for (label i = 0; i < n; ++i)
    {
        const scalar V1 = 4.0/3.0*pi*pow3(a.radius[i]);
        const scalar Vp = rampWeight(a.id[i], tNow)*V1;
        solidVolumeParticles_ += V1;
        solidVolumeRamp_ += V1 - Vp;
        deposit(i, Vp, solid, solidHalo);
        deposit(i, Vp*vector(toVec(a.v, i)), mom, momHalo);
    }
    haloAdd(solid, solidHalo);
    haloAdd(mom, momHalo);
    solidVolumeMesh_ = gSum(solid);
    reduce(solidVolumeParticles_, sumOp<scalar>());
    reduce(solidVolumeRamp_, sumOp<scalar>());

    epsRaw_.primitiveFieldRef() = 1.0 - solid/V;
    eps_.primitiveFieldRef() = max(epsRaw_.primitiveField(), epsMin_);
    eps_.correctBoundaryConditions();

    forAll(mom, c)
    {
        Up_[c] = solid[c] > 0 ? mom[c]/solid[c] : vector::zero;
    }
    Up_.correctBoundaryConditions();

    const dimensionedScalar one("one", dimless, 1.0);
    if (formulation_->pressureTimesVoidage()) pCoeff_ = eps_; else pCoeff_ = one;
    if (formulation_->viscousTimesVoidage()) tauCoeff_ = eps_; else tauCoeff_ = one;
}


Foam::scalar Foam::demCoupling::rampWeight
(
    const int64_t id,
    const scalar t
) const
{
    if (rampStart_.empty())
    {
        return 1;
    }
    const auto it = rampStart_.find(id);
    return
        it == rampStart_.end()
      ? 1
      : min(max(t - it->second, 0)/rampTime_, 1);
}


void Foam::demCoupling::startRamp(const DynamicList<int64_t>& inserted)
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
            rampStart_[id] = t0;
        }
    }
}


bool Foam::demCoupling::writeStep() const
{
    const Time& t = mesh_.time();
    return
        t.writeTime()
     || t.timeIndex() == writeRequested_
     || t.value() >= t.endTime().value() - 0.5*t.deltaTValue();
}


void Foam::demCoupling::evolve
(
    const volVectorField& U,
    const volScalarField& p,
    const volVectorField& divTauKin,
    const volScalarField& nu
)
{
    const auto tEvolve0 = std::chrono::steady_clock::now();
    const scalar tDem0 = tDem_;
    const scalar tComm0 = tComm_;

    const scalar dt = mesh_.time().deltaTValue();
    const label nDem = subSteps(dt);
    nSubCycles_ = nDem;

    // 1-2: positions at the start of the step (located by the last call).
    // Per-particle data below are indexed by the start index s; the core
    // may re-sort its storage inside dem_world_step, so the current index
    // is mapped back to s through the particle id.
    dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);

    const volVectorField gradPKin(fvc::grad(p));
    const vectorField& Uc = U.primitiveField();
    const vectorField& gradPc = gradPKin.primitiveField();
    const vectorField& divTc = divTauKin.primitiveField();
    const scalarField& epsc = eps_.primitiveField();
    const scalarField& nuc = nu.primitiveField();
    const scalarField& V = mesh_.V();
    const couplingFormulation& form = formulation_();

    // optional forces f'' (extraForces/): fluid vorticity and acceleration
    // at the particles, the explicit impulse and the added mass per force
    const label nExtra = extraForces_.size();
    vectorField vortCell, DuDtCell;
    extraForceFields(U, vortCell, DuDtCell);
    List<vector> vortP(nExtra ? n : 0), DuDtP(nExtra ? n : 0);
    List<vector> vStart(nExtra ? n : 0);
    List<scalarField> maK(nExtra, scalarField(n, 0));
    List<List<vector>> impK(nExtra, List<vector>(n, Zero));

    List<vector> uF(n), fGP(n), fExch(n), fPart(n), divTauP(n);
    scalarField epsP(n), muP(n), dragFac(n), Ksum(n, 0);

    // id -> start index
    for (label s = 0; s < n; ++s)
    {
        idSlot(startById_, a.id[s]) = s;
    }
    auto startIndex = [&](const int64_t id) -> label
    {
        if (id < 0 || id >= startById_.size()) return -1;
        const label s = startById_[id];
        return (s >= 0 && s < n && a.id[s] == id) ? s : -1;
    };
    // ids by start index (a.id may be reordered later)
    List<int64_t> idStart(n);
    for (label s = 0; s < n; ++s) idStart[s] = a.id[s];
    auto startOf = [&](const int64_t id) -> label
    {
        if (id < 0 || id >= startById_.size()) return -1;
        const label s = startById_[id];
        return (s >= 0 && s < n && idStart[s] == id) ? s : -1;
    };
    (void)startIndex;

    // cell-mean particle velocity (for the cell-mean drag variant)
    const vectorField& vsCell = Up_.primitiveField();

    // the particle volume the fluid sees (the voidage of this step; less
    // while an insertion ramp runs): the forces that scale with it, and
    // their share of the exchange, use the same volume, so that the
    // momentum exchange stays exact
    scalarField VpS(n);
    for (label s = 0; s < n; ++s)
    {
        VpS[s] =
            rampWeight(a.id[s], voidageTime_)*4.0/3.0*pi*pow3(a.radius[s]);
    }

    // the same in the other processors' cells of the weights (halo)
    const List<vector> UcH(haloGet(Uc));
    const List<vector> gradPcH(haloGet(gradPc));
    const List<vector> divTcH(haloGet(divTc));
    const List<scalar> epscH(haloGet(epsc));
    const List<scalar> nucH(haloGet(nuc));
    const List<vector> vortH(nExtra ? haloGet(vortCell) : List<vector>());
    const List<vector> DuDtH(nExtra ? haloGet(DuDtCell) : List<vector>());
    const List<vector> vsCellH
    (
        cellMeanDrag_ ? haloGet(vsCell) : List<vector>()
    );

    for (label s = 0; s < n; ++s)
    {
        const scalar Vp = VpS[s];
        uF[s] = interp(s, Uc, UcH);
        const vector gp = rhof_*interp(s, gradPc, gradPcH) + G_;
        const vector dtau = rhof_*interp(s, divTc, divTcH);
        epsP[s] = interp(s, epsc, epscH);
        muP[s] = rhof_*interp(s, nuc, nucH);
        dragFac[s] = form.dragFactor(epsP[s]);
        fGP[s] = -Vp*gp;
        divTauP[s] = Vp*dtau;
        form.explicitForces(Vp, gp, dtau, rhof_, g_, fPart[s], fExch[s]);
        setVec(a.force_ext, s, fPart[s]);
        setVec(a.torque_ext, s, vector::zero);
        setVec(a.drag_impulse, s, vector::zero);
        scalar ma = 0;
        if (nExtra)
        {
            vortP[s] = interp(s, vortCell, vortH);
            DuDtP[s] = interp(s, DuDtCell, DuDtH);
            vStart[s] = toVec(a.v, s);
            forAll(extraForces_, k)
            {
                maK[k][s] = dragFac[s]
                   *extraForces_[k].addedMass(2*a.radius[s], rhof_, epsP[s]);
                ma += maK[k][s];
            }
        }
        a.added_mass[s] = ma;
    }

    // 3: DEM sub-steps with drag re-evaluated every chunk
    const label chunk =
        dragUpdateInterval_ > 0 ? min(dragUpdateInterval_, nDem) : nDem;

    label done = 0;
    while (done < nDem)
    {
        const label m = min(chunk, nDem - done);
        a = world_.arrays();
        for (label j = 0; j < label(a.n_owned); ++j)
        {
            const label s = startOf(a.id[j]);
            if (s < 0)
            {
                // inserted during this fluid step: no drag until located
                a.drag_coeff[j] = 0;
                setVec(a.fluid_velocity, j, vector::zero);
                continue;
            }
            const vector v(toVec(a.v, j));
            vector slip = uF[s] - v;
            vector uf = uF[s];
            if (cellMeanDrag_)
            {
                // [S] method 1: drag from the cell-mean particle velocity
                const vector vs = interp(s, vsCell, vsCellH);
                slip = uF[s] - vs;
                uf = uF[s] - vs + v;
            }
            const scalar K =
                drag_->K(2*a.radius[j], epsP[s], mag(slip), rhof_, muP[s])
               *dragFac[s];
            a.drag_coeff[j] = K;
            setVec(a.fluid_velocity, j, uf);
            Ksum[s] += K*m/nDem;
            if (nExtra)
            {
                // explicit extra forces (times the set's factor), held
                // over this drag update
                extraForce::particleState st;
                st.d = 2*a.radius[j];
                st.v = v;
                st.omega = toVec(a.omega, j);
                st.u = uF[s];
                st.vorticity = vortP[s];
                st.DuDt = DuDtP[s];
                st.rhof = rhof_;
                st.muf = muP[s];
                st.eps = epsP[s];
                vector fx(Zero);
                forAll(extraForces_, k)
                {
                    const vector f = dragFac[s]*extraForces_[k].force(st);
                    impK[k][s] += f*(m*demDt_);
                    fx += f;
                }
                setVec(a.force_ext, j, fPart[s] + fx);
            }
            if (frozen_)
            {
                // fixed bed: no DEM motion; the exchange is the drag at v
                const vector imp =
                    toVec(a.drag_impulse, j) + K*(uf - v)*m*demDt_;
                setVec(a.drag_impulse, j, imp);
            }
        }
        if (!frozen_)
        {
            if (injectParticleNaN_ == nSteps_ + 1 && done == 0 && a.n_owned)
            {
                a.v[0] = std::numeric_limits<double>::quiet_NaN();
            }
            const auto t0 = std::chrono::steady_clock::now();
            const scalar tCommStep0 = tComm_;
            const dem_status st =
                Pstream::parRun() ? stepDecomposed(m) : world_.tryStep(m);
            tDem_ += std::chrono::duration<scalar>
            (
                std::chrono::steady_clock::now() - t0
            ).count()
              - (tComm_ - tCommStep0);
            if (st != DEM_OK)
            {
                // (decomposed: set by stepDecomposed, naming the processor)
                if (failure_.empty())
                {
                    failure_ = std::string("DEM core: ")
                      + dem_status_string(st) + ": " + world_.lastError();
                }
                ++nSteps_;
                return;
            }
        }
        done += m;
    }

    // 4: exchange, eta, balance (start-of-step weights)
    a = world_.arrays();
    const label nEnd = label(a.n_owned);

    vectorField Fc(mesh_.nCells(), Zero);
    scalarField Kcell(mesh_.nCells(), 0);
    vector sumParticle(Zero);
    vector sumDrag(Zero), sumGradP(Zero), sumTau(Zero);
    scalar sumMagParticle = 0;
    scalar etaSum = 0;
    label etaN = 0, etaAll = 0;
    scalarField etaCell(mesh_.nCells(), 0);
    scalarField wCell(mesh_.nCells(), 0);
    const label nHalo = haloStart_.last();
    vectorField FcHalo(nHalo, Zero);
    scalarField KcellHalo(nHalo, 0), etaCellHalo(nHalo, 0), wCellHalo(nHalo, 0);

    outIds_.setSize(nEnd);
    fDrag_.setSize(nEnd);
    fGradP_.setSize(nEnd);
    etaP_.setSize(nEnd);
    coordP_.setSize(nEnd);
    if (frozen_ || !writeStep())
    {
        // not counted: a fixed bed never evaluates contacts, and only
        // write steps write them (a count costs about 0.1 DEM step; a
        // last good state after a failure has them if its step was a
        // write step)
        coordP_ = -1;
    }
    else if (nEnd)
    {
        // now, while the sub-steps' neighbour list is valid (a migration
        // clears it: the core then reports the count as unknown)
        world_.check
        (
            dem_world_particle_contacts(world_, coordP_.data(), nullptr),
            "dem_world_particle_contacts"
        );
    }
    fExtra_.setSize(nExtra);
    forAll(fExtra_, k)
    {
        fExtra_[k].setSize(nEnd);
    }
    label nSeen = 0;
    DynamicList<int64_t> inserted;

    for (label j = 0; j < nEnd; ++j)
    {
        outIds_[j] = a.id[j];
        const label s = startOf(a.id[j]);
        if (s < 0)
        {
            inserted.append(a.id[j]);
            fDrag_[j] = Zero; fGradP_[j] = Zero; etaP_[j] = 0;
            forAll(fExtra_, k) fExtra_[k][j] = Zero;
            continue;
        }
        ++nSeen;
        const scalar Vp = VpS[s];
        const vector dragRate = toVec(a.drag_impulse, j)/dt;
        // extra forces: explicit impulse plus the implicit added-mass part
        // -m_a (v_end - v_start) (exactly what the core applied)
        vector extraRate(Zero);
        forAll(extraForces_, k)
        {
            fExtra_[k][j] =
                (impK[k][s] - maK[k][s]*(toVec(a.v, j) - vStart[s]))/dt;
            extraRate += fExtra_[k][j];
        }
        const vector fpf = dragRate + fPart[s] + extraRate;
        sumParticle += fpf;
        sumDrag += dragRate;
        sumGradP += fGP[s];
        sumTau += divTauP[s];
        sumMagParticle += mag(fpf);
        const vector exch = dragRate + fExch[s] + extraRate;

        // [Z]'s f_d + f'' of this particle (before the set's factor)
        const vector fd = (dragRate + extraRate)/dragFac[s];
        fDrag_[j] = dragRate;
        fGradP_[j] = fGP[s];

        // applicability index [Z 2.25-2.27], docs/theory.md section 6
        const scalar e = epsP[s];
        const vector fResid =
            fGP[s] - fd*(1 - e)/e + divTauP[s] + rhof_*Vp*g_;
        const vector fTotal = fd/e - rhof_*Vp*g_ + fResid;
        etaP_[j] = 100*mag(fResid)/max(mag(fTotal), VSMALL);
        // the bed average takes the particles that the fluid carries in
        // part at least: where its total force is below a tenth of the
        // weight (a bed at rest, no flow yet) the ratio is noise
        // (docs/theory.md section 6)
        if (mag(fTotal) >= etaMinForceRatio*a.density[j]*Vp*mag(g_))
        {
            etaSum += etaP_[j];
            ++etaN;
        }
        ++etaAll;

        deposit(s, exch, Fc, FcHalo);
        deposit(s, Ksum[s], Kcell, KcellHalo);
        deposit(s, etaP_[j], etaCell, etaCellHalo);
        deposit(s, scalar(1), wCell, wCellHalo);
    }
    haloAdd(Fc, FcHalo);
    haloAdd(Kcell, KcellHalo);
    haloAdd(etaCell, etaCellHalo);
    haloAdd(wCell, wCellHalo);
    if (Pstream::parRun())
    {
        reduce(sumParticle, sumOp<vector>());
        reduce(sumDrag, sumOp<vector>());
        reduce(sumGradP, sumOp<vector>());
        reduce(sumTau, sumOp<vector>());
        reduce(sumMagParticle, sumOp<scalar>());
        reduce(etaSum, sumOp<scalar>());
        reduce(etaN, sumOp<label>());
        reduce(etaAll, sumOp<label>());
    }
    if (nSeen != n)
    {
        FatalErrorInFunction
            << n - nSeen << " particles were removed inside dem_world_step; "
            << "demFoam books outlets itself and expects none"
            << exit(FatalError);
    }
    bedEta_ = {etaN ? etaSum/etaN : 0, etaN, etaAll};

    // fluid momentum source S = -F + (1 - c_p) grad p - (1 - c_tau) div tau,
    // 1 - c from the solid fraction of the same weights (exact, unclipped)
    const bool pEps = form.pressureTimesVoidage();
    const bool tauEps = form.viscousTimesVoidage();
    vector sumFluid(Zero);
    forAll(Fc, c)
    {
        F_[c] = Fc[c]/V[c];
        Kc_[c] = Kcell[c]/V[c];
        vector S = -F_[c];
        if (pEps)
        {
            S += (1 - epsRaw_[c])*(rhof_*gradPc[c] + G_);
        }
        if (tauEps)
        {
            S -= (1 - epsRaw_[c])*rhof_*divTc[c];
        }
        source_[c] = S;
        sumFluid += S*V[c];
        eta_[c] = wCell[c] > 0 ? etaCell[c]/wCell[c] : 0;
    }
    reduce(sumFluid, sumOp<vector>());
    sumDrag_ = sumDrag;
    sumGradP_ = sumGradP;
    sumTau_ = sumTau;
    balanceFluidVec_ = sumFluid;
    balanceParticleVec_ = sumParticle;
    balanceFluid_ = mag(sumFluid + sumParticle);
    balanceParticle_ = max(sumMagParticle, VSMALL);
    Ucoup_.primitiveFieldRef() = Uc;

    // 5: new positions -> voidage for the fluid step
    startRamp(inserted);
    locateAll();
    computeWeights();
    computeVoidage();

    bed_.sample(world_.arrays(), eps_);
    bed_.append();

    ++nSteps_;
    tCoupling_ +=
        std::chrono::duration<scalar>
        (
            std::chrono::steady_clock::now() - tEvolve0
        ).count()
      - (tDem_ - tDem0) - (tComm_ - tComm0);

    report(false);
}


void Foam::demCoupling::extraForceFields
(
    const volVectorField& U,
    vectorField& vorticity,
    vectorField& DuDt
)
{
    if (extraForces_.empty())
    {
        return;
    }
    bool needW = false, needA = false;
    forAll(extraForces_, k)
    {
        needW = needW || extraForces_[k].needsVorticity();
        needA = needA || extraForces_[k].needsFluidAcceleration();
    }
    vorticity.setSize(mesh_.nCells(), Zero);
    DuDt.setSize(mesh_.nCells(), Zero);
    if (needW)
    {
        vorticity = fvc::curl(U)().primitiveField();
    }
    if (needA)
    {
        // Du/Dt = du/dt + (u.grad)u; du/dt from U of this and the last
        // step (U is the field of the end of the previous step; Uprev_ the
        // one of the step before, kept with its time index; the step
        // between them is deltaT0, which a restart reads back exactly)
        DuDt = (U & fvc::grad(U))().primitiveField();
        const label index = mesh_.time().timeIndex();
        if (Uprev_.size() == mesh_.nCells() && index == indexUprev_ + 1)
        {
            DuDt += (U.primitiveField() - Uprev_)/mesh_.time().deltaT0Value();
        }
        Uprev_ = U.primitiveField();
        indexUprev_ = index;
    }
}


Foam::tmp<Foam::volScalarField> Foam::demCoupling::Kkin() const
{
    tmp<volScalarField> tK
    (
        new volScalarField
        (
            IOobject("Kkin", mesh_.time().timeName(), mesh_),
            mesh_,
            dimensionedScalar(dimless/dimTime, Zero),
            "zeroGradient"
        )
    );
    tK.ref().primitiveFieldRef() = Kc_.primitiveField()/rhof_;
    tK.ref().correctBoundaryConditions();
    return tK;
}


Foam::tmp<Foam::volVectorField> Foam::demCoupling::Skin() const
{
    tmp<volVectorField> tS
    (
        new volVectorField
        (
            IOobject("Skin", mesh_.time().timeName(), mesh_),
            mesh_,
            dimensionedVector(dimVelocity/dimTime, Zero),
            "zeroGradient"
        )
    );
    tS.ref().primitiveFieldRef() =
        (Kc_.primitiveField()*Ucoup_.primitiveField() - F_.primitiveField())
       /rhof_;
    tS.ref().correctBoundaryConditions();
    return tS;
}


void Foam::demCoupling::updateDriving(const volVectorField& U)
{
    if (!driving_) return;

    // volume mean of the superficial velocity eps U
    const scalarField& V = mesh_.V();
    const vector Us =
        gSum(eps_.primitiveField()*U.primitiveField()*V)/gSum(V);
    const scalar dt = mesh_.time().deltaTValue();

    // the driving force -G per volume moves by relaxation x the force that
    // would close the gap in one step; only along the target's components
    vector dG = -drivingRelax_*rhof_*(UsTarget_ - Us)/dt;
    for (direction k = 0; k < 3; ++k)
    {
        if (mag(UsTarget_[k]) < VSMALL) dG[k] = 0;
    }
    G_ += dG;

    Info<< "demCoupling: periodic driving: superficial velocity " << Us
        << " target " << UsTarget_ << ", mean pressure gradient G " << G_
        << " Pa/m" << endl;
}
