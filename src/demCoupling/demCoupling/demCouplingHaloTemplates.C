/*---------------------------------------------------------------------------*\
  demFoam

Description
    Halo exchange of the divided voidage in decomposed runs (the slots and
    lists are made by demCoupling::resolveRemote, demCouplingHalo.C).

\*---------------------------------------------------------------------------*/

#include "PstreamBuffers.H"
#include "UIndirectList.H"

// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

template<class Type>
Foam::List<Type> Foam::demCoupling::haloGet(const UList<Type>& f)
{
    List<Type> h(haloStart_.empty() ? 0 : haloStart_.last());
    if (!Pstream::parRun() || !haloAny_)
    {
        return h;
    }
    const auto t0 = std::chrono::steady_clock::now();
    PstreamBuffers pBufs(Pstream::commsTypes::nonBlocking);
    forAll(haloSend_, r)
    {
        if (haloSend_[r].empty()) continue;
        UOPstream os(r, pBufs);
        os << List<Type>(UIndirectList<Type>(f, haloSend_[r]));
    }
    pBufs.finishedSends();
    for (label r = 0; r < Pstream::nProcs(); ++r)
    {
        const label n = haloStart_[r+1] - haloStart_[r];
        if (!n) continue;
        UIPstream is(r, pBufs);
        List<Type> v;
        is >> v;
        if (v.size() != n)
        {
            FatalErrorInFunction
                << "halo of processor " << r << ": " << v.size()
                << " values for " << n << " slots" << abort(FatalError);
        }
        SubList<Type>(h, n, haloStart_[r]) = v;
    }
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
    return h;
}


template<class Type>
void Foam::demCoupling::haloAdd(UList<Type>& f, const UList<Type>& acc)
{
    if (!Pstream::parRun() || !haloAny_)
    {
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    PstreamBuffers pBufs(Pstream::commsTypes::nonBlocking);
    for (label r = 0; r < Pstream::nProcs(); ++r)
    {
        const label n = haloStart_[r+1] - haloStart_[r];
        if (!n) continue;
        UOPstream os(r, pBufs);
        os << List<Type>(SubList<Type>(acc, n, haloStart_[r]));
    }
    pBufs.finishedSends();
    forAll(haloSend_, r)
    {
        if (haloSend_[r].empty()) continue;
        UIPstream is(r, pBufs);
        List<Type> v;
        is >> v;
        if (v.size() != haloSend_[r].size())
        {
            FatalErrorInFunction
                << "halo deposit of processor " << r << ": " << v.size()
                << " values for " << haloSend_[r].size() << " cells"
                << abort(FatalError);
        }
        forAll(v, k)
        {
            f[haloSend_[r][k]] += v[k];
        }
    }
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
}


// ************************************************************************* //
