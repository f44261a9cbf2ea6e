/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    The weights of all particles (compute) and the halo exchange of the
    divided voidage in decomposed runs (the slots and lists are made by
    resolveRemote, particleMeshMap.C).

\*---------------------------------------------------------------------------*/

#include "UIPstream.H"
#include "UOPstream.H"
#include "UIndirectList.H"
#include <chrono>

// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

namespace Foam
{
namespace demHalo
{
    //- Message tag of the halo exchanges (their own, so that they cannot
    //  match other messages between the same processors)
    constexpr int tag = 23011;
}
}


template<class Position>
void Foam::particleMeshMap::compute
(
    const voidageModel& voidage,
    const label n,
    const double* radius,
    const labelUList& host,
    const Position& position
)
{
    wStart_.setSize(n + 1);
    wCells_.clear();
    wValues_.clear();
    // decomposed: the parts in other processors' cells, by particle
    DynamicList<remoteSample> remote;
    DynamicList<label> remoteOwner;
    for (label i = 0; i < n; ++i)
    {
        wStart_[i] = wCells_.size();
        voidage.addWeights
        (
            position(i), radius[i], host[i], wCells_, wValues_, remote
        );
        while (remoteOwner.size() < remote.size())
        {
            remoteOwner.append(i);
        }
    }
    wStart_[n] = wCells_.size();
    resolveRemote(remoteOwner, remote, host, voidage.dropsOutside());
}


template<class Type>
Foam::List<Type> Foam::particleMeshMap::haloGet(const UList<Type>& f)
{
    // point to point: both sides know the sizes (haloSend_, haloStart_),
    // so there is no exchange of message sizes
    List<Type> h(haloStart_.empty() ? 0 : haloStart_.last());
    if (!Pstream::parRun() || !haloAny_)
    {
        return h;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const label req0 = UPstream::nRequests();
    for (label r = 0; r < Pstream::nProcs(); ++r)
    {
        const label n = haloStart_[r+1] - haloStart_[r];
        if (!n) continue;
        UIPstream::read
        (
            Pstream::commsTypes::nonBlocking, r,
            reinterpret_cast<char*>(h.data() + haloStart_[r]),
            std::streamsize(n*sizeof(Type)), demHalo::tag
        );
    }
    List<List<Type>> out(Pstream::nProcs());
    forAll(haloSend_, r)
    {
        if (haloSend_[r].empty()) continue;
        out[r] = UIndirectList<Type>(f, haloSend_[r]);
        UOPstream::write
        (
            Pstream::commsTypes::nonBlocking, r,
            reinterpret_cast<const char*>(out[r].cdata()),
            std::streamsize(out[r].size()*sizeof(Type)), demHalo::tag
        );
    }
    UPstream::waitRequests(req0);
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
    return h;
}


template<class Type>
void Foam::particleMeshMap::haloAdd(UList<Type>& f, const UList<Type>& acc)
{
    if (!Pstream::parRun() || !haloAny_)
    {
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const label req0 = UPstream::nRequests();
    List<List<Type>> in(Pstream::nProcs());
    forAll(haloSend_, r)
    {
        if (haloSend_[r].empty()) continue;
        in[r].setSize(haloSend_[r].size());
        UIPstream::read
        (
            Pstream::commsTypes::nonBlocking, r,
            reinterpret_cast<char*>(in[r].data()),
            std::streamsize(in[r].size()*sizeof(Type)), demHalo::tag
        );
    }
    for (label r = 0; r < Pstream::nProcs(); ++r)
    {
        const label n = haloStart_[r+1] - haloStart_[r];
        if (!n) continue;
        UOPstream::write
        (
            Pstream::commsTypes::nonBlocking, r,
            reinterpret_cast<const char*>(acc.cdata() + haloStart_[r]),
            std::streamsize(n*sizeof(Type)), demHalo::tag
        );
    }
    UPstream::waitRequests(req0);
    forAll(in, r)
    {
        forAll(in[r], k)
        {
            f[haloSend_[r][k]] += in[r][k];
        }
    }
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
}


// ************************************************************************* //
