/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)

\*---------------------------------------------------------------------------*/

#include "voidageSmoothing.H"
#include "fvm.H"
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
    L2_(),
    laplacian_(),
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
    L2_.reset
    (
        new surfaceScalarField
        (
            IOobject
            (
                "voidageSmoothingL2", mesh.time().timeName(), mesh,
                IOobject::NO_READ, IOobject::NO_WRITE, false
            ),
            mesh,
            dimensionedScalar("L2", dimArea, sqr(length_))
        )
    );
    // uncorrected keeps the matrix an M-matrix (bounded, positive) on
    // non-orthogonal meshes
    laplacian_ = fv::laplacianScheme<scalar, scalar>::New
    (
        mesh, IStringStream("Gauss linear uncorrected")()
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

    fvScalarMatrix eqn(fvm::Sp(dimensionedScalar("one", dimless, 1), f));
    eqn -= laplacian_.ref().fvmLaplacian(L2_(), f);
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
