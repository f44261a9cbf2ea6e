/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

Application
    demInterFoam

Description
    Transient CFD-DEM solver for two incompressible, immiscible fluids
    (e.g. water and air) with the interface captured by a volume fraction
    (VOF, explicit MULES with interface compression), in the volume the
    particles leave free, coupled to the particles of the C DEM core through
    the same library and run-time selections as demFoam (constant/
    demProperties: set I, II or III, drag law, voidage model, extra forces,
    outlets, walls, restart, parallel, the safety net).

    Phase 1 (alpha1 = alpha.<phase 1>) and continuity:
        d(eps alpha1)/dt + div(eps phi alpha1) = 0,
        d(eps)/dt + div(eps phi) = 0,
    momentum of the mixture (rho = alpha1 rho1 + (1 - alpha1) rho2,
    mu likewise from the phases' transport models):
        ddt(eps rho, U) + div(eps rho phi, U) + c_tau div(tau)
          = -c_p grad p + eps rho g + c_p sigma kappa grad(alpha1)
            - Kc U + Sc,
    solved for p_rgh = p - rho g.h; docs/theory.md section 10.  The laws
    that need the fluid's density and viscosity get the mixture's values
    interpolated to the particle.

    Input as for interFoam (0/alpha.water, 0/p_rgh, 0/U, constant/
    transportProperties with phases and sigma, constant/g, optional
    constant/hRef, system/fvSolution solvers "alpha.water.*") plus
    constant/demProperties as for demFoam; docs/demInterFoam.md.

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "wallFvPatch.H"
#include "immiscibleIncompressibleTwoPhaseMixture.H"
#include "turbulentTransportModel.H"
#include "pimpleControl.H"
#include "fvOptions.H"
#include "profiling.H"
#include "MULES.H"
#include "demCoupling.H"
#include "interpolateInner.H"
#include "fluxReconstruction.H"
#include "constrainFixedVelocityFlux.H"
#include "runControl.H"

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Transient CFD-DEM solver for two incompressible, immiscible fluids"
        " (VOF) with the momentum formulations set I/II/III of Zhou et al."
        " (2010)"
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
        Info<< "\ndemInterFoam -checkInput: constant/demProperties, the mesh,"
            << " the phases and the initial particles are valid; nothing"
            << " written\nEnd\n" << endl;
        return 0;
    }

    // the pressure the fluid check looks at (runControlFluidCheck.H)
    const volScalarField& runControlPressure = p_rgh;
    #include "runControlInit.H"

    while (runTime.run())
    {
        #include "readTimeControls.H"
        #include "CourantNo.H"
        #include "phaseCourantNo.H"     // maxCoPhase: CoNum over one phase
        #include "interfaceCourantNo.H"
        #include "demDeltaT.H"      // setDeltaT.H in whole DEM steps

        #include "runControlStep.H"

        // The DEM part of the step, with the fluid fields of the last step:
        // p, div tau [N/m3], the mixture's mu and rho
        {
            // div tau: the fluid equation's own stress operator applied to
            // U, Reynolds stresses included (docs/theory.md section 10)
            const volVectorField divTau
            (
                "divTau",
                -(turbulence->divDevRhoReff(rho, U) & U)
            );
            // timed sections of a step for OpenFOAM's profiling (controlDict
            // profiling { active true; }: docs/performance.md, "Where a step's time goes")
            addProfiling(demEvolve, "dem.evolve");
            dem.evolve(U, p, divTau, mixture.mu()(), rho);
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
                addProfiling(alphaEqn, "alphaEqn");
                #include "alphaEqn.H"
                endProfiling(alphaEqn);

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


// ************************************************************************* //
