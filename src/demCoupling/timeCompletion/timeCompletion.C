/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "timeCompletion.H"
#include "OFstream.H"
#include "Pstream.H"
#include "PstreamReduceOps.H"

namespace
{

// The case's times (without constant/), sorted
Foam::instantList caseTimes(const Foam::Time& runTime)
{
    Foam::instantList all(runTime.times());
    Foam::DynamicList<Foam::instant> t(all.size());
    for (const Foam::instant& i : all)
    {
        if (i.name() != runTime.constant()) t.append(i);
    }
    return Foam::instantList(std::move(t));
}

// Whether the current time is the first of the case's times t.  Within
// 1e-10 relative, not instant::equal's 1e-15: a time's uniform/time value
// may differ from its directory name in the last digits (2.499999999998888
// in 2.5/), and two written times are at least a step apart
bool isFirst(const Foam::Time& runTime, const Foam::instantList& t)
{
    if (t.empty()) return true;
    const Foam::scalar a = t.first().value(), b = runTime.value();
    return Foam::mag(a - b) <= 1e-10*Foam::max(Foam::scalar(1), Foam::mag(b));
}

} // End anonymous namespace


const Foam::word& Foam::timeCompletion::markerName()
{
    static const word name("demWriteComplete");
    return name;
}


bool Foam::timeCompletion::isComplete(const fileName& timeDir)
{
    return isFile(timeDir/"uniform"/markerName());
}


void Foam::timeCompletion::mark(const Time& runTime)
{
    // every processor has written its part before any marks the time
    if (Pstream::parRun())
    {
        label written = 1;
        reduce(written, sumOp<label>());
    }
    const fileName dir(runTime.timePath()/"uniform");
    mkDir(dir);
    OFstream os(dir/markerName());
    os  << "// demFoam: every field, the cloud and the DEM state of time "
        << runTime.timeName() << " are written" << nl;
}


bool Foam::timeCompletion::isInitial(const Time& runTime)
{
    return returnReduce
    (
        isFirst(runTime, caseTimes(runTime))
     && !isComplete(runTime.timePath()),
        andOp<bool>()
    );
}


void Foam::timeCompletion::checkStart(const Time& runTime)
{
    const instantList t(caseTimes(runTime));
    const bool ok = isFirst(runTime, t) || isComplete(runTime.timePath());
    if (returnReduce(ok, andOp<bool>()))
    {
        return;
    }

    // the latest complete time before the start, on this processor
    word lastComplete;
    for (const instant& i : t)
    {
        if (i.value() < runTime.value() && isComplete(runTime.path()/i.name()))
        {
            lastComplete = i.name();
        }
    }
    FatalErrorInFunction
        << "the start time " << runTime.timePath() << " is incomplete: it "
        << "has no uniform/" << markerName() << ", which demFoam writes "
        << "after every field, the cloud and the DEM state of a time (a "
        << "run stopped or killed while writing it, or a time not written "
        << "by demFoam).  "
        << (
               lastComplete.empty()
             ? std::string("There is no complete time before it")
             : "The last complete time is " + lastComplete
           ).c_str()
        << ": delete " << runTime.timeName() << " (and any later time) and "
        << "start again (startFrom latestTime), or set startTime to a "
        << "complete time" << exit(FatalError);
}


// ************************************************************************* //
