#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Write particle centres as an OpenFOAM list of points.

  positions.py lattice X0 Y0 Z0 NX NY NZ SPACING   simple cubic lattice, first centre at (X0,Y0,Z0)
  positions.py random  X0 Y0 Z0 X1 Y1 Z1 N SEED    N uniform random points in the box (may overlap)
"""
import random, sys
kind = sys.argv[1]
pts = []
if kind == "lattice":
    x0, y0, z0 = map(float, sys.argv[2:5]); nx, ny, nz = map(int, sys.argv[5:8]); h = float(sys.argv[8])
    pts = [(x0 + i*h, y0 + j*h, z0 + k*h) for k in range(nz) for j in range(ny) for i in range(nx)]
elif kind == "random":
    lo = list(map(float, sys.argv[2:5])); hi = list(map(float, sys.argv[5:8]))
    n, seed = int(sys.argv[8]), int(sys.argv[9])
    rng = random.Random(seed)
    pts = [tuple(lo[k] + (hi[k] - lo[k])*rng.random() for k in range(3)) for _ in range(n)]
else:
    sys.exit("positions.py: kind must be lattice or random")
print("(")
for p in pts:
    print("    (%.12g %.12g %.12g)" % p)
print(")")
