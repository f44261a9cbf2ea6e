/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Ghost copies of particles across processor boundaries (docs/parallel.md,
    "Neighbour-only communication"): the partners, which owned particles go
    to which partner, their packing, and the DEM steps of a decomposed run
    with the ghosts refreshed between the drift and the force evaluation.

    Why half a skin per pair, and no propagation (docs/parallel.md,
    "Neighbour-only communication"):
    - Ghost sets.  The set q sends p at time T holds every q particle
      within r_i + r_max + skin of one of p's slab boxes at T (slabBoxes:
      their union holds p's centres).  While q's
      and p's particles each move at most skin/2 from T (each side checks
      its own and asks for a renewal otherwise), no q particle outside the
      set can touch a p particle.  A renewal is also asked when a side's
      owned set changed (migration, insertion, removal: its list is
      invalid), and on the first call.
    - Lists.  p's neighbour list, built at B, holds the pairs within
      r_i + r_j + skin at B.  It stays valid while p's particles move at
      most skin/2 from B (the core's criterion) and so do the ghosts: p
      measures their displacement since B from the states it receives
      (dem_world_ghost_displacement) and rebuilds, alone (no renewal, no
      message), before it exceeds skin/2.  So one pair's renewal forces no
      other pair's, and a rebuild does not propagate.
    - Displacements since a renewal are bounded without keeping
      positions: S_ sums the largest owned displacement of every finished
      list-build interval (the core's drift displacement at the rebuild,
      plus the rounding of its single-precision build positions); since a
      renewal at T, where the list was rebuilt, every owned particle moved
      at most S_ - S_(T) + d (d the drift displacement since the last
      build; the triangle inequality, interval by interval).

\*---------------------------------------------------------------------------*/

#include "processorGhosts.H"
#include "demCouplingTools.H"
#include "UIPstream.H"
#include "UOPstream.H"
#include "Map.H"
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace Foam::demTools;

// * * * * * * * * * * * * * * * * Helpers * * * * * * * * * * * * * * * * //

// MPI's profiling hook, a no-op unless a profiling library is loaded
// (bin/tools/mpiMessageCount counts the messages between the marks)
extern "C" int MPI_Pcontrol(const int level, ...) __attribute__((weak));

namespace
{
    // Marks the DEM sub-steps for a profiling library: MPI_Pcontrol(2, m)
    // on entry (m DEM steps follow), MPI_Pcontrol(1) on exit
    struct subStepMark
    {
        explicit subStepMark(const int m)
        {
            if (MPI_Pcontrol) MPI_Pcontrol(2, m);
        }
        ~subStepMark()
        {
            if (MPI_Pcontrol) MPI_Pcontrol(1);
        }
    };

    // Distance from x to the interval [lo, hi] of one axis; a periodic axis
    // (period L) takes the nearest image
    Foam::scalar axisGap
    (
        const Foam::scalar x,
        const Foam::scalar lo,
        const Foam::scalar hi,
        const bool periodic,
        const Foam::scalar L
    )
    {
        auto gap = [&](const Foam::scalar y)
        {
            return y < lo ? lo - y : (y > hi ? y - hi : Foam::scalar(0));
        };
        Foam::scalar g = gap(x);
        if (periodic)
        {
            g = Foam::min(g, Foam::min(gap(x - L), gap(x + L)));
        }
        return g;
    }
}


namespace
{
    // slabs of the owned centres along the longest axis of their box: a
    // partner's ghosts for this processor are chosen within reach of one
    // slab's box (docs/parallel.md, "Ghost selection by slabs")
    const int nSlabs = 16;

    // The boxes a partner selects ghosts by, as [count, lo, hi, lo, hi...]:
    // the owned centres cut into nSlabs slabs of equal thickness along the
    // longest axis of their box (lo, hi), each slab's box of its centres
    // (empty slabs left out), then the inlets' boxes.  Their union holds
    // every owned centre, so a particle within reach of none of them
    // cannot touch one here
    std::vector<double> slabBoxes
    (
        const dem_arrays& a,
        const Foam::label n,
        const double lo[3],
        const double hi[3],
        const Foam::List<Foam::boundBox>& inlets
    )
    {
        int axis = 0;
        for (int k = 1; k < 3; ++k)
        {
            if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
        }
        const double L = hi[axis] - lo[axis];
        std::vector<double> box(6*nSlabs);
        for (int s = 0; s < nSlabs; ++s)
        {
            for (int k = 0; k < 3; ++k)
            {
                box[6*s + k] = Foam::GREAT;
                box[6*s + 3 + k] = -Foam::GREAT;
            }
        }
        for (Foam::label i = 0; i < n; ++i)
        {
            const double* x = a.x + 3*i;
            int s = L > 0 ? int((x[axis] - lo[axis])/L*nSlabs) : 0;
            s = s < 0 ? 0 : (s >= nSlabs ? nSlabs - 1 : s);
            double* b = box.data() + 6*s;
            for (int k = 0; k < 3; ++k)
            {
                b[k] = x[k] < b[k] ? x[k] : b[k];
                b[3 + k] = x[k] > b[3 + k] ? x[k] : b[3 + k];
            }
        }
        std::vector<double> out(1, 0);
        for (int s = 0; s < nSlabs; ++s)
        {
            if (box[6*s] > box[6*s + 3]) continue;
            out.insert(out.end(), &box[6*s], &box[6*s] + 6);
        }
        for (const Foam::boundBox& bb : inlets)
        {
            for (int k = 0; k < 3; ++k) out.push_back(bb.min()[k]);
            for (int k = 0; k < 3; ++k) out.push_back(bb.max()[k]);
        }
        out[0] = double((out.size() - 1)/6);
        return out;
    }
}


// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::processorGhosts::processorGhosts
(
    const polyMesh& mesh,
    demWorld& world,
    const FixedList<bool, 3>& periodic,
    const vector& boxLo,
    const vector& boxHi,
    const List<boundBox>& inletBoxes,
    const scalar& inletRadius,
    scalar& commTime
)
:
    mesh_(mesh),
    world_(world),
    periodic_(periodic),
    boxLo_(boxLo),
    boxHi_(boxHi),
    inletBoxes_(inletBoxes),
    inletRadius_(inletRadius),
    tComm_(commTime),
    setUp_(false),
    partners_(),
    rMax0_(0),
    skin0_(0),
    stray_(0),
    ownBox_(),
    allBoxes_(),
    isPartner_(),
    sendIds_(),
    sendIdx_(),
    sendReorder_(-1),
    mappedN_(0),
    newIndex_(),
    recvSet_(),
    recvCount_(),
    recvFirst_(),
    partnerSkin_(),
    sRef_(),
    S_(0),
    dLast_(0),
    renewAll_(true),
    dead_(false),
    ownStatus_(DEM_OK),
    failStep_(0),
    failMessage_(),
    stepCount_(0)
{}


// * * * * * * * * * * * * * * Private functions * * * * * * * * * * * * * //

namespace
{
    // message tags of the per-step header, of a renewed ghost set and of
    // the boxes a renewal selects by
    const int tagHeader = 7301;
    const int tagSet = 7302;
    const int tagBoxes = 7303;

    // header: flags, box of owned centres (lo, hi), largest radius, skin
    const int headerSize = 9;
    const int askRenew = 1, isDead = 2, hasStates = 4;
}


void Foam::processorGhosts::sendBytes
(
    const label toProc, const int tag, const char* data, const size_t n
)
{
    UOPstream::write
    (
        Pstream::commsTypes::nonBlocking, toProc, data, std::streamsize(n), tag
    );
}


void Foam::processorGhosts::receiveBytes
(
    const label fromProc, const int tag, DynamicList<char>& buf
)
{
    buf.clearStorage();
    label pos = 0;
    UIPstream is(Pstream::commsTypes::scheduled, fromProc, buf, pos, tag);
}


void Foam::processorGhosts::setup()
{
    const label nProcs = Pstream::nProcs();
    const label me = Pstream::myProcNo();
    const dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);

    // this processor's box: its mesh, its particles now (a particle in no
    // processor's cells stays on the master at the first distribution) and
    // the inlets
    ownBox_ = boundBox(mesh_.points(), false);
    scalar r = inletRadius_;
    for (label i = 0; i < n; ++i)
    {
        ownBox_.add(toVec(a.x, i));
        r = max(r, a.radius[i]);
    }
    for (const boundBox& bb : inletBoxes_)
    {
        ownBox_.add(bb);
    }
    const bool hasParticles = n > 0 || inletBoxes_.size();

    typedef FixedList<scalar, 9> boxInfo;
    List<boxInfo> all(nProcs);
    boxInfo& mine = all[me];
    for (direction k = 0; k < 3; ++k)
    {
        mine[k] = ownBox_.min()[k];
        mine[3 + k] = ownBox_.max()[k];
    }
    mine[6] = r;
    mine[7] = dem_world_skin(world_);
    mine[8] = hasParticles;
    Pstream::gatherList(all);
    Pstream::scatterList(all);

    rMax0_ = 0;
    scalar skinMin = GREAT, skinMax = 0;
    for (const boxInfo& b : all)
    {
        rMax0_ = max(rMax0_, b[6]);
        if (b[8] > 0 && b[7] > 0)
        {
            skinMin = min(skinMin, b[7]);
            skinMax = max(skinMax, b[7]);
        }
    }
    if (skinMax > skinMin*(1 + 1e-12))
    {
        FatalErrorInFunction
            << "the DEM skin differs between processors (" << skinMin
            << " to " << skinMax << " m): the automatic skin follows the "
            << "largest particle of each processor; set dem/skin in "
            << "constant/demProperties (e.g. 0.2 of the largest diameter)"
            << exit(FatalError);
    }
    // the automatic skin of the largest particle if none is known yet
    // (no particles before the first insertion)
    skin0_ = max(skinMax, 0.4*rMax0_);

    // a particle may stray one largest radius outside its processor's box
    // within a fluid step (it moves a small fraction of its diameter); a
    // particle of p touches one of q only if the boxes are within
    // 2 r_max + skin + 2 stray
    stray_ = rMax0_;
    const scalar reach = 2*rMax0_ + skin0_ + 2*stray_;
    DynamicList<label> partners;
    for (label q = 0; q < nProcs; ++q)
    {
        if (q == me) continue;
        scalar d2 = 0;
        for (direction k = 0; k < 3; ++k)
        {
            const scalar L = boxHi_[k] - boxLo_[k];
            auto gap = [&](const scalar shift)
            {
                return max
                (
                    scalar(0),
                    max
                    (
                        all[q][k] + shift - mine[3 + k],
                        mine[k] - all[q][3 + k] - shift
                    )
                );
            };
            scalar g = gap(0);
            if (periodic_[k])
            {
                g = min(g, min(gap(L), gap(-L)));
            }
            d2 += sqr(g);
        }
        if (d2 < sqr(reach))
        {
            partners.append(q);
        }
    }
    partners_.transfer(partners);
    allBoxes_.setSize(nProcs);
    isPartner_.setSize(nProcs, false);
    forAll(all, q)
    {
        allBoxes_[q] = boundBox
        (
            point(all[q][0], all[q][1], all[q][2]),
            point(all[q][3], all[q][4], all[q][5])
        );
    }
    for (const label q : partners_) isPartner_[q] = true;
    const label np = partners_.size();
    sendIds_.setSize(np);
    sendIdx_.setSize(np);
    recvSet_.setSize(np);
    recvCount_.setSize(np, 0);
    recvFirst_.setSize(np, 0);
    partnerSkin_.setSize(np, 0);
    sRef_.setSize(np, 0);
    Pout<< "demCoupling: DEM partners of processor " << me
        << " (contact reach " << reach << " m): "
        << flatOutput(partners_) << endl;
    setUp_ = true;
}


void Foam::processorGhosts::fail(const dem_status st, const std::string& why)
{
    if (dead_) return;
    dead_ = true;
    ownStatus_ = st;
    failStep_ = stepCount_;
    failMessage_ = why;
}


bool Foam::processorGhosts::talk
(
    const bool start,
    const bool stale,
    const scalar d
)
{
    const auto t0 = std::chrono::steady_clock::now();
    const label np = partners_.size();
    dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);
    const scalar skin = dem_world_skin(world_);

    // header: the box of the owned centres (the master's with the inlets),
    // the largest radius; each particle within its stray of this
    // processor's box (else a partner might be missing)
    FixedList<double, headerSize> hdr;
    for (direction k = 0; k < 3; ++k)
    {
        hdr[1 + k] = GREAT;
        hdr[4 + k] = -GREAT;
    }
    scalar rMax = inletRadius_;
    // a particle beyond its stray may touch particles of (or be a ghost
    // for) a processor that is not a partner: those within its reach of
    // that processor's box (whose particles stray as well)
    auto nearOther = [&](const label i)
    {
        const scalar reach = a.radius[i] + rMax0_ + skin0_ + stray_;
        forAll(allBoxes_, q)
        {
            if (q == Pstream::myProcNo() || isPartner_[q]) continue;
            scalar d2 = 0;
            for (direction k = 0; k < 3 && d2 < sqr(reach); ++k)
            {
                d2 += sqr
                (
                    axisGap
                    (
                        a.x[3*i + k], allBoxes_[q].min()[k],
                        allBoxes_[q].max()[k], periodic_[k],
                        boxHi_[k] - boxLo_[k]
                    )
                );
            }
            if (d2 < sqr(reach)) return true;
        }
        return false;
    };
    if (!dead_)
    {
        // the box of the owned centres and the largest radius (a cheap
        // pass); the particle-by-particle stray check below only when the
        // box reaches beyond the processor's box by stray/sqrt(3) on an
        // axis (else no centre's distance to it can exceed the stray)
        double lo0 = GREAT, lo1 = GREAT, lo2 = GREAT;
        double hi0 = -GREAT, hi1 = -GREAT, hi2 = -GREAT;
        for (label i = 0; i < n; ++i)
        {
            const double* x = a.x + 3*i;
            lo0 = x[0] < lo0 ? x[0] : lo0;
            lo1 = x[1] < lo1 ? x[1] : lo1;
            lo2 = x[2] < lo2 ? x[2] : lo2;
            hi0 = x[0] > hi0 ? x[0] : hi0;
            hi1 = x[1] > hi1 ? x[1] : hi1;
            hi2 = x[2] > hi2 ? x[2] : hi2;
            rMax = a.radius[i] > rMax ? a.radius[i] : rMax;
        }
        hdr[1] = lo0; hdr[2] = lo1; hdr[3] = lo2;
        hdr[4] = hi0; hdr[5] = hi1; hdr[6] = hi2;
        const scalar s3 = stray_/Foam::sqrt(3.0);
        bool inside = true;
        for (direction k = 0; k < 3 && n; ++k)
        {
            inside = inside
             && hdr[1 + k] >= ownBox_.min()[k] - s3
             && hdr[4 + k] <= ownBox_.max()[k] + s3;
        }
        for (label i = 0; i < n && !inside; ++i)
        {
            scalar g2 = 0;
            for (direction k = 0; k < 3; ++k)
            {
                const scalar x = a.x[3*i + k];
                g2 += sqr
                (
                    axisGap
                    (
                        x, ownBox_.min()[k], ownBox_.max()[k], periodic_[k],
                        boxHi_[k] - boxLo_[k]
                    )
                );
            }
            if (g2 > sqr(stray_) && nearOther(i))
            {
                fail
                (
                    DEM_ERR_STATE,
                    "particle " + std::to_string(a.id[i]) + " is "
                  + std::to_string(Foam::sqrt(g2)) + " m outside the box "
                    "of this processor's cells within one fluid step and "
                    "within contact reach of a processor that is not one "
                    "of its DEM partners; a decomposed run allows one "
                    "largest particle radius (" + std::to_string(stray_)
                  + " m) (docs/parallel.md, Neighbour-only communication): "
                    "reduce the fluid time step"
                );
                break;
            }
        }
        if (!dead_ && rMax > rMax0_*(1 + 1e-12))
        {
            FatalErrorInFunction
                << "a particle of radius " << rMax << " m is larger than the "
                << "largest at the start of the run (" << rMax0_ << " m), "
                << "which set the reach of the DEM partners; please report "
                << "this" << exit(FatalError);
        }
        if (!dead_ && skin > skin0_*(1 + 1e-12))
        {
            FatalErrorInFunction
                << "the DEM skin grew to " << skin << " m, beyond the "
                << skin0_ << " m of the start, which set the reach of the "
                << "DEM partners: set dem/skin in constant/demProperties "
                << "(e.g. 0.2 of the largest diameter)" << exit(FatalError);
        }
    }
    for (const boundBox& bb : inletBoxes_)
    {
        for (direction k = 0; k < 3; ++k)
        {
            hdr[1 + k] = min(hdr[1 + k], bb.min()[k]);
            hdr[4 + k] = max(hdr[4 + k], bb.max()[k]);
        }
    }
    hdr[7] = rMax;
    hdr[8] = skin;
    // the owned set or the ghosts changed since the last build (not just
    // moved): the ghost sets this side sent are out of date
    const bool changed = stale && dem_world_list_invalid(world_);
    // the rounding of the core's single-precision build positions, per
    // displacement measured against them
    const scalar rounding =
        1.2e-7*max(mag(ownBox_.min()), mag(ownBox_.max()));

    // the storage indices of the ids sent, in the order of the last
    // mapping (stamped in each particle's indexTag): after a re-sort or a
    // removal the tags give each one's new index (memory O(particles here))
    const int64_t reorders = dem_world_reorder_count(world_);
    auto mapIndices = [&]()
    {
        if (reorders == sendReorder_) return;
        newIndex_.setSize(mappedN_);
        newIndex_ = -1;
        for (label i = 0; i < n; ++i)
        {
            const int64_t old = a.tag[indexTag][i];
            if (old >= 0 && old < mappedN_) newIndex_[label(old)] = i;
        }
        forAll(sendIds_, k)
        {
            forAll(sendIdx_[k], j)
            {
                const label old = sendIdx_[k][j];
                const label i =
                    old >= 0 && old < mappedN_ ? newIndex_[old] : -1;
                if (i < 0 || a.id[i] != sendIds_[k][j])
                {
                    FatalErrorInFunction
                        << "ghost particle " << label(sendIds_[k][j])
                        << " for processor " << partners_[k] << " is no "
                        << "longer owned here between renewals; please "
                        << "report this" << exit(FatalError);
                }
                sendIdx_[k][j] = i;
            }
        }
        for (label i = 0; i < n; ++i)
        {
            a.tag[indexTag][i] = i;
        }
        mappedN_ = n;
        sendReorder_ = reorders;
    };

    // phase 1: a header to every partner, with the ghost states unless
    // the pair renews (or this processor stopped)
    const label req0 = UPstream::nRequests();
    List<std::vector<double>> out(np);
    std::vector<char> ask(np, 0);
    for (label k = 0; k < np; ++k)
    {
        scalar thr = skin;
        if (partnerSkin_[k] > 0 && (thr <= 0 || partnerSkin_[k] < thr))
        {
            thr = partnerSkin_[k];
        }
        const bool far = S_ - sRef_[k] + d > 0.5*thr;
        ask[k] = (start && renewAll_) || changed || far;
        if (!dead_)
        {
            counts_.askStale += changed;
            counts_.askSkin += !changed && far;
        }
        int flags = (ask[k] ? askRenew : 0) | (dead_ ? isDead : 0);
        const bool states = !ask[k] && !dead_;
        if (states) flags |= hasStates;
        std::vector<double>& o = out[k];
        o.assign(hdr.begin(), hdr.end());
        o[0] = flags;
        if (states)
        {
            mapIndices();
            const labelUList& idx = sendIdx_[k];
            o.resize(headerSize + 9*idx.size());
            double* v = o.data() + headerSize;
            forAll(idx, j)
            {
                const label i = idx[j];
                for (direction c = 0; c < 3; ++c)
                {
                    v[9*j + c] = a.x[3*i + c];
                    v[9*j + 3 + c] = a.v[3*i + c];
                    v[9*j + 6 + c] = a.omega[3*i + c];
                }
            }
        }
        sendBytes
        (
            partners_[k], tagHeader, reinterpret_cast<const char*>(o.data()),
            o.size()*sizeof(double)
        );
    }

    // their headers (sizes by probe)
    std::vector<char> renew(np, 0), fresh(np, 0);
    List<FixedList<double, headerSize>> theirs(np);
    List<std::vector<double>> states(np);
    bool partnerDead = false;
    DynamicList<char> buf;
    // the next message with tag from partner k into buf, the time blocked
    // added to the counts
    auto receiveTimed = [&](const label k, const int tag)
    {
        const auto w0 = std::chrono::steady_clock::now();
        receiveBytes(partners_[k], tag, buf);
        counts_.wait += std::chrono::duration<double>
        (
            std::chrono::steady_clock::now() - w0
        ).count();
    };
    for (label k = 0; k < np; ++k)
    {
        receiveTimed(k, tagHeader);
        const size_t nd = size_t(buf.size())/sizeof(double);
        const double* in = reinterpret_cast<const double*>(buf.cdata());
        if (nd < size_t(headerSize))
        {
            FatalErrorInFunction
                << "a DEM ghost header from processor " << partners_[k]
                << " holds " << label(nd) << " values, expected at least "
                << headerSize << "; please report this" << exit(FatalError);
        }
        for (int j = 0; j < headerSize; ++j) theirs[k][j] = in[j];
        const int flags = int(in[0]);
        const scalar theirSkin = in[8];
        if
        (
            skin > 0 && theirSkin > 0
         && mag(theirSkin - skin) > 1e-12*max(skin, theirSkin)
        )
        {
            FatalErrorInFunction
                << "the DEM skin differs between processors ("
                << min(skin, theirSkin) << " to " << max(skin, theirSkin)
                << " m): the automatic skin follows the largest particle "
                << "of each processor; set dem/skin in "
                << "constant/demProperties (e.g. 0.2 of the largest "
                << "diameter)" << exit(FatalError);
        }
        partnerSkin_[k] = theirSkin;
        partnerDead = partnerDead || (flags & isDead);
        renew[k] =
            !dead_ && !(flags & isDead) && (ask[k] || (flags & askRenew));
        if ((flags & hasStates) && !renew[k])
        {
            if (nd != size_t(headerSize + 9*recvCount_[k]))
            {
                FatalErrorInFunction
                    << "processor " << partners_[k] << " sent the states of "
                    << label((nd - headerSize)/9) << " ghosts, "
                    << recvCount_[k] << " expected; please report this"
                    << exit(FatalError);
            }
            states[k].assign(in + headerSize, in + nd);
            fresh[k] = true;
        }
    }

    // phase 2: the new ghost sets of the renewing pairs
    bool anyRenew = false;
    for (const char b : renew) anyRenew = anyRenew || b;
    List<std::vector<char>> sets(np);
    // the slab boxes of the owned centres, one buffer sent to every
    // renewing partner (kept until the sends complete)
    std::vector<double> mySlabs;
    if (anyRenew)
    {
        // the slab boxes to each renewing partner, theirs from it
        const double lo[3] = {hdr[1], hdr[2], hdr[3]};
        const double hi[3] = {hdr[4], hdr[5], hdr[6]};
        mySlabs = slabBoxes(a, n, lo, hi, inletBoxes_);
        for (label k = 0; k < np; ++k)
        {
            if (!renew[k]) continue;
            sendBytes
            (
                partners_[k], tagBoxes,
                reinterpret_cast<const char*>(mySlabs.data()),
                mySlabs.size()*sizeof(double)
            );
        }
        List<std::vector<double>> theirBoxes(np);
        for (label k = 0; k < np; ++k)
        {
            if (!renew[k]) continue;
            receiveTimed(k, tagBoxes);
            const size_t nd = size_t(buf.size())/sizeof(double);
            const double* in = reinterpret_cast<const double*>(buf.cdata());
            if (nd < 1 || nd != size_t(1 + 6*label(in[0])))
            {
                FatalErrorInFunction
                    << "the DEM slab boxes from processor " << partners_[k]
                    << " hold " << label(nd) << " values, which do not "
                    << "match their count; please report this"
                    << exit(FatalError);
            }
            theirBoxes[k].assign(in + 1, in + nd);
        }

        // the partners that keep their sets: their indices in this order
        // (the renewed ones' below are in it too; after a restore only
        // renewals happen, and the tags are gone)
        for (label k = 0; k < np; ++k)
        {
            if (renew[k])
            {
                sendIds_[k].clear();
                sendIdx_[k].clear();
            }
        }
        mapIndices();
        size_t gs = 0;
        if (n)
        {
            world_.check
            (
                dem_world_pack_ghost(world_, 0, nullptr, &gs),
                "dem_world_pack_ghost"
            );
        }
        for (label k = 0; k < np; ++k)
        {
            if (!renew[k]) continue;
            const FixedList<double, headerSize>& b = theirs[k];
            const scalar rPair = max(rMax, b[7]);
            std::vector<char>& o = sets[k];
            DynamicList<label>& chosen = sendIdx_[k];   // cleared above
            const std::vector<double>& slabs = theirBoxes[k];
            const label nb = label(slabs.size()/6);
            // squared distance of particle i to box [lo, hi], stopping
            // once beyond reach
            auto gap2 = [&]
            (
                const label i, const double* lo, const double* hi,
                const scalar reach
            )
            {
                scalar d2 = 0;
                for (direction c = 0; c < 3 && d2 < sqr(reach); ++c)
                {
                    d2 += sqr
                    (
                        axisGap
                        (
                            a.x[3*i + c], lo[c], hi[c], periodic_[c],
                            boxHi_[c] - boxLo_[c]
                        )
                    );
                }
                return d2;
            };
            for (label i = 0; i < n; ++i)
            {
                const scalar reach = a.radius[i] + rPair + skin0_;
                // within reach of the partner's box, then of one slab
                if (gap2(i, &b[1], &b[4], reach) >= sqr(reach)) continue;
                bool near = false;
                for (label j = 0; j < nb && !near; ++j)
                {
                    const double* sb = slabs.data() + 6*j;
                    near = gap2(i, sb, sb + 3, reach) < sqr(reach);
                }
                if (!near) continue;
                sendIds_[k].append(a.id[i]);
                chosen.append(i);
            }
            // one allocation for the set: count header, then the ghosts
            const int64_t count = chosen.size();
            o.assign(2*sizeof(int64_t) + size_t(count)*gs, 0);
            forAll(chosen, j)
            {
                size_t sz = gs;
                world_.check
                (
                    dem_world_pack_ghost
                    (
                        world_, size_t(chosen[j]),
                        o.data() + 2*sizeof(int64_t) + size_t(j)*gs, &sz
                    ),
                    "dem_world_pack_ghost"
                );
            }
            const int64_t pre[2] = {int64_t(gs), count};
            std::memcpy(o.data(), pre, sizeof pre);
            sendBytes(partners_[k], tagSet, o.data(), o.size());
        }
        for (label k = 0; k < np; ++k)
        {
            if (!renew[k]) continue;
            receiveTimed(k, tagSet);
            recvSet_[k].assign(buf.cdata(), buf.cdata() + buf.size());
            int64_t pre[2] = {0, 0};
            if (recvSet_[k].size() >= sizeof pre)
            {
                std::memcpy(pre, recvSet_[k].data(), sizeof pre);
            }
            if
            (
                recvSet_[k].size() < sizeof pre
             || recvSet_[k].size() != sizeof pre + size_t(pre[0]*pre[1])
            )
            {
                FatalErrorInFunction
                    << "a DEM ghost set from processor " << partners_[k]
                    << " has " << label(recvSet_[k].size()) << " bytes, "
                    << "which do not match its count; please report this"
                    << exit(FatalError);
            }
            recvCount_[k] = label(pre[1]);
        }
    }

    // the ghosts here: all sets unpacked again when any pair renewed (the
    // others then get this step's states), else the states set in place
    const bool unpack = anyRenew || (start && renewAll_ && !dead_);
    if (unpack)
    {
        world_.check(dem_world_clear_ghosts(world_), "dem_world_clear_ghosts");
        label ng = 0;
        for (label k = 0; k < np; ++k)
        {
            recvFirst_[k] = ng;
            const std::vector<char>& set = recvSet_[k];
            if (set.size() < 2*sizeof(int64_t)) continue;
            int64_t pre[2];
            std::memcpy(pre, set.data(), sizeof pre);
            for (int64_t j = 0; j < pre[1]; ++j)
            {
                world_.check
                (
                    dem_world_unpack_particle
                    (
                        world_, set.data() + sizeof pre + j*pre[0],
                        size_t(pre[0]), 1
                    ),
                    "dem_world_unpack_particle (ghost)"
                );
            }
            ng += label(pre[1]);
        }
        // a rebuild also without ghosts (clear_ghosts of none keeps the
        // list): the displacement bounds count on it
        world_.check
        (
            dem_world_invalidate_list(world_), "dem_world_invalidate_list"
        );
    }
    for (label k = 0; k < np; ++k)
    {
        if (!fresh[k] || !recvCount_[k]) continue;
        world_.check
        (
            dem_world_set_ghost_states
            (
                world_, size_t(recvFirst_[k]), size_t(recvCount_[k]),
                states[k].data()
            ),
            "dem_world_set_ghost_states"
        );
    }
    // the ghosts here may have moved more than half a skin since this
    // side's last list build (the core's criterion for the owned ones):
    // rebuild it (no renewal needed)
    scalar thrAll = skin;
    for (const scalar sk : partnerSkin_)
    {
        if (sk > 0 && (thrAll <= 0 || sk < thrAll)) thrAll = sk;
    }
    const bool partnerFar =
        !dead_ && !unpack
     && dem_world_ghost_displacement(world_) + rounding > 0.5*thrAll;
    if (partnerFar && !stale && !unpack && !dead_)
    {
        world_.check
        (
            dem_world_invalidate_list(world_), "dem_world_invalidate_list"
        );
    }
    UPstream::waitRequests(req0);

    // the displacement bounds (processorGhosts.C, top)
    const bool rebuilt = !dead_ && (stale || unpack || partnerFar);
    if (start)
    {
        renewAll_ = false;
    }
    if (rebuilt)
    {
        S_ += d + rounding;
        for (label k = 0; k < np; ++k)
        {
            if (renew[k]) sRef_[k] = S_;
        }
        counts_.partnerRebuilds += partnerFar && !stale && !unpack;
    }
    // the displacement since the last build (the next call's start)
    dLast_ = rebuilt ? 0 : d;
    if (start)
    {
        ++counts_.calls;
        for (const char b : renew) counts_.startRenewals += b;
    }
    else
    {
        ++counts_.steps;
        counts_.rebuilds += rebuilt;
        for (const char b : renew) counts_.renewals += b;
        counts_.ghosts += double(world_.arrays().n_ghost);
        counts_.owned += double(n);
    }
    if (partnerDead && !dead_)
    {
        // a partner stopped: its ghosts here are no longer refreshed
        dead_ = true;
    }
    tComm_ += std::chrono::duration<scalar>
    (
        std::chrono::steady_clock::now() - t0
    ).count();
    return rebuilt;
}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

dem_status Foam::processorGhosts::step(const label m)
{
    if (!setUp_)
    {
        // once, outside the marked DEM sub-steps (a collective)
        setup();
    }
    const subStepMark mark(static_cast<int>(m));

    auto why = [&](const dem_status st)
    {
        return std::string(dem_status_string(st)) + ": " + world_.lastError();
    };
    // ghosts before the first drift too: it may rebuild the neighbour list
    // (after a migration), which must see them to keep the contact history
    // of pairs across processors.  A pair renews here only if either side's
    // owned set changed since the last step (migration, insertion, removal,
    // a restored checkpoint: the list is invalid) or its half skin is
    // used up; on the first call every pair renews
    talk(true, !dead_ && dem_world_list_stale(world_), dLast_);
    for (label s = 0; s < m; ++s)
    {
        ++stepCount_;
        bool pending = false;
        if (!dead_)
        {
            // the start checks once per call, as dem_world_step(w, m)
            const dem_status st = world_.tryDrift(s == 0);
            if (st != DEM_OK) fail(st, why(st));
            else pending = true;
        }
        const bool stale = pending && dem_world_list_stale(world_);
        const scalar d = pending ? dem_world_drift_displacement(world_) : 0;
        talk(false, stale, d);
        if (pending)
        {
            // also after a partner stopped (completes the step)
            const dem_status st = world_.tryForces();
            if (st != DEM_OK) fail(st, why(st));
        }
    }
    if (!dead_)
    {
        // the contacts of the last step while the ghosts are there
        world_.captureContacts();
    }
    return ownStatus_;
}


std::string Foam::processorGhosts::summary() const
{
    const counts& c = counts_;
    const double s = max(c.steps, label(1));
    char line[512];
    std::snprintf
    (
        line, sizeof line,
        "ghost exchange: %ld DEM steps in %ld calls, partners %ld; pair "
        "renewals at the calls' start %ld; per DEM step: pair renewals "
        "%.4f (this side asked, start included: owned set changed %.4f, "
        "half skin %.4f), list rebuilds %.4f (for a partner's ghosts "
        "%.4f), owned %.0f, ghosts %.0f (%.1f %%); blocked in receives "
        "%.3f s",
        long(c.steps), long(c.calls), long(partners_.size()),
        long(c.startRenewals),
        c.renewals/s, c.askStale/s, c.askSkin/s, c.rebuilds/s,
        c.partnerRebuilds/s,
        c.owned/s, c.ghosts/s, 100*c.ghosts/max(c.owned, 1.0), c.wait
    );
    return line;
}


dem_status Foam::processorGhosts::agree(std::string& failure)
{
    const label nProcs = Pstream::nProcs();
    const label me = Pstream::myProcNo();
    // the earliest DEM step, then the lowest processor
    label first = ownStatus_ != DEM_OK ? failStep_*nProcs + me : labelMax;
    reduce(first, minOp<label>());
    dem_status st = DEM_OK;
    if (first != labelMax)
    {
        List<string> why(nProcs);
        if (ownStatus_ != DEM_OK)
        {
            why[me] = failMessage_;
        }
        Pstream::gatherList(why);
        Pstream::scatterList(why);
        const label p = first % nProcs;
        failure = "DEM core: " + why[p] + " (processor "
          + std::to_string(p) + ")";
        st = ownStatus_ != DEM_OK ? ownStatus_ : DEM_ERR_STATE;
    }
    if (st != DEM_OK)
    {
        // the fluid step is undone from its checkpoint: every pair renews
        renewAll_ = true;
    }
    dead_ = false;
    ownStatus_ = DEM_OK;
    failStep_ = 0;
    failMessage_.clear();
    stepCount_ = 0;
    return st;
}


// ************************************************************************* //
