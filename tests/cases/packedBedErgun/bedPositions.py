#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Frozen random bed for the centre voidage model: N spheres spread over the
cells below height H with counts proportional to the cell volumes (the
rounding carried from cell to cell, so the bed's solid fraction is exact),
each centre a random point near its cell centre.  The centre model sees only
the counts, so every bed cell gets the bed's voidage up to one particle.

usage: bedPositions.py TIME_DIR H SOLID_FRACTION D SEED > positions
(TIME_DIR holds C and V of postProcess -func 'writeCellCentres' and
-func 'writeCellVolumes')."""
import math, random, sys
from foamField import internal_field

tdir, H, phi, d, seed = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), \
    float(sys.argv[4]), int(sys.argv[5])
C, V = internal_field(tdir + "/C"), internal_field(tdir + "/V")
rng = random.Random(seed)
Vp = math.pi * d**3 / 6
carry, pts = 0.0, []
for c, v in zip(C, V):
    if c[2] >= H:
        continue
    want = phi * v / Vp + carry
    n = int(round(want))
    carry = want - n
    r = 0.15 * v ** (1 / 3)        # stays inside hexahedra of aspect < 3
    for _ in range(n):
        pts.append([x + rng.uniform(-r, r) for x in c])
print("(")
for p in pts:
    print("    (%.9g %.9g %.9g)" % tuple(p))
print(")")
