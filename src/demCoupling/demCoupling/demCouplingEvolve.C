/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    One fluid time step of the coupling, evolve(): the steps 1-5 listed in
    demCoupling.H, and the cell fields the extra forces need.

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

// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

// The particle data of one fluid step, indexed by the start index s (the
// order of the core's arrays when the step begins; the core may re-sort its
// storage inside dem_world_step, so later indices map back through the id)
struct Foam::demCoupling::stepData
{
    scalar dt;
    label nDem;
    label n;
    label nExtra;

    // fluid fields of the last fluid step (cells) and their halo copies
    const vectorField* Uc;
    const vectorField* gradPc;
    const vectorField* divTc;
    List<vector> vsCellH;

    // the fluid's density: a cell field (a mixture of fluids, evolve with
    // rho) or nullptr for the constant rhof; unit: the factor that turns
    // grad p, div tau and the viscosity passed in into Pa/m, N/m3 and Pa s
    // (rhof for kinematic ones, 1 for dynamic ones)
    const scalarField* rhoc;
    scalar unit;

    // per particle: fluid values at the particle, forces and coefficients
    List<vector> uF, fGP, fExch, fPart, divTauP;
    scalarField epsP, muP, rhoP, dragFac, Ksum, VpS;
    List<int64_t> idStart;

    // optional forces f'' (extraForces/): fluid vorticity and acceleration
    // at the particles, the explicit impulse and the added mass per force
    List<vector> vortP, DuDtP, vStart;
    List<scalarField> maK;
    List<List<vector>> impK;

    stepData(const scalar dt, const label nDem, const label n, const label nExtra)
    :
        dt(dt), nDem(nDem), n(n), nExtra(nExtra),
        Uc(nullptr), gradPc(nullptr), divTc(nullptr),
        rhoc(nullptr), unit(1),
        uF(n), fGP(n), fExch(n), fPart(n), divTauP(n),
        epsP(n), muP(n), rhoP(n), dragFac(n), Ksum(n, 0), VpS(n), idStart(n),
        vortP(nExtra ? n : 0), DuDtP(nExtra ? n : 0), vStart(nExtra ? n : 0),
        maK(nExtra, scalarField(n, 0)),
        impK(nExtra, List<vector>(n, Zero))
    {}

    //- Start index of owned particle j (its startTag, checked against
    //  the ids at the start), -1 for one inserted during the step
    label startOf(const dem_arrays& a, const label j) const
    {
        const int64_t s = a.tag[demTools::startTag][j];
        return (s >= 0 && s < n && idStart[s] == a.id[j]) ? label(s) : -1;
    }
};


void Foam::demCoupling::evolve
(
    const volVectorField& U,
    const volScalarField& p,
    const volVectorField& divTauKin,
    const volScalarField& nu
)
{
    evolveFluid(U, p, divTauKin, nu, nullptr);
}


void Foam::demCoupling::evolve
(
    const volVectorField& U,
    const volScalarField& p,
    const volVectorField& divTau,
    const volScalarField& mu,
    const volScalarField& rho
)
{
    evolveFluid(U, p, divTau, mu, &rho);
}


void Foam::demCoupling::evolveFluid
(
    const volVectorField& U,
    const volScalarField& p,
    const volVectorField& divTau,
    const volScalarField& viscosity,
    const volScalarField* rho
)
{
    const auto tEvolve0 = std::chrono::steady_clock::now();
    const scalar tDem0 = diag_.time().dem;
    const scalar tComm0 = diag_.time().comm;

    const scalar dt = mesh_.time().deltaTValue();
    const label nDem = subSteps(dt);
    nSubCycles_ = nDem;

    stepData sd(dt, nDem, label(world_.arrays().n_owned), extraForces_.size());
    const volVectorField gradP(fvc::grad(p));
    sd.Uc = &U.primitiveField();
    sd.gradPc = &gradP.primitiveField();
    sd.divTc = &divTau.primitiveField();
    sd.rhoc = rho ? &rho->primitiveField() : nullptr;
    sd.unit = rho ? 1 : rhof_;

    // 1-2: the fluid at the particles' start positions (located and weighted
    // by the last call)
    sampleFluid(sd, U, viscosity);

    // 3: DEM sub-steps with the drag re-evaluated every dragUpdateInterval
    if (!subStep(sd))
    {
        ++nSteps_;
        return;
    }

    // 4: exchange, eta, balance (start-of-step weights)
    DynamicList<int64_t> inserted;
    exchange(sd, inserted);

    // 5: new positions -> voidage for the fluid step
    insertion_.startRamp(inserted);
    cloud_.locate(failure_);
    computeWeights();
    computeVoidage();
    relaxVoidage();

    bed_.sample(world_.arrays(), eps_);
    bed_.append();

    ++nSteps_;
    diag_.time().coupling +=
        std::chrono::duration<scalar>
        (
            std::chrono::steady_clock::now() - tEvolve0
        ).count()
      - (diag_.time().dem - tDem0) - (diag_.time().comm - tComm0);

    report(false);
}


void Foam::demCoupling::sampleFluid
(
    stepData& sd,
    const volVectorField& U,
    const volScalarField& viscosity
)
{
    dem_arrays a = world_.arrays();
    const label n = sd.n;
    const vectorField& Uc = *sd.Uc;
    const vectorField& gradPc = *sd.gradPc;
    const vectorField& divTc = *sd.divTc;
    const scalarField& epsc = eps_.primitiveField();
    const scalarField& nuc = viscosity.primitiveField();
    const couplingFormulation& form = formulation_();
    const label nExtra = sd.nExtra;

    vectorField vortCell, DuDtCell;
    extraForceFields(U, vortCell, DuDtCell);

    // start index in the particle's tag, and the ids by start index (the
    // core may re-sort the particles during the DEM sub-steps)
    for (label s = 0; s < n; ++s)
    {
        a.tag[startTag][s] = s;
        sd.idStart[s] = a.id[s];
    }

    // cell-mean particle velocity (for the cell-mean drag variant)
    const vectorField& vsCell = Up_.primitiveField();

    // the particle volume the fluid sees (the voidage of this step; less
    // while an insertion ramp runs): the forces that scale with it, and
    // their share of the exchange, use the same volume, so that the
    // momentum exchange stays exact
    for (label s = 0; s < n; ++s)
    {
        sd.VpS[s] =
            insertion_.rampWeight(a.id[s])*4.0/3.0*pi*pow3(a.radius[s]);
    }

    // the same in the other processors' cells of the weights (halo)
    const List<vector> UcH(map_.haloGet(Uc));
    const List<vector> gradPcH(map_.haloGet(gradPc));
    const List<vector> divTcH(map_.haloGet(divTc));
    const List<scalar> epscH(map_.haloGet(epsc));
    const List<scalar> nucH(map_.haloGet(nuc));
    const List<scalar> rhocH(sd.rhoc ? map_.haloGet(*sd.rhoc) : List<scalar>());
    const List<vector> vortH(nExtra ? map_.haloGet(vortCell) : List<vector>());
    const List<vector> DuDtH(nExtra ? map_.haloGet(DuDtCell) : List<vector>());
    if (cellMeanDrag_)
    {
        sd.vsCellH = map_.haloGet(vsCell);
    }

    for (label s = 0; s < n; ++s)
    {
        const scalar Vp = sd.VpS[s];
        sd.uF[s] = map_.interp(s, Uc, UcH);
        const vector gp = sd.unit*map_.interp(s, gradPc, gradPcH) + state_.G;
        const vector dtau = sd.unit*map_.interp(s, divTc, divTcH);
        sd.epsP[s] = map_.interp(s, epsc, epscH);
        sd.muP[s] = sd.unit*map_.interp(s, nuc, nucH);
        // the fluid at the particle: a mixture's density interpolated with
        // the same weights (docs/theory.md section 10), else rhof
        sd.rhoP[s] = sd.rhoc ? map_.interp(s, *sd.rhoc, rhocH) : rhof_;
        const scalar rhoP = sd.rhoP[s];
        sd.dragFac[s] = form.dragFactor(sd.epsP[s]);
        sd.fGP[s] = -Vp*gp;
        sd.divTauP[s] = Vp*dtau;
        form.explicitForces
        (
            Vp, gp, dtau, rhoP, g_, sd.fPart[s], sd.fExch[s]
        );
        setVec(a.force_ext, s, sd.fPart[s]);
        setVec(a.torque_ext, s, vector::zero);
        setVec(a.drag_impulse, s, vector::zero);
        scalar ma = 0;
        if (nExtra)
        {
            sd.vortP[s] = map_.interp(s, vortCell, vortH);
            sd.DuDtP[s] = map_.interp(s, DuDtCell, DuDtH);
            sd.vStart[s] = toVec(a.v, s);
            forAll(extraForces_, k)
            {
                sd.maK[k][s] = sd.dragFac[s]
                   *extraForces_[k].addedMass(2*a.radius[s], rhoP, sd.epsP[s]);
                ma += sd.maK[k][s];
            }
        }
        a.added_mass[s] = ma;
    }
}


bool Foam::demCoupling::subStep(stepData& sd)
{
    const label nDem = sd.nDem;
    const label nExtra = sd.nExtra;
    const vectorField& vsCell = Up_.primitiveField();
    const label chunk =
        dragUpdateInterval_ > 0 ? min(dragUpdateInterval_, nDem) : nDem;
    // the DEM step of this fluid step (dem/timeStep, or with
    // fitToFluidStep deltaT/nDem: the core takes it as a changeable setting)
    const scalar hDem = subStepLength(sd.dt, nDem);
    if (config_.dt != hDem)
    {
        config_.dt = hDem;
        world_.check
        (
            dem_world_configure_run(world_, &config_),
            "dem_world_configure_run (the DEM step of this fluid step)"
        );
    }

    label done = 0;
    while (done < nDem)
    {
        const label m = min(chunk, nDem - done);
        dem_arrays a = world_.arrays();
        // (decomposed: no more DEM work after a failure in this fluid step,
        // processorGhosts::step only answers the partners)
        const label nDrag = ghosts_.dead() ? 0 : label(a.n_owned);
        for (label j = 0; j < nDrag; ++j)
        {
            const label s = sd.startOf(a, j);
            if (s < 0)
            {
                // inserted during this fluid step: no drag until located
                a.drag_coeff[j] = 0;
                setVec(a.fluid_velocity, j, vector::zero);
                continue;
            }
            const vector v(toVec(a.v, j));
            vector slip = sd.uF[s] - v;
            vector uf = sd.uF[s];
            if (cellMeanDrag_)
            {
                // [S] method 1: drag from the cell-mean particle velocity
                const vector vs = map_.interp(s, vsCell, sd.vsCellH);
                slip = sd.uF[s] - vs;
                uf = sd.uF[s] - vs + v;
            }
            const scalar K =
                drag_->K(2*a.radius[j], sd.epsP[s], mag(slip), sd.rhoP[s], sd.muP[s])
               *sd.dragFac[s];
            a.drag_coeff[j] = K;
            setVec(a.fluid_velocity, j, uf);
            sd.Ksum[s] += K*m/nDem;
            if (nExtra)
            {
                // explicit extra forces (times the set's factor), held
                // over this drag update
                extraForce::particleState st;
                st.d = 2*a.radius[j];
                st.v = v;
                st.omega = toVec(a.omega, j);
                st.u = sd.uF[s];
                st.vorticity = sd.vortP[s];
                st.DuDt = sd.DuDtP[s];
                st.rhof = sd.rhoP[s];
                st.muf = sd.muP[s];
                st.eps = sd.epsP[s];
                vector fx(Zero);
                forAll(extraForces_, k)
                {
                    const vector f = sd.dragFac[s]*extraForces_[k].force(st);
                    sd.impK[k][s] += f*(m*hDem);
                    fx += f;
                }
                setVec(a.force_ext, j, sd.fPart[s] + fx);
            }
            if (frozen_)
            {
                // fixed bed: no DEM motion; the exchange is the drag at v
                const vector imp =
                    toVec(a.drag_impulse, j) + K*(uf - v)*m*hDem;
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
            const scalar tCommStep0 = diag_.time().comm;
            // decomposed: this processor's status; a failure is agreed
            // once per fluid step, below
            const dem_status st =
                Pstream::parRun() ? ghosts_.step(m) : world_.tryStep(m);
            diag_.time().dem += std::chrono::duration<scalar>
            (
                std::chrono::steady_clock::now() - t0
            ).count()
              - (diag_.time().comm - tCommStep0);
            if (st != DEM_OK && !Pstream::parRun())
            {
                failure_ = std::string("DEM core: ")
                  + dem_status_string(st) + ": " + world_.lastError();
                return false;
            }
        }
        done += m;
    }
    if (Pstream::parRun() && !frozen_)
    {
        // the first failure on any processor (earliest DEM step, then
        // lowest processor) stops all of them, each with its message; the
        // sub-steps of the fluid step are undone from the checkpoint
        const dem_status st = ghosts_.agree(failure_);
        if (st != DEM_OK)
        {
            return false;
        }
    }
    return true;
}


void Foam::demCoupling::exchange
(
    const stepData& sd,
    DynamicList<int64_t>& inserted
)
{
    const scalar dt = sd.dt;
    const label n = sd.n;
    const label nExtra = sd.nExtra;
    const vectorField& Uc = *sd.Uc;
    const vectorField& gradPc = *sd.gradPc;
    const vectorField& divTc = *sd.divTc;
    const scalarField& V = mesh_.V();
    const couplingFormulation& form = formulation_();

    dem_arrays a = world_.arrays();
    const label nEnd = label(a.n_owned);

    vectorField Fc(mesh_.nCells(), Zero);
    vectorField KUcell(localDragReaction_ ? mesh_.nCells() : 0, Zero);
    scalarField Kcell(mesh_.nCells(), 0);
    scalarField etaCell(mesh_.nCells(), 0);
    scalarField wCell(mesh_.nCells(), 0);
    const label nHalo = map_.nHalo();
    vectorField FcHalo(nHalo, Zero);
    vectorField KUcellHalo(localDragReaction_ ? nHalo : 0, Zero);
    scalarField KcellHalo(nHalo, 0), etaCellHalo(nHalo, 0), wCellHalo(nHalo, 0);

    state_.outIds.setSize(nEnd);
    state_.fDrag.setSize(nEnd);
    state_.fGradP.setSize(nEnd);
    state_.etaP.setSize(nEnd);
    state_.coordP.setSize(nEnd);
    if (frozen_ || !writeStep())
    {
        // not counted: a fixed bed never evaluates contacts, and only
        // write steps write them (a count costs about 0.1 DEM step; a
        // last good state after a failure has them if its step was a
        // write step)
        state_.coordP = -1;
    }
    else if (nEnd)
    {
        // now, while the sub-steps' neighbour list is valid (a migration
        // clears it: the core then reports the count as unknown)
        world_.check
        (
            dem_world_particle_contacts(world_, state_.coordP.data(), nullptr),
            "dem_world_particle_contacts"
        );
    }
    state_.fExtra.setSize(nExtra);
    forAll(state_.fExtra, k)
    {
        state_.fExtra[k].setSize(nEnd);
    }
    label nSeen = 0;
    diag_.beginStep();

    for (label j = 0; j < nEnd; ++j)
    {
        state_.outIds[j] = a.id[j];
        const label s = sd.startOf(a, j);
        if (s < 0)
        {
            inserted.append(a.id[j]);
            state_.fDrag[j] = Zero; state_.fGradP[j] = Zero; state_.etaP[j] = 0;
            forAll(state_.fExtra, k) state_.fExtra[k][j] = Zero;
            continue;
        }
        ++nSeen;
        const scalar Vp = sd.VpS[s];
        const vector dragRate = toVec(a.drag_impulse, j)/dt;
        // extra forces: explicit impulse plus the implicit added-mass part
        // -m_a (v_end - v_start) (exactly what the core applied)
        vector extraRate(Zero);
        forAll(extraForces_, k)
        {
            state_.fExtra[k][j] =
                (sd.impK[k][s] - sd.maK[k][s]*(toVec(a.v, j) - sd.vStart[s]))/dt;
            extraRate += state_.fExtra[k][j];
        }
        const vector exch = dragRate + sd.fExch[s] + extraRate;
        state_.fDrag[j] = dragRate;
        state_.fGradP[j] = sd.fGP[s];

        // eta and the momentum balance's sums (couplingDiagnostics)
        state_.etaP[j] = diag_.addParticle
        ({
            dragRate, extraRate, sd.fPart[s], sd.fGP[s], sd.divTauP[s],
            sd.dragFac[s], sd.epsP[s], sd.rhoP[s], Vp, a.density[j]
        });

        map_.deposit(s, exch, Fc, FcHalo);
        map_.deposit(s, sd.Ksum[s], Kcell, KcellHalo);
        if (localDragReaction_)
        {
            map_.deposit(s, sd.Ksum[s]*sd.uF[s], KUcell, KUcellHalo);
        }
        map_.deposit(s, state_.etaP[j], etaCell, etaCellHalo);
        map_.deposit(s, scalar(1), wCell, wCellHalo);
    }
    map_.haloAdd(Fc, FcHalo);
    map_.haloAdd(Kcell, KcellHalo);
    if (localDragReaction_)
    {
        map_.haloAdd(KUcell, KUcellHalo);
        KUcoup_.primitiveFieldRef() = KUcell/V;
    }
    map_.haloAdd(etaCell, etaCellHalo);
    map_.haloAdd(wCell, wCellHalo);
    if (nSeen != n)
    {
        FatalErrorInFunction
            << n - nSeen << " particles were removed inside dem_world_step; "
            << "demFoam books outlets itself and expects none"
            << exit(FatalError);
    }

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
            S += (1 - epsRaw_[c])*(sd.unit*gradPc[c] + state_.G);
        }
        if (tauEps)
        {
            S -= (1 - epsRaw_[c])*sd.unit*divTc[c];
        }
        source_[c] = S;
        sumFluid += S*V[c];
        eta_[c] = wCell[c] > 0 ? etaCell[c]/wCell[c] : 0;
    }
    state_.bedEta = diag_.endStep(sumFluid);
    Ucoup_.primitiveFieldRef() = Uc;
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
        // step (U is the field of the end of the previous step; state_.Uprev the
        // one of the step before, kept with its time index; the step
        // between them is deltaT0, which a restart reads back exactly)
        DuDt = (U & fvc::grad(U))().primitiveField();
        const label index = mesh_.time().timeIndex();
        if (state_.Uprev.size() == mesh_.nCells() && index == state_.indexUprev + 1)
        {
            DuDt += (U.primitiveField() - state_.Uprev)/mesh_.time().deltaT0Value();
        }
        state_.Uprev = U.primitiveField();
        state_.indexUprev = index;
    }
}


// ************************************************************************* //
