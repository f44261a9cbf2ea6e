/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "bedMonitor.H"
#include <fstream>

namespace
{
    // histogram bins over the mesh height
    constexpr Foam::label nBins = 2000;
}


Foam::bedMonitor::bedMonitor(const fvMesh& mesh, const vector& g)
:
    mesh_(mesh),
    up_(mag(g) > VSMALL ? -g/mag(g) : vector(0, 0, 1)),
    base_(0),
    span_(0),
    h95_(0),
    h2Mean_(0),
    eps_(1),
    n_(0)
{
    scalar lo = GREAT, hi = -GREAT;
    for (const point& p : mesh.points())
    {
        const scalar h = p & up_;
        lo = min(lo, h);
        hi = max(hi, h);
    }
    reduce(lo, minOp<scalar>());
    reduce(hi, maxOp<scalar>());
    base_ = lo;
    span_ = max(hi - lo, VSMALL);
}


void Foam::bedMonitor::sample(const dem_arrays& a, const volScalarField& eps)
{
    const label n = label(a.n_owned);
    labelList bins(nBins, 0);
    scalar hSum = 0;
    for (label i = 0; i < n; ++i)
    {
        const vector x(a.x[3*i], a.x[3*i + 1], a.x[3*i + 2]);
        const scalar h = (x & up_) - base_;
        hSum += h;
        ++bins[min(max(label(h/span_*nBins), label(0)), nBins - 1)];
    }
    Pstream::listCombineGather(bins, plusEqOp<label>());
    Pstream::listCombineScatter(bins);
    n_ = returnReduce(n, sumOp<label>());
    h2Mean_ = n_ ? 2*returnReduce(hSum, sumOp<scalar>())/n_ : 0;

    // the upper edge of the bin where 95 % of the centres are reached
    h95_ = 0;
    label below = 0;
    for (label b = 0; b < nBins && n_; ++b)
    {
        below += bins[b];
        if (below >= 0.95*n_)
        {
            h95_ = (b + 1)*span_/nBins;
            break;
        }
    }

    scalar vEps = 0, v = 0;
    const scalarField& V = mesh_.V();
    forAll(V, celli)
    {
        if ((mesh_.C()[celli] & up_) - base_ <= h95_)
        {
            vEps += eps[celli]*V[celli];
            v += V[celli];
        }
    }
    reduce(vEps, sumOp<scalar>());
    reduce(v, sumOp<scalar>());
    eps_ = v > 0 ? vEps/v : 1;
}


void Foam::bedMonitor::append() const
{
    if (!Pstream::master()) return;
    const Time& runTime = mesh_.time();
    const fileName dir
    (
        runTime.globalPath()/"postProcessing"/"demBed"
       /runTime.timeName(runTime.startTime().value())
    );
    mkDir(dir);
    const fileName file(dir/"bed.dat");
    const bool fresh = !isFile(file);
    std::ofstream os(file.c_str(), std::ios::app);
    os.precision(8);
    if (fresh)
    {
        os  << "# bed against gravity from the lowest mesh point: time [s],"
            << " h95 [m] (95 % of the centres below), 2<h> [m], mean"
            << " voidage of the cells below h95, particles\n";
    }
    os  << runTime.value() << ' ' << h95_ << ' ' << h2Mean_ << ' ' << eps_
        << ' ' << n_ << '\n';
}


void Foam::bedMonitor::report() const
{
    Info<< "demCoupling: bed: h95 " << h95_ << " m (95 % of the centres "
        << "below), 2<h> " << h2Mean_ << " m, mean voidage below h95 "
        << eps_ << " (" << n_ << " particles)" << endl;
}


// ************************************************************************* //
