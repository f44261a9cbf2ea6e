/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    The report of a step and the progress lines of the run and of the
    settling (docs/demProperties.md, "Clean failure and progress").

\*---------------------------------------------------------------------------*/

#include "couplingDiagnostics.H"
#include "OStringStream.H"
#include <cmath>

// * * * * * * * * * * * * * * * * Helpers * * * * * * * * * * * * * * * * //

namespace
{
    std::string hms(const Foam::scalar s)
    {
        const long t = long(s + 0.5);
        char buf[32];
        std::snprintf
        (
            buf, sizeof buf, "%ld:%02ld:%02ld", t/3600, (t/60) % 60, t % 60
        );
        return buf;
    }
}


// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::couplingDiagnostics::couplingDiagnostics
(
    const fvMesh& mesh,
    demWorld& world,
    const particleLocator& locator,
    const demTools::periodicBox& box,
    const couplingState& state,
    const couplingFormulation& formulation,
    const PtrList<extraForce>& extraForces,
    const meshCloud& cloud,
    const particleMeshMap& map,
    const bedMonitor& bed,
    const vector& g,
    const dictionary& dict
)
:
    mesh_(mesh),
    world_(world),
    locator_(locator),
    box_(box),
    state_(state),
    formulation_(formulation),
    extraForces_(extraForces),
    cloud_(cloud),
    map_(map),
    bed_(bed),
    g_(g),
    contacts_(mesh, world, box, dict),
    etaWarning_(dict.getOrDefault<scalar>("etaWarning", 20.0)),
    rampTime_(dict.getOrDefault<scalar>("insertionRampTime", 0)),
    progressInterval_(dict.getOrDefault<scalar>("progressInterval", 60)),
    progressSteps_(dict.getOrDefault<label>("progressSteps", 0)),
    startTime_(mesh.time().value()),
    wallStart_(std::chrono::steady_clock::now()),
    wallLastProgress_(0),
    balance_(),
    sums_()
{}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::couplingDiagnostics::startClock()
{
    wallStart_ = std::chrono::steady_clock::now();
}


Foam::scalar Foam::couplingDiagnostics::addParticle(const particleStep& p)
{
    const vector fpf = p.drag + p.explicitF + p.extra;
    sums_.particle += fpf;
    sums_.drag += p.drag;
    sums_.gradP += p.gradP;
    sums_.tau += p.divTau;
    sums_.magParticle += mag(fpf);

    // [Z]'s f_d + f'' of this particle (before the set's factor)
    const vector fd = (p.drag + p.extra)/p.dragFactor;

    // applicability index [Z 2.25-2.27], docs/theory.md section 6
    const scalar e = p.eps;
    const vector fResid =
        p.gradP - fd*(1 - e)/e + p.divTau + p.rhoFluid*p.Vp*g_;
    const vector fTotal = fd/e - p.rhoFluid*p.Vp*g_ + fResid;
    const scalar eta = 100*mag(fResid)/max(mag(fTotal), VSMALL);
    // the bed average takes the particles that the fluid carries in
    // part at least: where its total force is below a tenth of the
    // weight (a bed at rest, no flow yet) the ratio is noise
    // (docs/theory.md section 6)
    if (mag(fTotal) >= etaMinForceRatio*p.density*p.Vp*mag(g_))
    {
        sums_.eta += eta;
        ++sums_.etaN;
    }
    ++sums_.etaAll;
    return eta;
}


Foam::couplingState::bedEtaStats Foam::couplingDiagnostics::endStep
(
    vector sumFluid
)
{
    if (Pstream::parRun())
    {
        reduce(sums_.particle, sumOp<vector>());
        reduce(sums_.drag, sumOp<vector>());
        reduce(sums_.gradP, sumOp<vector>());
        reduce(sums_.tau, sumOp<vector>());
        reduce(sums_.magParticle, sumOp<scalar>());
        reduce(sums_.eta, sumOp<scalar>());
        reduce(sums_.etaN, sumOp<label>());
        reduce(sums_.etaAll, sumOp<label>());
    }
    reduce(sumFluid, sumOp<vector>());
    balance_.sumDrag = sums_.drag;
    balance_.sumGradP = sums_.gradP;
    balance_.sumTau = sums_.tau;
    balance_.fluidVec = sumFluid;
    balance_.particleVec = sums_.particle;
    balance_.fluid = mag(sumFluid + sums_.particle);
    balance_.particle = max(sums_.magParticle, VSMALL);
    const label n = sums_.etaN;
    return {n ? sums_.eta/n : 0, n, sums_.etaAll};
}


void Foam::couplingDiagnostics::report
(
    const bool full,
    const label nSubCycles
) const
{
    // (before the first step both are 0)
    const scalar rel =
        balance_.particle > 0 ? balance_.fluid/balance_.particle : scalar(0);
    Info<< "demCoupling: particles "
        << returnReduce(label(dem_world_count(world_)), sumOp<label>())
        << ", DEM steps " << nSubCycles
        << ", momentum balance: fluid " << balance_.fluidVec
        << " particles " << balance_.particleVec
        << " relErr " << rel << endl;

    if (!full) return;

    Info<< "demCoupling: sum of particle drag " << balance_.sumDrag
        << ", of pressure-gradient forces " << balance_.sumGradP
        << ", of viscous forces " << balance_.sumTau << endl;

    // (mesh + the part still ramping in = particles)
    Info<< "demCoupling: solid volume: mesh " << solid_.mesh
        << " particles " << solid_.particles
        << " relDiff "
        << mag(solid_.mesh + solid_.ramp - solid_.particles)
          /max(solid_.particles, VSMALL);
    if (rampTime_ > 0)
    {
        Info<< " (ramping in " << solid_.ramp << ", "
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
        formulation_.assumesNoFluidAcceleration()
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


void Foam::couplingDiagnostics::settling
(
    const int64_t done,
    const int64_t nSettle,
    const std::chrono::steady_clock::time_point& start,
    scalar& wallLast
) const
{
    const scalar wall = std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - start
    ).count();
    bool due = done < nSettle && wall - wallLast >= progressInterval_;
    Pstream::scatter(due);
    if (due)
    {
        wallLast = wall;
        Info<< "progress: settling (DEM only), t = "
            << dem_world_time(world_) << " s of "
            << mesh_.time().value() << " (" << label(100*done/nSettle)
            << " % of the settling), wall " << hms(wall).c_str()
            << ", to its end ~"
            << hms(wall*(nSettle - done)/done).c_str() << endl;
    }
}


void Foam::couplingDiagnostics::progress
(
    const label nSteps,
    const bool force
)
{
    const scalar wall = std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - wallStart_
    ).count();
    bool due =
        force
     || (progressSteps_ > 0 && nSteps % progressSteps_ == 0)
     || (progressSteps_ == 0 && wall - wallLastProgress_ >= progressInterval_);
    // decomposed: the master's clock decides (the line needs all processors)
    Pstream::scatter(due);
    if (!due) return;
    wallLastProgress_ = wall;

    const Time& runTime = mesh_.time();
    const scalar t = runTime.value();
    const scalar tEnd = runTime.endTime().value();
    const scalar done = t - startTime_;
    const scalar eta =
        done > 0 ? wall*max(tEnd - t, scalar(0))/done : scalar(0);

    dem_stats st;
    world_.check(dem_world_stats(world_, &st), "dem_world_stats");
    const label nAll =
        returnReduce(label(dem_world_count(world_)), sumOp<label>());
    // (decomposed: every processor created the initial particles, the
    // master alone inserts; its count is the total)
    label nInserted = label(st.inserted);
    Pstream::scatter(nInserted);
    const scalar maxOverlap =
        returnReduce(scalar(st.max_overlap_ratio), maxOp<scalar>());
    const label lost = cloud_.lostTotal();
    const labelList& outletPatches = cloud_.outletPatches();
    List<label> outCounts(outletPatches.size());
    forAll(outletPatches, k)
    {
        scalar mass = 0;
        outCounts[k] = cloud_.outletTotal(k, mass);
    }

    const scalar tComm = returnReduce(time_.comm, maxOp<scalar>());
    const scalar total =
        max(time_.dem + time_.coupling + time_.fluid + time_.comm, VSMALL);
    // percent done, rounded down; 100 only at the last step (the time
    // summed from the steps may end a rounding error below endTime)
    const bool last = tEnd - t < 0.5*runTime.deltaTValue();
    const label percent =
        last ? 100
      : min(label(100*(t - startTime_)/max(tEnd - startTime_, VSMALL)), 99);
    OStringStream os;
    os  << "progress: t = " << t << " s of " << tEnd << " ("
        << percent << " %), wall " << hms(wall).c_str() << ", to the end ~"
        << hms(eta).c_str()
        << ", particles " << nAll
        << " (inserted " << nInserted << ", removed";
    forAll(outletPatches, k)
    {
        os  << " " << mesh_.boundaryMesh()[outletPatches[k]].name() << " "
            << outCounts[k];
    }
    if (outletPatches.empty()) os << " 0";
    os  << ", lost " << lost << ")"
        << ", max overlap " << 0.001*std::round(1e5*maxOverlap)
        << " % of d"
        << ", time DEM " << label(100*time_.dem/total + 0.5)
        << " % coupling " << label(100*time_.coupling/total + 0.5)
        << " % fluid " << label(100*time_.fluid/total + 0.5) << " %";
    if (Pstream::parRun())
    {
        os  << " communication " << label(100*time_.comm/total + 0.5)
            << " % (most on one processor " << label(100*tComm/total + 0.5)
            << " %), particle volume across processors "
            << int64_t(returnReduce(map_.haloParticleSteps(), sumOp<scalar>()))
            << " particle-steps";
    }
    Info<< os.str().c_str() << endl;
}


// ************************************************************************* //
