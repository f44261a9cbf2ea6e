/*---------------------------------------------------------------------------*\
  demFoam: CFD-DEM for OpenFOAM
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "insertionRegion.H"
#include "OStringStream.H"

Foam::insertionRegion::insertionRegion
(
    const dictionary& d,
    const particleLocator& locator,
    const scalar rMax
)
:
    type_(d.get<word>("type")),
    bounds_(),
    base_(Zero),
    axis_(0, 0, 1),
    radius_(0),
    length_(0),
    mesh_(d.getOrDefault<bool>("insideMesh", false) ? &locator : nullptr),
    rMax_(rMax)
{
    if (type_ == "cylinder")
    {
        base_ = d.get<point>("base");
        axis_ = d.get<vector>("axis");
        axis_ /= mag(axis_);
        radius_ = d.get<scalar>("radius");
        length_ = d.get<scalar>("length");
        // bounding box of the two end discs
        const point top(base_ + length_*axis_);
        vector ext;
        for (direction k = 0; k < 3; ++k)
        {
            ext[k] = radius_*std::sqrt(max(1 - sqr(axis_[k]), scalar(0)));
        }
        bounds_ = boundBox(min(base_, top) - ext, max(base_, top) + ext);
    }
    else
    {
        bounds_ = boundBox(d.get<point>("min"), d.get<point>("max"));
    }
}


bool Foam::insertionRegion::contains(const point& x) const
{
    if (type_ == "cylinder")
    {
        const scalar s = (x - base_) & axis_;
        if (s < rMax_ || s > length_ - rMax_) return false;
        if (mag((x - base_) - s*axis_) > radius_ - rMax_) return false;
    }
    if (!mesh_) return true;
    if (!mesh_->inside(x)) return false;
    for (direction k = 0; k < 3; ++k)
    {
        vector e(Zero);
        e[k] = rMax_;
        if (!mesh_->inside(x + e) || !mesh_->inside(x - e)) return false;
    }
    return true;
}


int Foam::insertionRegion::inside(const double x[3], void* user)
{
    return static_cast<const insertionRegion*>(user)->contains
    (
        point(x[0], x[1], x[2])
    );
}


std::string Foam::insertionRegion::describe() const
{
    OStringStream os;
    if (type_ == "cylinder")
    {
        os  << "cylinder base " << base_ << " axis " << axis_ << " radius "
            << radius_ << " length " << length_;
    }
    else
    {
        os  << "box " << bounds_.min() << " " << bounds_.max();
    }
    if (mesh_) os << ", inside the mesh";
    return os.str();
}


// ************************************************************************* //
