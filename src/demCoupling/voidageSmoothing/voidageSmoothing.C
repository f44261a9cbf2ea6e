/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

\*---------------------------------------------------------------------------*/

#include "voidageSmoothing.H"
#include "fvm.H"
#include "laplacianScheme.H"
#include "surfaceFields.H"
#include "IStringStream.H"

// * * * * * * * * * * * * * * * * Constructor * * * * * * * * * * * * * * //

Foam::voidageSmoothing::voidageSmoothing
(
    const fvMesh& mesh,
    const dictionary& dict
)
:
    mesh_(mesh),
    length_(dict.getOrDefault<scalar>("voidageSmoothingLength", 0)),
    field_(),
    solverControls_(IStringStream
    (
        "solver PCG; preconditioner DIC; tolerance 1e-13; relTol 0; "
        "maxIter 10000;"
    )())
{
    if (!active()) return;

    field_.reset
    (
        new volScalarField
        (
            IOobject
            (
                "solidFractionSmoothed",
                mesh.time().timeName(),
                mesh,
                IOobject::NO_READ,
                IOobject::NO_WRITE,
                false
            ),
            mesh,
            dimensionedScalar("zero", dimless, Zero),
            "zeroGradient"
        )
    );
    Info<< "demCoupling: voidage smoothed over " << length_ << " m"
        << " (voidageSmoothingLength)" << endl;
}


// * * * * * * * * * * * * * * * Member functions  * * * * * * * * * * * * //

void Foam::voidageSmoothing::smooth(scalarField& s)
{
    if (!active()) return;

    const scalarField& V = mesh_.V();
    const scalar total = gSum(s*V);

    volScalarField& f = field_();
    f.primitiveFieldRef() = s;
    f.correctBoundaryConditions();

    // the scheme is fixed here, not read from fvSchemes: uncorrected keeps
    // the matrix an M-matrix (bounded, positive) on non-orthogonal meshes
    tmp<fv::laplacianScheme<scalar, scalar>> lap
    (
        fv::laplacianScheme<scalar, scalar>::New
        (
            mesh_, IStringStream("Gauss linear uncorrected")()
        )
    );
    const surfaceScalarField L2
    (
        IOobject
        (
            "voidageSmoothingL2", mesh_.time().timeName(), mesh_,
            IOobject::NO_READ, IOobject::NO_WRITE, false
        ),
        mesh_,
        dimensionedScalar("L2", dimArea, sqr(length_))
    );

    fvScalarMatrix eqn(fvm::Sp(dimensionedScalar("one", dimless, 1), f));
    eqn -= lap.ref().fvmLaplacian(L2, f);
    eqn.source() += s*V;
    eqn.solve(solverControls_);

    // the exact solution keeps the total; the iterative one to its
    // tolerance, so scale it back to the total
    const scalar totalSmoothed = gSum(f.primitiveField()*V);
    s = f.primitiveField();
    if (totalSmoothed > 0)
    {
        s *= total/totalSmoothed;
    }
}


// ************************************************************************* //
