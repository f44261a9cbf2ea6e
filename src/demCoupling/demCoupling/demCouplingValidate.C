/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Description
    Checks of constant/demProperties before anything is built or written
    (docs/demProperties.md, "Checks before the first step"): every keyword of every scope is known
    (else the nearest valid name is suggested), every value has the right
    type and range, model, law, material and patch names exist.  A second
    check, after the initial particles are placed and before the first
    step, tests the state: particle centres inside the mesh, no overlap
    above maxInitialOverlap, dem/timeStep below the safe fraction of the
    contact time.  Every message names the file, the keyword, the value and
    what is allowed.

\*---------------------------------------------------------------------------*/

#include "demCoupling.H"
#include "demCouplingTools.H"
#include "extraForce.H"
#include "keyChecker.H"
#include "OStringStream.H"
#include <cmath>
#include <unordered_map>

namespace
{

using namespace Foam;
using Foam::demTools::toVec;

using kind = keySpec::kind;
const auto num = &keySpec::num;
const auto any = &keySpec::any;
const auto choice = &keySpec::choice;

const double inf = HUGE_VAL;


const auto numText = &keyChecker::numText;
const auto listText = &keyChecker::listText;
const auto valueText = &keyChecker::valueText;


List<keySpec> materialKeys()
{
    return List<keySpec>
    ({
        num("youngsModulus", kind::Scalar, 0, inf, true, false),
        num("poissonRatio", kind::Scalar, 0, 0.5, false, true),
        num("stiffnessN", kind::Scalar, 0, inf, true, false),
        num("stiffnessT", kind::Scalar, 0, inf, true, false),
        num("friction", kind::Scalar, 0, inf, false, false),
        num("rollingFriction", kind::Scalar, 0, inf, false, false),
        num("restitution", kind::Scalar, 0, 1, true, false),
        num("damping", kind::Scalar, 0, inf, false, false),
        any("rigid", kind::Bool)
    });
}


//- diameter / density: a positive number or a distribution dictionary
void checkDistribution
(
    const keyChecker& chk,
    const dictionary& parent,
    const word& scope,
    const word& key
)
{
    const entry* ep = parent.findEntry(key, keyType::LITERAL);
    if (!ep)
    {
        chk.require(parent, scope, key, "a number or a distribution { type ...; }");
    }
    if (!ep->isDict()) return;      // the number was checked (> 0) already

    const dictionary& d = ep->dict();
    const word sc(scope + key + "/");
    const wordList types({"fixed", "uniform", "normal", "discrete"});
    chk.require(d, sc, "type", listText(types));
    chk.checkValue(d, sc, *d.findEntry("type", keyType::LITERAL), choice("type", types));
    const word type(d.get<word>("type"));
    const keySpec positive = num("", kind::Scalar, 0, inf, true, false);
    auto pos = [&](const char* n)
    {
        keySpec k(positive);
        k.name = n;
        return k;
    };
    List<keySpec> keys({choice("type", types)});
    if (type == "fixed") keys.append(pos("value"));
    if (type == "uniform") { keys.append(pos("min")); keys.append(pos("max")); }
    if (type == "normal")
    {
        keys.append(pos("mean"));
        keys.append(num("stdDev", kind::Scalar, 0, inf, false, false));
    }
    if (type == "discrete")
    {
        keys.append(any("values", kind::List));
        keys.append(any("weights", kind::List));
    }
    chk.check(d, sc, keys);
    for (const keySpec& k : keys)
    {
        chk.require(d, sc, k.name, "for type " + type);
    }
    if (type == "uniform" && d.get<scalar>("max") < d.get<scalar>("min"))
    {
        chk.fail(d, sc, "max", numText(d.get<scalar>("max")),
                 "below min " + numText(d.get<scalar>("min")) + "; allowed max >= min");
    }
    if (type == "normal" && d.get<scalar>("mean") - 3*d.get<scalar>("stdDev") <= 0)
    {
        chk.fail(d, sc, "stdDev", numText(d.get<scalar>("stdDev")),
                 "mean - 3 stdDev must stay > 0 (the normal distribution is truncated at 3 stdDev)");
    }
    if (type == "discrete")
    {
        const scalarField vals(d.get<scalarField>("values"));
        const scalarField wts(d.get<scalarField>("weights"));
        if (vals.empty() || vals.size() != wts.size())
        {
            chk.fail(d, sc, "weights", std::to_string(wts.size()) + " entries",
                     "values (" + std::to_string(vals.size())
                   + " entries) and weights need the same non-zero length");
        }
        if (min(vals) <= 0 || min(wts) < 0 || sum(wts) <= 0)
        {
            chk.fail(d, sc, "values", "", "allowed values > 0, weights >= 0 with a positive sum");
        }
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Checks * * * * * * * * * * * * * * * * //

bool Foam::demCoupling::checkDictionary
(
    const dictionary& dict,
    const fileName& file,
    const fvMesh& mesh
)
{
    const keyChecker chk(file);
    const wordList patches(mesh.boundaryMesh().names());

    const wordList formulations
    (
        couplingFormulation::dictionaryConstructorTablePtr_->sortedToc()
    );
    const wordList drags(dragModel::dictionaryConstructorTablePtr_->sortedToc());
    const wordList voidages
    (
        voidageModel::dictionaryConstructorTablePtr_->sortedToc()
    );
    const wordList forces(extraForce::dictionaryConstructorTablePtr_->sortedToc());

    List<keySpec> top
    ({
        choice("formulation", formulations),
        choice("dragModel", drags),
        choice("dragScheme", wordList({"perParticle", "cellMean"})),
        choice("dragReaction", wordList({"exact", "local"})),
        choice("voidageModel", voidages),
        num("epsMin", kind::Scalar, 0, 1, true, true),
        num("voidageRelaxationTime", kind::Scalar, 0, inf, false, false),
        num("voidageSmoothingLength", kind::Scalar, 0, inf, false, false),
        num("etaWarning", kind::Scalar, 0, inf, false, false),
        num("insertionRampTime", kind::Scalar, 0, inf, false, false),
        any("frozen", kind::Bool),
        any("writeContacts", kind::Bool),
        num("maxWalkSteps", kind::Label, 1, inf, false, false),
        any("extraForces", kind::List),
        any("periodicDriving", kind::Dict),
        any("fluidInletPatches", kind::List),
        any("outletPatches", kind::List),
        any("wallPatches", kind::List),
        any("wallMaterial", kind::Word),
        num("settlingTime", kind::Scalar, 0, inf, false, false),
        any("dem", kind::Dict),
        any("materials", kind::Dict),
        any("materialPairs", kind::Dict),
        any("initialParticles", kind::Dict),
        any("inlets", kind::Dict),
        num("progressInterval", kind::Scalar, 0, inf, false, false),
        num("progressSteps", kind::Label, 0, inf, false, false),
        num("maxLostParticles", kind::Label, 0, inf, false, false),
        num("maxInitialOverlap", kind::Scalar, 0, 1, false, true)
    });
    // coefficient dictionaries of every model (only the selected one is used)
    for (const wordList* models : {&drags, &voidages, &forces})
    {
        for (const word& m : *models)
        {
            top.append(keySpec{m + "Coeffs", kind::Dict, 0, 0, false, false, wordList()});
        }
    }
    chk.check(dict, "", top);
    chk.require(dict, "", "formulation", listText(formulations));
    chk.require(dict, "", "dragModel", listText(drags));
    chk.require(dict, "", "dem", "dem { timeStep ...; }");
    chk.require(dict, "", "materials", "materials { name { ... } }");
    chk.require(dict, "", "wallMaterial", "a name from materials");

    // model coefficients: each model lists its own (keySpec.H)
    for (const wordList* models : {&drags, &voidages, &forces})
    {
        for (const word& m : *models)
        {
            const word name(m + "Coeffs");
            if (dict.isDict(name))
            {
                chk.check(dict.subDict(name), name + "/", keySpec::coeffKeysOf(name));
            }
        }
    }

    for (const word& f : dict.getOrDefault<wordList>("extraForces", wordList()))
    {
        chk.checkName(dict, "", "extraForces", f, forces, "force");
    }
    for (const char* key : {"fluidInletPatches", "outletPatches", "wallPatches"})
    {
        for (const word& p : dict.getOrDefault<wordList>(key, wordList()))
        {
            chk.checkName(dict, "", key, p, patches, "patch in the mesh");
        }
    }

    if (dict.isDict("periodicDriving"))
    {
        const dictionary& d = dict.subDict("periodicDriving");
        chk.check(d, "periodicDriving/", List<keySpec>({
            any("superficialVelocity", kind::Vector),
            num("relaxation", kind::Scalar, 0, 1, true, false),
            any("initialGradient", kind::Vector)}));
        chk.require(d, "periodicDriving/", "superficialVelocity", "a vector (x y z)");
    }

    // dem { }
    const dictionary& dem = dict.subDict("dem");
    wordList laws;
    for (int l = 0; l < DEM_CONTACT_LAW_COUNT; ++l)
    {
        const char* nm = dem_contact_law_name(dem_contact_law(l));
        if (nm) laws.append(word(nm));
    }
    chk.check(dem, "dem/", List<keySpec>({
        choice("contactLaw", laws),
        num("timeStep", kind::Scalar, 0, inf, true, false),
        num("dragUpdateInterval", kind::Label, 0, inf, false, false),
        any("fitToFluidStep", kind::Bool),
        num("maxDtFraction", kind::Scalar, 0, inf, true, false),
        num("maxOverlapRatio", kind::Scalar, 0, inf, true, false),
        num("skin", kind::Scalar, 0, inf, false, false),
        num("domainMargin", kind::Scalar, 0, inf, false, false),
        num("seed", kind::Label, 0, inf, false, false),
        num("impactSpeed", kind::Scalar, 0, inf, false, false),
        any("dampingPredicted", kind::Bool)}));
    chk.require(dem, "dem/", "timeStep", "the DEM time step [s] > 0");

    // materials
    const dictionary& mats = dict.subDict("materials");
    wordList materialNames;
    // rigid materials (rigid yes): for walls only
    wordList rigidNames;
    for (const entry& e : mats)
    {
        if (!e.isDict())
        {
            chk.fail(mats, "materials/", e.keyword(), valueText(e),
                     "expected a material dictionary name { youngsModulus ...; }");
        }
        const word sc("materials/" + e.keyword() + "/");
        chk.check(e.dict(), sc, materialKeys());
        if (!e.dict().found("restitution") && !e.dict().found("damping"))
        {
            chk.fail(e.dict(), sc, "restitution", "",
                     "missing; give restitution (0 < e <= 1) or damping (>= 0)");
        }
        materialNames.append(e.keyword());
        if (e.dict().getOrDefault<bool>("rigid", false))
        {
            rigidNames.append(e.keyword());
        }
    }
    if (materialNames.empty())
    {
        chk.fail(mats, "", "materials", "{ }", "no material given; give at least one");
    }
    chk.checkName
    (
        dict, "", "wallMaterial", dict.get<word>("wallMaterial"),
        materialNames, "material"
    );

    if (dict.isDict("materialPairs"))
    {
        List<keySpec> keys(materialKeys());
        keys.append(any("materials", kind::List));
        for (const entry& e : dict.subDict("materialPairs"))
        {
            const word sc("materialPairs/" + e.keyword() + "/");
            if (!e.isDict())
            {
                chk.fail(dict.subDict("materialPairs"), "materialPairs/",
                         e.keyword(), valueText(e), "expected a dictionary");
            }
            chk.check(e.dict(), sc, keys);
            chk.require(e.dict(), sc, "materials", "two names from materials");
            const wordList names(e.dict().get<wordList>("materials"));
            if (names.size() != 2)
            {
                chk.fail(e.dict(), sc, "materials", listText(names),
                         "give two material names");
            }
            for (const word& n : names)
            {
                chk.checkName(e.dict(), sc, "materials", n, materialNames, "material");
            }
        }
    }

    // initialParticles and inlets
    // a particle material: one of materials, and not rigid (walls only)
    auto particleMaterial = [&](const dictionary& d, const word& sc)
    {
        const word m(d.get<word>("material"));
        chk.checkName(d, sc, "material", m, materialNames, "material");
        if (rigidNames.found(m))
        {
            chk.fail(d, sc, "material", m,
                     "a material without rigid yes (rigid materials are for walls only)");
        }
    };
    const keySpec positive = num("", kind::Distribution, 0, inf, true, false);
    auto dist = [&](const char* n)
    {
        keySpec k(positive);
        k.name = n;
        return k;
    };
    if (dict.isDict("initialParticles"))
    {
        const dictionary& all = dict.subDict("initialParticles");
        word indexedBefore;
        for (const entry& e : all)
        {
            const word sc("initialParticles/" + e.keyword() + "/");
            if (!e.isDict())
            {
                chk.fail(all, "initialParticles/", e.keyword(), valueText(e),
                         "expected a dictionary name { type box; ... }");
            }
            const dictionary& d = e.dict();
            const wordList types({"box", "cylinder", "list"});
            chk.require(d, sc, "type", listText(types));
            chk.check(d, sc, List<keySpec>({choice("type", types)
                , any("min", kind::Vector), any("max", kind::Vector)
                , any("base", kind::Vector), any("axis", kind::Vector)
                , num("radius", kind::Scalar, 0, inf, true, false)
                , num("length", kind::Scalar, 0, inf, true, false)
                , any("insideMesh", kind::Bool)
                , choice("arrangement", wordList({"random", "lattice", "randomBlocks"}))
                , num("number", kind::Label, 1, inf, false, false)
                , any("positions", kind::List)
                , dist("diameter"), dist("density")
                , any("material", kind::Word), any("velocity", kind::Vector)
                , any("angularVelocity", kind::Vector)}));
            const word type(d.get<word>("type"));
            const wordList need
            (
                type == "box"
              ? wordList({"min", "max", "number", "diameter", "density", "material"})
              : type == "cylinder"
              ? wordList({"base", "axis", "radius", "length", "number", "diameter", "density", "material"})
              : wordList({"positions", "diameter", "density", "material"})
            );
            for (const word& k : need)
            {
                chk.require(d, sc, k, "for type " + type);
            }
            if (type == "box" || type == "cylinder")
            {
                checkDistribution(chk, d, sc, "diameter");
                checkDistribution(chk, d, sc, "density");
            }
            if (type == "box")
            {
                const vector lo(d.get<vector>("min")), hi(d.get<vector>("max"));
                if (lo.x() >= hi.x() || lo.y() >= hi.y() || lo.z() >= hi.z())
                {
                    OStringStream os;
                    os << hi;
                    chk.fail(d, sc, "max", os.str(), "allowed max > min in every component");
                }
            }
            else if (type == "cylinder" && mag(d.get<vector>("axis")) < VSMALL)
            {
                chk.fail(d, sc, "axis", "(0 0 0)", "allowed a non-zero vector (its direction is the cylinder's axis)");
            }
            else if (type == "list" && d.found("insideMesh"))
            {
                chk.fail(d, sc, "insideMesh", "", "only for type box or cylinder (a list's centres must all be inside the mesh)");
            }
            if (type == "list" && d.found("arrangement"))
            {
                chk.fail(d, sc, "arrangement", d.get<word>("arrangement"), "only for type box or cylinder");
            }
            // lattice and randomBlocks compute each particle from its index:
            // a processor keeps only those near it
            const word arrangement(d.getOrDefault<word>("arrangement", "random"));
            const bool indexed = arrangement != "random";
            if (indexed && d.getOrDefault<bool>("insideMesh", false))
            {
                chk.fail(d, sc, "insideMesh", "yes", "not with arrangement " + arrangement + " (it fills the box or cylinder itself; use arrangement random to take the mesh's shape)");
            }
            if (!indexed && type != "list" && Pstream::parRun() && indexedBefore != "")
            {
                // every processor draws a random fill against all particles
                // before it, and a lattice fill keeps only those near it
                chk.fail(d, sc, "arrangement", arrangement, "a random fill after the " + indexedBefore + " in a decomposed run; put the lattice and randomBlocks entries after the random ones, or give this one arrangement lattice or randomBlocks");
            }
            if (indexed && indexedBefore == "")
            {
                indexedBefore = arrangement + " fill " + e.keyword();
            }
            if
            (
                type != "list" && Pstream::parRun()
             && d.found("insideMesh") && d.get<bool>("insideMesh")
            )
            {
                // the test sees this processor's cells only: the processors
                // would draw different sets
                chk.fail(d, sc, "insideMesh", "yes", "not in a decomposed run (each processor sees only its own cells, so each would draw another set); run serially to the first write and continue decomposed from that time (docs/parallel.md, \"From serial to parallel\")");
            }
            if (type == "list")
            {
                for (const char* k : {"diameter", "density", "angularVelocity"})
                {
                    if (d.isDict(k))
                    {
                        chk.fail(d, sc, k, "{ ... }", "type list takes a number, not a distribution");
                    }
                }
                for (const vector& x : d.get<List<vector>>("positions"))
                {
                    if (!std::isfinite(x.x() + x.y() + x.z()))
                    {
                        chk.fail(d, sc, "positions", "", "contains a non-finite position");
                    }
                }
            }
            particleMaterial(d, sc);
        }
    }
    if (dict.isDict("inlets"))
    {
        const dictionary& all = dict.subDict("inlets");
        for (const entry& e : all)
        {
            const word sc("inlets/" + e.keyword() + "/");
            if (!e.isDict())
            {
                chk.fail(all, "inlets/", e.keyword(), valueText(e),
                         "expected a dictionary name { patch ...; }");
            }
            const dictionary& d = e.dict();
            chk.check(d, sc, List<keySpec>({any("patch", kind::Word)
                , choice("rateType", wordList({"number", "mass"}))
                , num("rate", kind::Scalar, 0, inf, false, false)
                , num("start", kind::Scalar, 0, inf, false, false)
                , num("end", kind::Scalar, 0, inf, false, false)
                , dist("diameter"), dist("density")
                , any("material", kind::Word), any("velocity", kind::Vector)}));
            for (const char* k : {"patch", "rate", "diameter", "density", "material"})
            {
                chk.require(d, sc, k, "for an inlet");
            }
            checkDistribution(chk, d, sc, "diameter");
            checkDistribution(chk, d, sc, "density");
            chk.checkName(d, sc, "patch", d.get<word>("patch"), patches, "patch in the mesh");
            particleMaterial(d, sc);
        }
    }

    return true;
}


void Foam::demCoupling::checkInitialState()
{
    const keyChecker chk(dict_.instance()/dict_.name());
    dem_arrays a = world_.arrays();
    const label n = label(a.n_owned);

    // centres inside the mesh (decomposed: in some processor's cells; each
    // processor holds the particles near its mesh here, so the whole set
    // is checked and every overlapping pair is seen by some processor)
    const labelList owner(decomposition_.cellOwners());
    const bool near = decomposition_.nearOnly();
    const label me = Pstream::myProcNo();
    label nOut = 0, nOwn = 0, firstOut = -1;
    for (label i = 0; i < n; ++i)
    {
        if (owner[i] < 0)
        {
            if (firstOut < 0 || a.id[i] < a.id[firstOut]) firstOut = i;
            ++nOut;
        }
        nOwn += owner[i] == me;
    }
    const label nAll = near ? decomposition_.total() : n;
    if (near && returnReduce(nOwn, sumOp<label>()) > nAll)
    {
        FatalErrorInFunction
            << "the processors hold " << returnReduce(nOwn, sumOp<label>())
            << " initial particles in their cells of " << nAll << " drawn; "
            << "please report this" << exit(FatalError);
    }
    if (near)
    {
        // (one outside all cells but near several processors is seen by
        // each of them: counted as the particles no processor owns)
        nOut = nAll - returnReduce(nOwn, sumOp<label>());
    }
    if (nOut)
    {
        // the lowest id seen outside (decomposed: over the processors)
        OStringStream os;
        if (firstOut >= 0)
        {
            os  << "id " << label(a.id[firstOut]) << " at "
                << toVec(a.x, firstOut);
        }
        std::string first(os.str());
        if (near)
        {
            List<string> all(Pstream::nProcs());
            labelList ids(Pstream::nProcs(), labelMax);
            all[me] = first;
            if (firstOut >= 0) ids[me] = label(a.id[firstOut]);
            Pstream::gatherList(all);
            Pstream::scatterList(all);
            Pstream::gatherList(ids);
            Pstream::scatterList(ids);
            const label r = findMin(ids);
            first =
                ids[r] < labelMax ? std::string(all[r])
              : std::string("outside every processor's mesh box");
        }
        chk.fail
        (
            dict_.subDict("initialParticles"), "", "initialParticles",
            "", std::to_string(nOut) + " of " + std::to_string(nAll)
          + " initial particles have their centre outside the mesh (the"
            " first: " + first + "); allowed: every centre inside the mesh"
        );
    }

    if (frozen_ || returnReduce(n, sumOp<label>()) == 0) return;

    // overlaps between particles: cell list with the largest diameter
    const scalar limit = dict_.getOrDefault<scalar>("maxInitialOverlap", 0.05);
    scalar dMax = 0;
    for (label i = 0; i < n; ++i) dMax = max(dMax, 2*a.radius[i]);
    std::unordered_map<int64_t, DynamicList<label>> cells;
    auto key = [&](const label i, const int dx, const int dy, const int dz)
    {
        const int64_t cx = int64_t(std::floor(a.x[3*i]/dMax)) + dx;
        const int64_t cy = int64_t(std::floor(a.x[3*i+1]/dMax)) + dy;
        const int64_t cz = int64_t(std::floor(a.x[3*i+2]/dMax)) + dz;
        return (cx*73856093) ^ (cy*19349663) ^ (cz*83492791);
    };
    for (label i = 0; i < n; ++i) cells[key(i, 0, 0, 0)].append(i);
    scalar worst = 0;
    label wi = -1, wj = -1;
    for (label i = 0; i < n; ++i)
    {
        for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
        {
            const auto it = cells.find(key(i, dx, dy, dz));
            if (it == cells.end()) continue;
            for (const label j : it->second)
            {
                if (j <= i) continue;
                const scalar dist = mag(toVec(a.x, i) - toVec(a.x, j));
                const scalar ov =
                    (a.radius[i] + a.radius[j] - dist)
                   /(2*min(a.radius[i], a.radius[j]));
                if (ov > worst)
                {
                    worst = ov;
                    wi = i;
                    wj = j;
                }
            }
        }
    }
    // (decomposed: the worst over the processors)
    const scalar worstAll = near ? returnReduce(worst, maxOp<scalar>()) : worst;
    if (worstAll > limit)
    {
        OStringStream os;
        if (worst == worstAll)
        {
            os  << "particles " << label(a.id[wi]) << " at " << toVec(a.x, wi)
                << " and " << label(a.id[wj]) << " at " << toVec(a.x, wj)
                << " overlap by " << worst << " of the smaller diameter;"
                << " allowed overlap <= maxInitialOverlap " << limit
                << " (move them apart, or raise maxInitialOverlap)";
        }
        std::string why(os.str());
        if (near)
        {
            List<string> all(Pstream::nProcs());
            all[me] = why;
            Pstream::gatherList(all);
            Pstream::scatterList(all);
            for (const string& w : all)
            {
                if (!w.empty())
                {
                    why = w;
                    break;
                }
            }
        }
        chk.fail(dict_, "", "initialParticles", "", why);
    }

    // the DEM time step against the contact time (decomposed: the
    // smallest over the processors' particles)
    double dtMax = 0;
    world_.check(dem_world_max_dt(world_, &dtMax), "dem_world_max_dt");
    if (near)
    {
        reduce(dtMax, minOp<double>());
    }
    if (demDt_ > dtMax)
    {
        const dictionary& demDict = dict_.subDict("dem");
        OStringStream os;
        os  << "above the safe fraction maxDtFraction of the contact time;"
            << " allowed timeStep <= " << dtMax << " s for these particles"
            << " and materials (lower timeStep, or a softer youngsModulus"
            << " / stiffnessN: the contact time grows as E^(-2/5) for Hertz"
            << " and k^(-1/2) for linear springs)";
        chk.fail(demDict, "dem/", "timeStep", numText(demDt_), os.str());
    }
}


// ************************************************************************* //
