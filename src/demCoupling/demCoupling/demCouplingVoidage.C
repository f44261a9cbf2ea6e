/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    The particles' volume on the mesh (step 5 of evolve(), demCoupling.H):
    their (cell, weight) lists, the voidage eps and the cell-mean particle
    velocity Up, a new particle's volume weighted by its insertion ramp
    (particleInsertion); the solid fraction smoothed in space
    (voidageSmoothingLength); the continuity's voidage relaxed in time
    (voidageRelaxationTime).

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

    // insertion ramp (particleInsertion): a new particle's volume enters
    // over insertionRampTime
    insertion_.rampAt(mesh_.time().value());

    scalarField solid(mesh_.nCells(), 0);
    vectorField mom(mesh_.nCells(), Zero);
    const label nHalo = map_.nHalo();
    scalarField solidHalo(nHalo, 0);
    vectorField momHalo(nHalo, Zero);
    scalar& solidParticles = diag_.solid().particles;
    scalar& solidRamp = diag_.solid().ramp;
    solidParticles = 0;
    solidRamp = 0;
    for (label i = 0; i < n; ++i)
    {
        const scalar V1 = 4.0/3.0*pi*pow3(a.radius[i]);
        const scalar Vp = insertion_.rampWeight(a.id[i])*V1;
        solidParticles += V1;
        solidRamp += V1 - Vp;
        map_.deposit(i, Vp, solid, solidHalo);
        map_.deposit(i, Vp*vector(toVec(a.v, i)), mom, momHalo);
    }
    map_.haloAdd(solid, solidHalo);
    map_.haloAdd(mom, momHalo);
    diag_.solid().mesh = gSum(solid);
    reduce(solidParticles, sumOp<scalar>());
    reduce(solidRamp, sumOp<scalar>());

    // epsRaw: the weights' own solid fraction, for the exchange terms that
    // must balance (demCouplingEvolve.C); eps: what the fluid and the drag
    // laws see, smoothed over voidageSmoothingLength if it is set
    scalarField solidFraction(solid/V);
    epsRaw_.primitiveFieldRef() = 1.0 - solidFraction;
    smoothing_.smooth(solidFraction);
    eps_.primitiveFieldRef() = max(1.0 - solidFraction, epsMin_);
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


void Foam::demCoupling::startRelaxedVoidage()
{
    if (epsRelaxTime_ <= 0) return;
    IOobject io
    (
        "epsRelaxed",
        mesh_.time().timeName(),
        mesh_,
        IOobject::MUST_READ,
        IOobject::AUTO_WRITE
    );
    if (io.typeHeaderOk<volScalarField>(true))
    {
        // a restart goes on from the relaxed state it wrote
        epsRelaxed_.reset(new volScalarField(io, mesh_));
    }
    else
    {
        io.readOpt() = IOobject::NO_READ;
        epsRelaxed_.reset(new volScalarField(io, eps_));
        Info<< "demCoupling: voidageRelaxationTime " << epsRelaxTime_
            << " s: no epsRelaxed in " << mesh_.time().timeName()
            << "; it starts from the particles' eps" << endl;
    }
    epsRelaxed_->oldTime();
}


void Foam::demCoupling::relaxVoidage()
{
    if (!epsRelaxed_.valid()) return;
    // implicit Euler of d(epsR)/dt = (eps - epsR)/tau: a convex combination
    // of the old epsR and the new eps, so epsMin <= epsR <= 1 stays
    volScalarField& epsR = epsRelaxed_();
    epsR.storeOldTimes();
    const scalar dt = mesh_.time().deltaTValue();
    const scalar a = dt/(epsRelaxTime_ + dt);
    epsR.primitiveFieldRef() =
        epsR.oldTime().primitiveField()
      + a*(eps_.primitiveField() - epsR.oldTime().primitiveField());
    epsR.correctBoundaryConditions();
}


// ************************************************************************* //
