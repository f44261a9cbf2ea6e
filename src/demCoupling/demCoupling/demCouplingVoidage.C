/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    The particles' volume on the mesh (step 5 of evolve(), demCoupling.H):
    their (cell, weight) lists, the voidage eps and the cell-mean particle
    velocity Up, and the insertion ramp by which a new particle's volume
    enters the voidage over insertionRampTime.

\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "demCouplingTools.H"
#include "mathematicalConstants.H"

using namespace Foam::constant::mathematical;
using namespace Foam::demTools;

// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::demCoupling::computeWeights()
{
    const dem_arrays a = world_.arrays();
    map_.compute
    (
        voidage_(), label(a.n_owned), a.radius, cloud_.host(),
        [&](const label i) { return box_.wrapped(a.x, i); }
    );
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
    for (auto it = state_.rampStart.begin(); it != state_.rampStart.end(); )
    {
        if (tNow - it->second >= rampTime_) it = state_.rampStart.erase(it);
        else ++it;
    }
    voidageTime_ = tNow;

    scalarField solid(mesh_.nCells(), 0);
    vectorField mom(mesh_.nCells(), Zero);
    const label nHalo = map_.nHalo();
    scalarField solidHalo(nHalo, 0);
    vectorField momHalo(nHalo, Zero);
    scalar& solidParticles = diag_.solid.particles;
    scalar& solidRamp = diag_.solid.ramp;
    solidParticles = 0;
    solidRamp = 0;
    for (label i = 0; i < n; ++i)
    {
        const scalar V1 = 4.0/3.0*pi*pow3(a.radius[i]);
        const scalar Vp = rampWeight(a.id[i], tNow)*V1;
        solidParticles += V1;
        solidRamp += V1 - Vp;
        map_.deposit(i, Vp, solid, solidHalo);
        map_.deposit(i, Vp*vector(toVec(a.v, i)), mom, momHalo);
    }
    map_.haloAdd(solid, solidHalo);
    map_.haloAdd(mom, momHalo);
    diag_.solid.mesh = gSum(solid);
    reduce(solidParticles, sumOp<scalar>());
    reduce(solidRamp, sumOp<scalar>());

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
    if (state_.rampStart.empty())
    {
        return 1;
    }
    const auto it = state_.rampStart.find(id);
    return
        it == state_.rampStart.end()
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
            state_.rampStart[id] = t0;
        }
    }
}


// ************************************************************************* //
