/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Divided voidage across processor boundaries (decomposed runs).

    The divided voidage model places a particle's volume on the cells that
    hold its sample points, each found by a walk from the host cell.  A
    walk that leaves this processor through a processor face is continued
    on the neighbour processor from the cell behind that face, and on from
    there if it leaves again: the point ends in the cell a serial run finds,
    or outside the mesh (then, as in serial, in the host cell, or dropped
    for a model that drops such points: divided with radiusFactor > 1).

    A cell of another processor in a particle's weights is a halo slot
    (wCells_ < 0).  The processor that holds the cell keeps, per processor
    it serves, the list of its cells in slot order (haloSend_).  Per fluid
    step, the fluid values the particles need are fetched for the slots
    (haloGet) and the particles' solid volume, momentum and exchange force
    are added to the cells that hold them (haloAdd), so that eps, the
    interpolated fluid state and the fluid's source equal the serial ones.

\*---------------------------------------------------------------------------*/

#include "particleMeshMap.H"
#include "Map.H"
#include <chrono>

// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::particleMeshMap::particleMeshMap
(
    const fvMesh& mesh,
    const particleLocator& locator,
    scalar& commTime
)
:
    mesh_(mesh),
    locator_(locator),
    tComm_(commTime),
    wStart_(),
    wCells_(),
    wValues_(),
    haloSend_(),
    haloStart_(2, Zero),
    haloAny_(false),
    haloParticleSteps_(0)
{}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::particleMeshMap::resolveRemote
(
    const labelUList& owner,
    const UList<remoteSample>& remote,
    const labelUList& host,
    const bool dropOutside
)
{
    const label nProcs = Pstream::nProcs();
    const label me = Pstream::myProcNo();
    haloSend_ = List<labelList>(nProcs);
    haloStart_.setSize(nProcs + 1);
    haloStart_ = 0;
    haloAny_ = false;
    if (!Pstream::parRun() || !returnReduce(remote.size() > 0, orOp<bool>()))
    {
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();

    // the processor patch to each processor through which walks go on
    // (particleLocator::processorBehind)
    const polyBoundaryMesh& pbm = mesh_.boundaryMesh();
    labelList patchTo(nProcs, -1);
    forAll(pbm, patchi)
    {
        if (pbm[patchi].size())
        {
            const label r = locator_.processorBehind(pbm[patchi].start());
            if (r >= 0) patchTo[r] = patchi;
        }
    }

    // result per remote sample: the processor whose cell holds it (-1: no
    // cell, the host cell) and the cell (this processor) or its index in
    // that processor's haloSend_ list for this one
    labelList resProc(remote.size(), -1);
    labelList resCell(remote.size(), -1);

    // cells served to each processor, with their index
    List<DynamicList<label>> serve(nProcs);
    List<Map<label>> served(nProcs);

    // walk requests (origin, its sample index, face of the patch between
    // sender and receiver, hops so far, point) and answers (sample index,
    // served index or -1) to send this round
    List<DynamicList<label>> qOrig(nProcs), qIdx(nProcs), qFace(nProcs);
    List<DynamicList<label>> qHops(nProcs);
    List<DynamicList<point>> qPt(nProcs);
    List<DynamicList<label>> aIdx(nProcs), aSlot(nProcs);
    const label maxHops = 2*nProcs;

    auto answer = [&](const label origin, const label k, const label cell)
    {
        if (origin == me)
        {
            resProc[k] = cell >= 0 ? me : -1;
            resCell[k] = cell;
            return;
        }
        label h = -1;
        if (cell >= 0)
        {
            const auto it = served[origin].cfind(cell);
            if (it.found())
            {
                h = *it;
            }
            else
            {
                h = serve[origin].size();
                serve[origin].append(cell);
                served[origin].insert(cell, h);
            }
        }
        aIdx[origin].append(k);
        aSlot[origin].append(h);
    };
    auto request = [&]
    (
        const label origin, const label k, const point& p,
        const label exitFace, const label hops
    )
    {
        const label nbr = locator_.processorBehind(exitFace);
        if (nbr < 0 || hops >= maxHops)
        {
            answer(origin, k, -1);
            return;
        }
        qOrig[nbr].append(origin);
        qIdx[nbr].append(k);
        qFace[nbr].append(exitFace - pbm[patchTo[nbr]].start());
        qHops[nbr].append(hops + 1);
        qPt[nbr].append(p);
    };

    forAll(remote, k)
    {
        request(me, k, remote[k].p, remote[k].face, 0);
    }

    for (label round = 0; ; ++round)
    {
        label nOut = 0;
        forAll(qOrig, r) nOut += qOrig[r].size() + aIdx[r].size();
        if (!returnReduce(nOut, sumOp<label>()))
        {
            break;
        }
        PstreamBuffers pBufs(Pstream::commsTypes::nonBlocking);
        for (label r = 0; r < nProcs; ++r)
        {
            if (qOrig[r].empty() && aIdx[r].empty()) continue;
            UOPstream os(r, pBufs);
            os  << qOrig[r] << qIdx[r] << qFace[r] << qHops[r] << qPt[r]
                << aIdx[r] << aSlot[r];
            qOrig[r].clear(); qIdx[r].clear(); qFace[r].clear();
            qHops[r].clear(); qPt[r].clear();
            aIdx[r].clear(); aSlot[r].clear();
        }
        labelList recvSizes;
        pBufs.finishedSends(recvSizes);
        for (label r = 0; r < nProcs; ++r)
        {
            if (!recvSizes[r]) continue;
            UIPstream is(r, pBufs);
            labelList orig, idx, face, hops, ai, as;
            List<point> pt;
            is >> orig >> idx >> face >> hops >> pt >> ai >> as;
            forAll(ai, j)
            {
                resProc[ai[j]] = as[j] >= 0 ? r : -1;
                resCell[ai[j]] = as[j];
            }
            if (orig.size() && patchTo[r] < 0)
            {
                FatalErrorInFunction
                    << "processor " << me << ": walk requests from processor "
                    << r << ", which has no processor patch to it"
                    << abort(FatalError);
            }
            forAll(orig, j)
            {
                const label start = pbm[patchTo[r]].faceCells()[face[j]];
                label exitFace = -1;
                const label c = locator_.locate(pt[j], start, exitFace, false);
                if (c >= 0)
                {
                    answer(orig[j], idx[j], c);
                }
                else
                {
                    request(orig[j], idx[j], pt[j], exitFace, hops[j]);
                }
            }
        }
    }

    // slots: the cells of processor r that this one uses, in r's order
    labelList nFrom(nProcs, 0);
    forAll(remote, k)
    {
        if (resProc[k] >= 0 && resProc[k] != me)
        {
            nFrom[resProc[k]] = max(nFrom[resProc[k]], resCell[k] + 1);
        }
    }
    for (label r = 0; r < nProcs; ++r)
    {
        haloStart_[r+1] = haloStart_[r] + nFrom[r];
        haloSend_[r].transfer(serve[r]);
    }
    haloAny_ = returnReduce(haloStart_[nProcs] > 0, orOp<bool>());
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
    if (remote.empty())
    {
        return;
    }

    // the weights with the remote parts merged in, per particle
    const label n = wStart_.size() - 1;
    labelList start(n + 1);
    DynamicList<label> cells(wCells_.size() + remote.size());
    DynamicList<scalar> values(wCells_.size() + remote.size());
    label k = 0;
    for (label i = 0; i < n; ++i)
    {
        start[i] = cells.size();
        for (label m = wStart_[i]; m < wStart_[i+1]; ++m)
        {
            cells.append(wCells_[m]);
            values.append(wValues_[m]);
        }
        bool across = false;
        scalar dropped = 0;
        for (; k < remote.size() && owner[k] == i; ++k)
        {
            if (resProc[k] < 0 && dropOutside)
            {
                dropped += remote[k].w;
                continue;
            }
            across = across || (resProc[k] >= 0 && resProc[k] != me);
            const label code =
                resProc[k] < 0 ? host[i]
              : resProc[k] == me ? resCell[k]
              : -1 - (haloStart_[resProc[k]] + resCell[k]);
            bool found = false;
            for (label m = start[i]; m < cells.size(); ++m)
            {
                if (cells[m] == code)
                {
                    values[m] += remote[k].w;
                    found = true;
                    break;
                }
            }
            if (!found)
            {
                cells.append(code);
                values.append(remote[k].w);
            }
        }
        if (dropped > 0)
        {
            // the particle's volume over its parts inside the mesh
            for (label m = start[i]; m < cells.size(); ++m)
            {
                values[m] /= 1 - dropped;
            }
        }
        if (across) ++haloParticleSteps_;
    }
    start[n] = cells.size();
    wStart_.transfer(start);
    wCells_.transfer(cells);
    wValues_.transfer(values);
}


// ************************************************************************* //
