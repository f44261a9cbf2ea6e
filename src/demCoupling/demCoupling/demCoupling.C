/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "timeCompletion.H"
#include "dictionaryFileCheck.H"
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
    cellMeanDrag_(false),
    localDragReaction_(false),
    frozen_(dict_.getOrDefault<bool>("frozen", false)),
    epsMin_(dict_.getOrDefault<scalar>("epsMin", 0.1)),
    epsRelaxTime_(dict_.getOrDefault<scalar>("voidageRelaxationTime", 0)),
    smoothing_(mesh, dict_),
    demDt_(0),
    fitToFluidStep_(false),
    dragUpdateInterval_(0),
    nSubCycles_(0),
    insertion_(mesh, world_, locator_, dict_, materialIds_, state_),
    diag_
    (
        mesh, world_, locator_, box_, state_, formulation_(), extraForces_,
        cloud_, map_, bed_, g_, dict_
    ),
    ghosts_
    (
        mesh, world_, box_.periodic, box_.lo, box_.hi, insertion_.inletBoxes(),
        insertion_.inletRadius(), diag_.time().comm
    ),
    decomposition_(mesh, world_, locator_, box_, ghosts_, diag_.time().comm),
    cloud_
    (
        mesh, world_, locator_, box_, decomposition_, state_,
        dict_.getOrDefault<label>("maxLostParticles", 0)
    ),
    driving_(dict_.found("periodicDriving")),
    UsTarget_(Zero),
    drivingRelax_(0.2),
    map_(mesh, locator_, diag_.time().comm),
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
    KUcoup_(fieldIO(mesh, "KUcoupling", false), mesh,
           dimensionedVector(dimForce/dimVolume, Zero)),
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
    snapBuf_ = nullptr;
    snapSize_ = 0;
    snapCapacity_ = 0;
    nSteps_ = 0;
    writeRequested_ = -1;
    injectParticleNaN_ = injectedStep("particleNaN");

    // decomposed: the mesh's tet base points are computed with
    // communication on first use (findCell); here, on every processor, so
    // that a later findCell on one processor alone does not wait for others
    if (Pstream::parRun())
    {
        (void)mesh_.tetBasePtIs();
    }

    // a keyword of two values: true for the second; anything else stops
    const auto secondOf = [this](const word& key, const word& first, const word& second)
    {
        const word w(dict_.getOrDefault<word>(key, first));
        if (w != first && w != second)
        {
            FatalIOErrorInFunction(dict_)
                << key << " " << w << " in " << dict_.name()
                << ": allowed " << first << " (default) or " << second
                << exit(FatalIOError);
        }
        return w == second;
    };
    localDragReaction_ = secondOf("dragReaction", "exact", "local");
    cellMeanDrag_ = secondOf("dragScheme", "perParticle", "cellMean");
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
        state_.G = dd.getOrDefault<vector>("initialGradient", Zero);
    }

    const dictionary& demDict = dict_.subDict("dem");
    demDt_ = demDict.get<scalar>("timeStep");
    fitToFluidStep_ = demDict.getOrDefault<bool>("fitToFluidStep", false);
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
    cloud_.addOutlets(dict_);
    insertion_.addInlets();

    if (!restoreState(mesh.time().timePath()/"uniform", initial))
    {
        // decomposed: every processor draws the whole set but stores only
        // the particles near its mesh (keepNear), checks those, keeps the
        // ones in its cells and settles them (settle())
        decomposition_.keepNear(insertion_.initialDiameterMax());
        insertion_.addInitialParticles();
        decomposition_.keepNearEnd();
        checkInitialState();
        if (checkOnly) return;
        decomposition_.distributeByCell();
        if (nSettle > 0)
        {
            Info<< "demCoupling: settling " << nSettle << " DEM steps ("
                << tSettle << " s, DEM time " << t0 - nSettle*demDt_
                << " to " << t0 << ") without fluid"
                << (Pstream::parRun() ? " (decomposed)" : "")
                << endl;
            settle(nSettle);
        }
        // exactly the fluid's (the sum of the steps may differ by round-off)
        world_.check(dem_world_set_time(world_, t0), "dem_world_set_time");
    }
    else
    {
        // the restored state carries the configuration it was written with;
        // dt, gravity and the limits of constant/demProperties apply from
        // here (contact law, skin and domain stay the state's)
        world_.check
        (
            dem_world_configure_run(world_, &config_),
            "dem_world_configure_run (after restoring the DEM state)"
        );
    }
    if (mag(dem_world_time(world_) - t0) > 0.5*demDt_)
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
    cloud_.locate(failure_);
    computeWeights();
    computeVoidage();
    eps_.oldTime() == eps_;
    startRelaxedVoidage();
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
        << ", solid volume " << diag_.solid().particles << " m3" << nl << endl;
    Info<< "demCoupling: drag reaction "
        << (localDragReaction_ ? "local" : "exact") << nl << endl;

    // the progress estimate counts the coupled steps only (not the
    // settling and set-up before them)
    diag_.startClock();
}


// * * * * * * * * * * * * * * Per-step work  * * * * * * * * * * * * * * * //

Foam::label Foam::demCoupling::subSteps(const scalar dt) const
{
    if (fitToFluidStep_)
    {
        // the fewest equal steps not longer than demDt_ (a step within
        // 1e-9 of a multiple takes that multiple)
        return max(label(1), label(std::ceil(dt/demDt_*(1 - 1e-9))));
    }
    const label n = label(dt/demDt_ + 0.5);
    if (n < 1 || mag(n*demDt_ - dt) > 1e-6*dt)
    {
        FatalIOErrorInFunction(dict_.subDict("dem"))
            << "constant/demProperties: keyword dem/timeStep value "
            << demDt_ << ": the fluid time step deltaT " << dt
            << " s of system/controlDict is " << dt/demDt_ << " times it;"
            << " allowed: deltaT a whole multiple (>= 1) of dem/timeStep,"
            << " or dem/fitToFluidStep yes (equal DEM steps not longer than"
            << " timeStep)"
            << exit(FatalIOError);
    }
    return n;
}


bool Foam::demCoupling::writeStep() const
{
    const Time& t = mesh_.time();
    return
        t.writeTime()
     || t.timeIndex() == writeRequested_
     || t.value() >= t.endTime().value() - 0.5*t.deltaTValue();
}


namespace
{
    // A cell field of the particle source (zero-gradient patches: the half
    // cell at a boundary holds the cell's particles)
    template<class Type>
    Foam::tmp<Foam::GeometricField<Type, Foam::fvPatchField, Foam::volMesh>>
    sourceField
    (
        const Foam::fvMesh& mesh,
        const Foam::word& name,
        const Foam::dimensionSet& dims,
        const Foam::tmp<Foam::Field<Type>>& values
    )
    {
        using namespace Foam;
        tmp<GeometricField<Type, fvPatchField, volMesh>> tf
        (
            new GeometricField<Type, fvPatchField, volMesh>
            (
                IOobject(name, mesh.time().timeName(), mesh),
                mesh,
                dimensioned<Type>(dims, Zero),
                "zeroGradient"
            )
        );
        tf.ref().primitiveFieldRef() = values;
        tf.ref().correctBoundaryConditions();
        return tf;
    }
}


Foam::tmp<Foam::volScalarField> Foam::demCoupling::Kc() const
{
    return sourceField<scalar>
    (
        mesh_, "Kc", dimDensity/dimTime, tmp<scalarField>(Kc_.primitiveField())
    );
}


Foam::tmp<Foam::vectorField> Foam::demCoupling::dragMoment() const
{
    // exact: K_c U_coupling, so that the fluid gets the particles' drag
    // forces plus K_c (U - U_coupling); local: sum of w K u_f, so that it
    // gets sum of w K (U_c - v) (docs/theory.md section 2.2)
    if (localDragReaction_)
    {
        return tmp<vectorField>(KUcoup_.primitiveField());  // a reference, no copy
    }
    return Kc_.primitiveField()*Ucoup_.primitiveField();
}


Foam::tmp<Foam::volVectorField> Foam::demCoupling::Sc() const
{
    return sourceField<vector>
    (
        mesh_, "Sc", dimForce/dimVolume,
        dragMoment() - F_.primitiveField()
    );
}


// (the kinematic ones: the same divided by rhof)
Foam::tmp<Foam::volScalarField> Foam::demCoupling::Kkin() const
{
    return sourceField<scalar>
    (
        mesh_, "Kkin", dimless/dimTime, Kc_.primitiveField()/rhof_
    );
}


Foam::tmp<Foam::volVectorField> Foam::demCoupling::Skin() const
{
    return sourceField<vector>
    (
        mesh_, "Skin", dimVelocity/dimTime,
        (dragMoment() - F_.primitiveField())
       /rhof_
    );
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
    state_.G += dG;

    Info<< "demCoupling: periodic driving: superficial velocity " << Us
        << " target " << UsTarget_ << ", mean pressure gradient G " << state_.G
        << " Pa/m" << endl;
}
