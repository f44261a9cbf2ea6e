/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Application
    demFoam

Description
    Transient incompressible CFD-DEM solver: PIMPLE for the fluid with the
    fluid volume fraction eps (continuity d(eps)/dt + div(eps u) = 0), the
    particles in the C DEM core (src/dem) coupled by the momentum
    formulation set I, II or III of Zhou et al. (2010), docs/theory.md
    section 3 (constant/demProperties, keyword formulation).

    Fluid momentum equation (kinematic, p = p/rho_f):
        ddt(eps, U) + div(eps phi, U) + c_tau divDevReff(U)
          = -c_p grad p + eps g + S/rho_f,
    c_p = eps (sets I, II) or 1 (set III), c_tau = eps (set II) or 1; S, the
    particles' momentum source, holds -F of the set with the drag
    semi-implicit (see couplingFormulation.H for set I's pressure part).
    Turbulence models (laminar, RAS, LES), fvOptions and function objects
    are selected as usual.

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "singlePhaseTransportModel.H"
#include "turbulentTransportModel.H"
#include "pimpleControl.H"
#include "fvOptions.H"
#include "demCoupling.H"
#include "interpolateInner.H"
#include "fluxReconstruction.H"
#include "timeCompletion.H"
#include "processorDirs.H"
#include "signalRequests.H"
#include <chrono>
#include <csetjmp>
#include <csignal>

// A floating-point exception in the fluid solution (OpenFOAM's trapFpe)
// jumps back to the time loop, which writes the last good state
static sigjmp_buf fpeJump;
static void fpeHandler(int)
{
    siglongjmp(fpeJump, 1);
}

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Transient incompressible CFD-DEM solver with the momentum"
        " formulations set I/II/III of Zhou et al. (2010)"
    );

    argList::addBoolOption
    (
        "checkInput",
        "check constant/demProperties against the mesh and the initial"
        " particles (keywords, types, ranges, names, overlaps, time step),"
        " report and stop without writing anything"
    );

    #include "postProcess.H"

    #include "addCheckCaseOptions.H"
    #include "setRootCaseLists.H"
    #include "createTime.H"
    // a decomposition that does not fit, or a start from a half-written
    // time, stops here, before the mesh or any field is read
    checkProcessorDirs(runTime);
    timeCompletion::checkStart(runTime);
    #include "restoreTimeValue.H"
    demFoamSignals::watch();
    #include "createMesh.H"
    #include "createControl.H"
    #include "createTimeControls.H"
    #include "createFields.H"
    #include "initContinuityErrs.H"

    if (args.found("checkInput"))
    {
        Info<< "\ndemFoam -checkInput: constant/demProperties, the mesh and "
            << "the initial particles are valid; nothing written\nEnd\n"
            << endl;
        return 0;
    }

    // keep the previous time of every field, for the last good state
    #include "storeOldTimes.H"
    const label iStart = runTime.timeIndex();
    const label injectFluidNaN = demCoupling::injectedStep("fluidNaN");
    const label injectFpe = demCoupling::injectedStep("fpe");
    // processor p raises the stop signal on itself in step N + p, after the
    // step's requests were taken: a signal that reaches the processors in
    // different steps
    const label injectLateSignal = demCoupling::injectedStep("lateSignal");
    if (injectLateSignal >= 0 && !sigStopAtWriteNow::active())
    {
        FatalErrorInFunction
            << "DEMFOAM_DEBUG_INJECT=lateSignal@" << injectLateSignal
            << " needs OptimisationSwitches { stopAtWriteNowSignal N; } in "
            << runTime.controlDict().name() << exit(FatalError);
    }
    volatile scalar tGood = runTime.value();
    volatile label iGood = runTime.timeIndex();
    #include "writeLastGood.H"

    Info<< "\nStarting time loop\n" << endl;

    if (sigsetjmp(fpeJump, 1))
    {
        writeLastGood("floating-point exception (SIGFPE) in the fluid solution");
    }
    // serial only: in a decomposed run the other processors would wait in
    // the fluid solution's communication; there OpenFOAM's own SIGFPE
    // handler stops the run (the last written time is the restart point)
    struct sigaction fpeAction, fpeDefault;
    fpeAction.sa_handler = fpeHandler;
    sigemptyset(&fpeAction.sa_mask);
    fpeAction.sa_flags = 0;
    if (!Pstream::parRun())
    {
        sigaction(SIGFPE, &fpeAction, &fpeDefault);
    }

    while (runTime.run())
    {
        #include "readTimeControls.H"
        #include "CourantNo.H"
        #include "setDeltaT.H"

        tGood = runTime.value();
        iGood = runTime.timeIndex();
        dem.checkpoint();
        ++runTime;

        Info<< "Time = " << runTime.timeName() << nl << endl;

        // requests by signal, taken here on every processor
        demFoamSignals::watch();
        const label requests = demFoamSignals::take();
        if (requests & demFoamSignals::requestStop)
        {
            Info<< "demFoam: stop signal (" << demFoamSignals::stopSignal().c_str()
                << "): writing t = "
                << runTime.timeName() << " and stopping" << nl << endl;
            runTime.setEndTime(runTime.value());
        }
        if (requests & demFoamSignals::requestWrite)
        {
            Info<< "demFoam: write signal (writeNowSignal "
                << sigWriteNow::signalNumber() << "): writing t = "
                << runTime.timeName() << nl << endl;
            dem.writeThisStep();
        }
        if
        (
            injectLateSignal >= 0
         && runTime.timeIndex() - iStart
         == injectLateSignal + Pstream::myProcNo()
        )
        {
            std::raise(sigStopAtWriteNow::signalNumber());
        }

        // The DEM part of the step, with the fluid fields of the last step
        {
            const volVectorField divTau
            (
                "divTau",
                fvc::div(turbulence->nuEff()*dev2(T(fvc::grad(U))))
              + fvc::laplacian(turbulence->nuEff(), U)
            );
            dem.evolve(U, p, divTau, laminarTransport.nu()());
        }
        if (!dem.failure().empty())
        {
            writeLastGood(dem.failure());
        }

        const auto tFluid0 = std::chrono::steady_clock::now();

        epsf = fvc::interpolate(eps);
        epsPhi = epsf*phi;

        // --- Pressure-velocity PIMPLE corrector loop
        while (pimple.loop())
        {
            #include "UEqn.H"

            // --- Pressure corrector loop
            while (pimple.correct())
            {
                #include "pEqn.H"
            }

            if (pimple.turbCorr())
            {
                laminarTransport.correct();
                turbulence->correct();
            }
        }

        if (runTime.timeIndex() - iStart == injectFluidNaN)
        {
            U[0].x() = std::numeric_limits<scalar>::quiet_NaN();
        }
        if (runTime.timeIndex() - iStart == injectFpe)
        {
            volatile scalar zero = 0;
            U[0].x() = 1/zero;
        }
        const std::string fluidFailure(demCoupling::nonFinite(U, p));
        if (!fluidFailure.empty())
        {
            writeLastGood(fluidFailure);
        }

        dem.updateDriving(U);
        dem.addFluidTime
        (
            std::chrono::duration<scalar>
            (
                std::chrono::steady_clock::now() - tFluid0
            ).count()
        );

        const bool writeStep = dem.writeStep();
        if (writeStep)
        {
            dem.write();
        }
        if (writeStep && !runTime.writeTime())
        {
            // the last step with endTime off the write grid, or a request
            if (!requests)
            {
                Info<< "demFoam: endTime " << runTime.endTime().value()
                    << " is off the write grid; writing the final state"
                    << endl;
            }
            runTime.writeNow();
        }
        else
        {
            runTime.write();
        }
        if (runTime.writeTime())
        {
            // last: the time is complete (a restart may start from it)
            timeCompletion::mark(runTime);
        }

        runTime.printExecutionTime(Info);
        dem.progress(!runTime.run());
    }
    if (!Pstream::parRun())
    {
        sigaction(SIGFPE, &fpeDefault, nullptr);
    }

    Info<< "End\n" << endl;

    return 0;
}
