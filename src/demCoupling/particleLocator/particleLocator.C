/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "particleLocator.H"
#include "processorPolyPatch.H"
#include "processorCyclicPolyPatch.H"

Foam::particleLocator::particleLocator(const polyMesh& mesh, const label maxWalk)
:
    mesh_(mesh),
    maxWalk_(maxWalk),
    nWalk_(0),
    nGlobal_(0),
    faceProc_(mesh.nBoundaryFaces(), -1),
    magSf_(mag(mesh.faceAreas())),
    faceTol_(1e-12*sqrt(magSf_))
{
    for (const polyPatch& pp : mesh.boundaryMesh())
    {
        if (isA<processorPolyPatch>(pp) && !isA<processorCyclicPolyPatch>(pp))
        {
            const label r = refCast<const processorPolyPatch>(pp).neighbProcNo();
            SubList<label>(faceProc_, pp.size(), pp.start() - mesh.nInternalFaces()) = r;
        }
    }
}


Foam::label Foam::particleLocator::exitFace
(
    const point& p,
    const label celli,
    scalar& dist
) const
{
    const cell& c = mesh_.cells()[celli];
    const vectorField& Sf = mesh_.faceAreas();
    const vectorField& Cf = mesh_.faceCentres();
    const labelList& own = mesh_.faceOwner();

    label best = -1;
    dist = 0;
    forAll(c, i)
    {
        const label facei = c[i];
        scalar d = ((p - Cf[facei]) & Sf[facei])/magSf_[facei];
        if (own[facei] != celli)
        {
            d = -d;
        }
        // tolerance: 1e-12 of the face size
        if (d > dist + faceTol_[facei])
        {
            dist = d;
            best = facei;
        }
    }
    return best;
}


Foam::label Foam::particleLocator::walk
(
    const point& p,
    label& celli,
    label& exitFacei
) const
{
    exitFacei = -1;
    if (celli < 0 || celli >= mesh_.nCells())
    {
        return -1;
    }
    ++nWalk_;
    for (label step = 0; step < maxWalk_; ++step)
    {
        scalar dist;
        const label facei = exitFace(p, celli, dist);
        if (facei < 0)
        {
            return celli;
        }
        if (mesh_.isInternalFace(facei))
        {
            const label own = mesh_.faceOwner()[facei];
            celli = (own == celli ? mesh_.faceNeighbour()[facei] : own);
        }
        else
        {
            exitFacei = facei;
            break;
        }
    }
    return -1;
}


Foam::label Foam::particleLocator::search
(
    const point& p,
    const label lastCell,
    label& exitFacei
) const
{
    ++nGlobal_;
    const label found = mesh_.findCell(p);
    if (found >= 0)
    {
        exitFacei = -1;
        return found;
    }

    if (exitFacei < 0 && lastCell >= 0 && lastCell < mesh_.nCells())
    {
        // the boundary face of the last cell that p lies furthest beyond
        const cell& c = mesh_.cells()[lastCell];
        scalar best = -GREAT;
        forAll(c, i)
        {
            const label facei = c[i];
            if (!mesh_.isInternalFace(facei))
            {
                const vector n = mesh_.faceAreas()[facei]/magSf_[facei];
                const scalar d = (p - mesh_.faceCentres()[facei]) & n;
                if (d > best)
                {
                    best = d;
                    exitFacei = facei;
                }
            }
        }
    }
    return -1;
}


Foam::label Foam::particleLocator::locate
(
    const point& p,
    const label seed,
    label& exitFacei,
    const bool global
) const
{
    label celli = seed;
    const label found = walk(p, celli, exitFacei);
    if (found >= 0 || (!global && seed >= 0))
    {
        return found;
    }
    return search(p, celli, exitFacei);
}


Foam::label Foam::particleLocator::locateOrCross
(
    const point& p,
    const label seed,
    label& exitFacei
) const
{
    label celli = seed;
    const label found = walk(p, celli, exitFacei);
    if (found >= 0 || (exitFacei >= 0 && processorBehind(exitFacei) >= 0))
    {
        return found;
    }
    return search(p, celli, exitFacei);
}
