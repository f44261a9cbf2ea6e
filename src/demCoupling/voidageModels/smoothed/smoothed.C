/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "smoothed.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace voidageModels
{
    defineTypeNameAndDebug(smoothed, 0);
    addToRunTimeSelectionTable(voidageModel, smoothed, dictionary);
    addCoeffKeys(smoothed);
}
}

Foam::List<Foam::keySpec> Foam::voidageModels::smoothed::coeffKeys()
{
    using kind = keySpec::kind;
    const double inf = HUGE_VAL;
    return List<keySpec>
    ({
        keySpec::num("nLayers", kind::Label, 0, 10, false, false),
        keySpec::num("bandwidthFactor", kind::Scalar, 0, inf, true, false)
    });
}


Foam::voidageModels::smoothed::smoothed
(
    const dictionary& dict, const fvMesh& mesh, const particleLocator& l
)
:
    voidageModel(typeName, dict, mesh, l),
    nLayers_(coeffs_.getOrDefault<label>("nLayers", 1)),
    bandwidthFactor_(coeffs_.getOrDefault<scalar>("bandwidthFactor", 1.0))
{
    if (nLayers_ < 0 || nLayers_ > 3 || bandwidthFactor_ <= 0)
    {
        FatalIOErrorInFunction(coeffs_)
            << "smoothedCoeffs in " << coeffs_.name() << ": nLayers "
            << nLayers_ << " (allowed 0..3), bandwidthFactor "
            << bandwidthFactor_ << " (allowed > 0)" << exit(FatalIOError);
    }
    if (Pstream::parRun())
    {
        WarningInFunction
            << "voidageModel smoothed in a decomposed run: its kernel layers"
            << " stop at processor boundaries, so eps and the forces next to"
            << " them depend on the decomposition (docs/parallel.md, Known"
            << " limitations); divided and centre do not" << endl;
    }
}


void Foam::voidageModels::smoothed::addWeights
(
    const point& x, const scalar r, const label hostCell,
    DynamicList<label>& cells, DynamicList<scalar>& weights,
    DynamicList<remoteSample>&
) const
{
    const label start = cells.size();
    const labelListList& cc = mesh_.cellCells();
    const scalarField& V = mesh_.V();
    const vectorField& C = mesh_.C().primitiveField();

    const scalar b =
        bandwidthFactor_*max(2*r, Foam::cbrt(V[hostCell]));

    cells.append(hostCell);
    label layerStart = start;
    for (label layer = 0; layer < nLayers_; ++layer)
    {
        const label layerEnd = cells.size();
        for (label k = layerStart; k < layerEnd; ++k)
        {
            for (const label nb : cc[cells[k]])
            {
                bool seen = false;
                for (label m = start; m < cells.size(); ++m)
                {
                    if (cells[m] == nb) { seen = true; break; }
                }
                if (!seen)
                {
                    cells.append(nb);
                }
            }
        }
        layerStart = layerEnd;
    }

    scalar sum = 0;
    for (label k = start; k < cells.size(); ++k)
    {
        const label c = cells[k];
        const scalar w = V[c]*exp(-magSqr(C[c] - x)/(2*sqr(b)));
        weights.append(w);
        sum += w;
    }
    for (label k = start; k < cells.size(); ++k)
    {
        weights[k] /= sum;
    }
}
