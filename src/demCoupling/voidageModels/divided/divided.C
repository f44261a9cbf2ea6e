/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "divided.H"
#include "addToRunTimeSelectionTable.H"
#include "FixedList.H"

namespace Foam
{
namespace voidageModels
{
    defineTypeNameAndDebug(divided, 0);
    addToRunTimeSelectionTable(voidageModel, divided, dictionary);
    addCoeffKeys(divided);
}
}

Foam::List<Foam::keySpec> Foam::voidageModels::divided::coeffKeys()
{
    using kind = keySpec::kind;
    return List<keySpec>
    ({
        keySpec::num("nLattice", kind::Label, 2, 12, false, false),
        keySpec::num("radiusFactor", kind::Scalar, 1, 5, false, false)
    });
}


Foam::voidageModels::divided::divided
(
    const dictionary& dict, const fvMesh& mesh, const particleLocator& l
)
:
    voidageModel(typeName, dict, mesh, l),
    radiusFactor_(coeffs_.getOrDefault<scalar>("radiusFactor", 1.0))
{
    const label n = coeffs_.getOrDefault<label>("nLattice", 6);
    if (n < 2 || n > 12)
    {
        FatalIOErrorInFunction(coeffs_)
            << "dividedCoeffs/nLattice " << n << " in " << coeffs_.name()
            << ": allowed 2..12" << exit(FatalIOError);
    }
    if (radiusFactor_ < 1 || radiusFactor_ > 5)
    {
        FatalIOErrorInFunction(coeffs_)
            << "dividedCoeffs/radiusFactor " << radiusFactor_ << " in "
            << coeffs_.name() << ": allowed 1..5" << exit(FatalIOError);
    }
    DynamicList<vector> pts;
    const scalar h = 2.0/n;
    for (label i = 0; i < n; ++i)
    {
        for (label j = 0; j < n; ++j)
        {
            for (label k = 0; k < n; ++k)
            {
                const vector s(-1 + (i + 0.5)*h, -1 + (j + 0.5)*h, -1 + (k + 0.5)*h);
                if (magSqr(s) <= 1.0)
                {
                    pts.append(s);
                }
            }
        }
    }
    samples_.transfer(pts);
}


void Foam::voidageModels::divided::addWeights
(
    const point& x, const scalar rp, const label hostCell,
    DynamicList<label>& cells, DynamicList<scalar>& weights,
    DynamicList<remoteSample>& remote
) const
{
    // the sampled sphere: the particle's, or radiusFactor times wider
    const scalar r = radiusFactor_*rp;
    const label start = cells.size();
    const scalar w = 1.0/samples_.size();

    // Faces of the host cell whose plane is closer to the centre than r
    // (only those can be crossed by a sample point).  A sample behind all of
    // them is in the host cell, exactly as the walk would find for a convex
    // cell, without the walk.
    const cell& hc = mesh_.cells()[hostCell];
    const vectorField& Sf = mesh_.faceAreas();
    const vectorField& Cf = mesh_.faceCentres();
    const labelList& own = mesh_.faceOwner();
    FixedList<vector, 64> nOut;
    FixedList<scalar, 64> dIn;
    label nNear = 0;
    bool allNear = hc.size() > 64;
    if (!allNear)
    {
        for (const label facei : hc)
        {
            vector n = Sf[facei]/locator_.magSf()[facei];
            if (own[facei] != hostCell) n = -n;
            const scalar d = (Cf[facei] - x) & n;
            if (d < r)
            {
                nOut[nNear] = n;
                dIn[nNear] = d;
                ++nNear;
            }
        }
    }
    if (!allNear && nNear == 0)
    {
        cells.append(hostCell);
        weights.append(1.0);
        return;
    }

    label prev = hostCell;
    const label remoteStart = remote.size();
    label nRemote = 0;
    forAll(samples_, s)
    {
        const vector q = r*samples_[s];
        if (!allNear)
        {
            bool inHost = true;
            for (label k = 0; k < nNear; ++k)
            {
                if ((q & nOut[k]) > dIn[k])
                {
                    inHost = false;
                    break;
                }
            }
            if (inHost)
            {
                bool found = false;
                for (label k = start; k < cells.size(); ++k)
                {
                    if (cells[k] == hostCell)
                    {
                        weights[k] += w;
                        found = true;
                        break;
                    }
                }
                if (!found)
                {
                    cells.append(hostCell);
                    weights.append(w);
                }
                continue;
            }
        }
        label exitFace = -1;
        label c = locator_.locate(x + q, prev, exitFace, false);
        if (c < 0)
        {
            if (locator_.processorBehind(exitFace) >= 0)
            {
                // in a neighbour processor's cells (or beyond): the walk
                // goes on there (demCoupling::resolveRemote)
                remote.append(remoteSample{x + q, exitFace, w});
                ++nRemote;
                continue;
            }
            if (dropsOutside())
            {
                // outside the mesh, in the widened sphere: dropped, the
                // others share its volume (normalisation below)
                continue;
            }
            // outside the mesh (beyond a wall the particle touches at
            // most): counted in the host cell
            c = hostCell;
        }
        else
        {
            prev = c;
        }
        bool found = false;
        for (label k = start; k < cells.size(); ++k)
        {
            if (cells[k] == c)
            {
                weights[k] += w;
                found = true;
                break;
            }
        }
        if (!found)
        {
            cells.append(c);
            weights.append(w);
        }
    }
    // make the sum exactly 1 (round-off of repeated additions, and the
    // points dropped outside the mesh)
    scalar sum = nRemote*w;
    for (label k = start; k < cells.size(); ++k)
    {
        sum += weights[k];
    }
    for (label k = start; k < cells.size(); ++k)
    {
        weights[k] /= sum;
    }
    for (label k = remoteStart; k < remote.size(); ++k)
    {
        remote[k].w /= sum;
    }
}
