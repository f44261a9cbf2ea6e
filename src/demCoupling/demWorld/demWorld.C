/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "demWorld.H"
#include <cfenv>
#include "error.H"
#include "messageStream.H"

namespace
{
    void demLogToFoam(dem_log_level level, const char* msg, void*)
    {
        if (level == DEM_LOG_WARNING)
        {
            WarningInFunction << "DEM core: " << msg << Foam::endl;
        }
        else if (level == DEM_LOG_INFO)
        {
            Foam::Info<< "DEM core: " << msg << Foam::endl;
        }
    }
}


Foam::demWorld::demWorld()
:
    w_(nullptr)
{
    const dem_status s = dem_world_create(&w_);
    if (s != DEM_OK || !w_)
    {
        FatalErrorInFunction
            << "dem_world_create failed: " << dem_status_string(s)
            << exit(FatalError);
    }
    dem_world_set_logger(w_, demLogToFoam, nullptr);
}


Foam::demWorld::~demWorld()
{
    dem_world_destroy(&w_);
}


void Foam::demWorld::check(dem_status s, const char* call) const
{
    if (s != DEM_OK)
    {
        FatalErrorInFunction
            << "DEM core call " << call << " failed with status "
            << dem_status_string(s) << nl
            << "    " << dem_world_last_error(w_)
            << exit(FatalError);
    }
}


dem_arrays Foam::demWorld::arrays() const
{
    dem_arrays a;
    check(dem_world_arrays(w_, &a), "dem_world_arrays");
    return a;
}


namespace
{
    // Call into the core with floating-point traps suspended
    template<class Call>
    dem_status withoutTraps(const Call& call)
    {
        std::fenv_t env;
        std::feholdexcept(&env);            // save and suspend traps
        const dem_status s = call();
        std::feclearexcept(FE_ALL_EXCEPT);
        std::fesetenv(&env);                // restore OpenFOAM's traps
        return s;
    }
}


dem_status Foam::demWorld::tryStep(const int64_t nsteps)
{
    return withoutTraps([&]{ return dem_world_step(w_, nsteps); });
}


dem_status Foam::demWorld::tryDrift()
{
    return withoutTraps([&]{ return dem_world_step_drift(w_); });
}


dem_status Foam::demWorld::tryForces()
{
    return withoutTraps([&]{ return dem_world_step_forces(w_); });
}


void Foam::demWorld::step(const int64_t nsteps, const char* what)
{
    check(tryStep(nsteps), what);
}
