/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "demWorld.H"
#include <cfenv>
#include <unordered_map>
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
    const dem_status s = withoutTraps([&]{ return dem_world_step(w_, nsteps); });
    if (s == DEM_OK) captureContacts();
    return s;
}


dem_status Foam::demWorld::tryDrift(const bool first)
{
    return withoutTraps
    (
        [&]
        {
            return first
              ? dem_world_step_drift(w_) : dem_world_step_drift_next(w_);
        }
    );
}


dem_status Foam::demWorld::tryForces()
{
    return withoutTraps([&]{ return dem_world_step_forces(w_); });
}


void Foam::demWorld::step(const int64_t nsteps, const char* what)
{
    check(tryStep(nsteps), what);
}


void Foam::demWorld::keepContacts()
{
    check(dem_world_record_contacts(w_, 1), "dem_world_record_contacts");
    keepContacts_ = true;
}


void Foam::demWorld::captureContacts()
{
    if (!keepContacts_) return;
    contactsKnown_ = false;
    contacts_.clear();
    contactPoints_.clear();
    size_t n = 0;
    if (dem_world_contacts(w_, nullptr, 0, &n) != DEM_OK) return;
    contacts_.resize(n);
    check(dem_world_contacts(w_, contacts_.data(), n, &n), "dem_world_contacts");

    // index by id, owned particles first (a periodic ghost image of an
    // owned particle then maps to the owned copy)
    const dem_arrays a = arrays();
    const size_t nAll = a.n_owned + a.n_ghost;
    std::unordered_map<int64_t, size_t> index(2*nAll + 1);
    for (size_t i = 0; i < nAll; ++i)
    {
        index.emplace(a.id[i], i);
    }
    contactPoints_.resize(3*n);
    for (size_t k = 0; k < n; ++k)
    {
        dem_contact& c = contacts_[k];
        if (!c.wall && c.id_a > c.id_b)
        {
            std::swap(c.id_a, c.id_b);
            for (int d = 0; d < 3; ++d)
            {
                c.normal[d] = -c.normal[d];
                c.force_n[d] = -c.force_n[d];
                c.force_t[d] = -c.force_t[d];
            }
        }
        const auto it = index.find(c.id_a);
        if (it == index.end())
        {
            FatalErrorInFunction
                << "contact of particle " << c.id_a << " that this "
                << "processor does not hold" << exit(FatalError);
        }
        const size_t i = it->second;
        const double r = a.radius[i];
        const double s = c.wall ? r - c.overlap - 1e-6*r : r - 0.5*c.overlap;
        for (int d = 0; d < 3; ++d)
        {
            contactPoints_[3*k + d] = a.x[3*i + d] - s*c.normal[d];
        }
    }
    contactsStep_ = dem_world_step_count(w_);
    contactsKnown_ = true;
}
