/*---------------------------------------------------------------------------*\
  demFoam
  Copyright (C) 2026 the demFoam authors
  License: GPL-3.0-or-later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "patchWalls.H"
#include "demCouplingTools.H"
#include "emptyPolyPatch.H"
#include "wallPolyPatch.H"
#include "processorPolyPatch.H"
#include "globalMeshData.H"
#include "globalIndex.H"

using Foam::demTools::joinAll;

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

void Foam::patchWalls::mergeAcrossProcessors
(
    const fvMesh& mesh,
    const polyPatch& pp,
    DynamicList<double>& verts,
    DynamicList<int>& tris
)
{
    // this processor's vertices: the patch's local points, then the face
    // centres added for degenerate faces
    const label nLocal = pp.nPoints();
    const label nCentre = label(verts.size()/3) - nLocal;

    // a point on several processors' patches gets one global number
    // (OpenFOAM's point coupling, no tolerance): the merged points of all
    // processors in processor order, then all face centres
    labelList pointToGlobal, uniqueMeshPoints;
    const autoPtr<globalIndex> merged
    (
        mesh.globalData().mergePoints
        (
            pp.meshPoints(), pp.meshPointMap(), pointToGlobal,
            uniqueMeshPoints
        )
    );
    const globalIndex centres(nCentre);
    const label centreStart = merged().size() + centres.offset(Pstream::myProcNo());
    for (int& t : tris)
    {
        t = int(t < nLocal ? pointToGlobal[t] : centreStart + t - nLocal);
    }

    DynamicList<double> mine(3*uniqueMeshPoints.size());
    for (const label pointi : uniqueMeshPoints)
    {
        const point& x = mesh.points()[pointi];
        mine.append(x.x()); mine.append(x.y()); mine.append(x.z());
    }
    DynamicList<double> myCentres(3*nCentre);
    for (label k = 3*nLocal; k < verts.size(); ++k) myCentres.append(verts[k]);

    verts = demTools::joinAll(mine);
    verts.append(demTools::joinAll(myCentres));
    tris = demTools::joinAll(tris);
}


void Foam::patchWalls::add
(
    demWorld& world,
    const fvMesh& mesh,
    const wordList& extraWalls,
    const int mat
)
{
    const double zeroVel[3] = {0, 0, 0};

    // decomposed: every processor gets the walls of all (a particle near a
    // processor boundary may touch a wall face of the neighbour)
    for (const polyPatch& pp : mesh.boundaryMesh())
    {
        if (isA<processorPolyPatch>(pp)) continue;
        if (!returnReduce(pp.size(), sumOp<label>())) continue;

        if (isA<emptyPolyPatch>(pp))
        {
            // one plane per distinct face plane (front and back of 2-D meshes)
            const List<vector> nAll
            (
                joinAll(vectorField(pp.faceAreas()/mag(pp.faceAreas())))
            );
            const List<point> cAll(joinAll(pp.faceCentres()));
            List<vector> ns;
            List<point> ps;
            forAll(nAll, i)
            {
                const vector& n = nAll[i];
                const point& c = cAll[i];
                bool known = false;
                forAll(ns, k)
                {
                    if ((ns[k] & n) > 1 - 1e-6 && mag((c - ps[k]) & n) < 1e-9)
                    {
                        known = true;
                        break;
                    }
                }
                if (!known)
                {
                    ns.append(n);
                    ps.append(c);
                }
            }
            forAll(ns, k)
            {
                // DEM plane normal points into the domain
                const vector nIn = -ns[k];
                int id;
                world.check
                (
                    dem_world_add_plane
                    (
                        world, ps[k].cdata(), nIn.cdata(), mat, zeroVel, &id
                    ),
                    "dem_world_add_plane"
                );
                Info<< "demCoupling: empty patch " << pp.name()
                    << " -> DEM plane at " << ps[k] << " normal " << nIn << endl;
            }
        }
        else if (isA<wallPolyPatch>(pp) || extraWalls.found(pp.name()))
        {
            // fan triangulation from the first vertex; faces where that
            // gives a degenerate triangle (collinear points, as on the
            // boundary of polyDualMesh meshes) are fanned about their centre
            // instead, skipping degenerate triangles
            const pointField& lp = pp.localPoints();
            const faceList& lf = pp.localFaces();
            DynamicList<double> verts(3*lp.size());
            for (const point& x : lp)
            {
                verts.append(x.x()); verts.append(x.y()); verts.append(x.z());
            }
            DynamicList<int> tris;
            auto triArea = [&](const point& a, const point& b, const point& c)
            {
                return 0.5*mag((b - a) ^ (c - a));
            };
            forAll(lf, facei)
            {
                const face& f = lf[facei];
                const scalar fArea = f.mag(lp);
                bool degenerate = false;
                for (label k = 1; k + 1 < f.size(); ++k)
                {
                    if (triArea(lp[f[0]], lp[f[k]], lp[f[k+1]]) <= 1e-10*fArea)
                    {
                        degenerate = true;
                    }
                }
                if (!degenerate)
                {
                    for (label k = 1; k + 1 < f.size(); ++k)
                    {
                        tris.append(f[0]); tris.append(f[k]); tris.append(f[k+1]);
                    }
                    continue;
                }
                const point c = f.centre(lp);
                const int ci = int(verts.size()/3);
                verts.append(c.x()); verts.append(c.y()); verts.append(c.z());
                forAll(f, k)
                {
                    const label a = f[k], b = f.nextLabel(k);
                    if (triArea(c, lp[a], lp[b]) > 1e-10*fArea)
                    {
                        tris.append(ci); tris.append(int(a)); tris.append(int(b));
                    }
                }
            }
            if (Pstream::parRun())
            {
                mergeAcrossProcessors(mesh, pp, verts, tris);
            }
            int id;
            world.check
            (
                dem_world_add_trimesh
                (
                    world, verts.size()/3, verts.cdata(), tris.size()/3,
                    tris.cdata(), mat, zeroVel, &id
                ),
                "dem_world_add_trimesh"
            );
            Info<< "demCoupling: wall patch " << pp.name() << " -> DEM wall of "
                << tris.size()/3 << " triangles" << endl;
        }
    }
}
