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
#include "wallFvPatch.H"
#include "singlePhaseTransportModel.H"
#include "turbulentTransportModel.H"
#include "pimpleControl.H"
#include "fvOptions.H"
#include "profiling.H"
#include "demCoupling.H"
#include "interpolateInner.H"
#include "fluxReconstruction.H"
#include "constrainFixedVelocityFlux.H"
#include "runControl.H"

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
    #include "runControlStart.H"
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

    // the pressure the fluid check looks at (runControlFluidCheck.H)
    const volScalarField& runControlPressure = p;
    #include "runControlInit.H"

    while (runTime.run())
    {
        #include "readTimeControls.H"
        #include "CourantNo.H"
        #include "demDeltaT.H"      // setDeltaT.H in whole DEM steps

        #include "runControlStep.H"

        // The DEM part of the step, with the fluid fields of the last step
        {
            // div tau: the fluid equation's own stress operator applied to
            // U, Reynolds stresses included (docs/theory.md section 2)
            const volVectorField divTau
            (
                "divTau",
                -(turbulence->divDevReff(U) & U)
            );
            // timed sections of a step for OpenFOAM's profiling (controlDict
            // profiling { active true; }: docs/performance.md, "Where a step's time goes")
            addProfiling(demEvolve, "dem.evolve");
            dem.evolve(U, p, divTau, laminarTransport.nu()());
        }
        if (!dem.failure().empty())
        {
            writeLastGood(dem.failure());
        }

        #include "runControlSolveStart.H"

        // --- Pressure-velocity PIMPLE corrector loop (runControl.H,
        // nonFiniteSolution: a NaN that stops OpenFOAM's record of the
        // solvers' residuals ends the step as a failure)
        try
        {
            while (pimple.loop())
            {
                addProfiling(UEqn, "UEqn");
                #include "UEqn.H"
                endProfiling(UEqn);

                // --- Pressure corrector loop
                while (pimple.correct())
                {
                    addProfiling(pEqn, "pEqn");
                    #include "pEqn.H"
                }

                if (pimple.turbCorr())
                {
                    addProfiling(turbulence, "turbulence");
                    laminarTransport.correct();
                    turbulence->correct();
                }
            }
        }
        catch (const IOerror& e)
        {
            solveFailure = nonFiniteSolution(e, solveThrowing);
        }
        #include "runControlSolveEnd.H"
    }
    #include "runControlEnd.H"

    Info<< "End\n" << endl;

    return 0;
}
