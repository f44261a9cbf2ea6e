#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Initial and settled states for the demFoam DEM benchmark (bench/dem/run).

  bed.py lattice N DATAFILE          loose jittered lattice -> LIGGGHTS data file
                                     (input of the one-time settling run)
  bed.py convert N DUMP DATA BIN     settled LIGGGHTS dump -> LIGGGHTS data file
                                     (read_data) and the binary input of our
                                     driver, with identical numbers in both
  bed.py geometry N                  print "L H" (box side and height, m)

Geometry: square box of side L = d * round((N (pi/6) / 0.6)^(1/3)) so that the
settled bed (packing fraction about 0.6) is roughly a cube; the top wall sits
above the loose lattice, so the settled bed does not touch it.
"""
import math, random, struct, sys

D = 2.0e-3          # diameter [m] (docs/performance.md, bench/dem)
RHO = 2500.0        # density [kg/m3] (docs/performance.md)
S = 1.05 * D        # lattice spacing of the loose start (packing fraction 0.45)
MAGIC = b"DEMBED01"

def geometry(n):
    side = D * round((n * math.pi / 6.0 / 0.6) ** (1.0 / 3.0))
    per_side = int(side // S)
    layers = -(-n // (per_side * per_side))
    height = layers * S + 2.0 * D
    return side, height, per_side, layers

def lattice(n, path):
    side, height, m, layers = geometry(n)
    rng = random.Random(12345 + n)
    pitch = side / m                       # >= S
    jit = 0.45 * (pitch - D)               # keeps the start free of overlaps
    jz = 0.45 * (S - D)
    pos = []
    for k in range(layers):
        cells = [(i, j) for i in range(m) for j in range(m)]
        if len(pos) + len(cells) > n:      # last layer: random subset
            rng.shuffle(cells)
            cells = cells[: n - len(pos)]
        for (i, j) in cells:
            pos.append(((i + 0.5) * pitch + rng.uniform(-jit, jit),
                        (j + 0.5) * pitch + rng.uniform(-jit, jit),
                        D + k * S + rng.uniform(-jz, jz)))
    with open(path, "w") as f:
        f.write("demFoam benchmark: loose lattice of %d spheres\n\n" % n)
        f.write("%d atoms\n1 atom types\n\n" % n)
        f.write("%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n%.17g %.17g zlo zhi\n\n"
                % (0.0, side, 0.0, side, 0.0, height))
        f.write("Atoms\n\n")
        for i, (x, y, z) in enumerate(pos):
            f.write("%d 1 %.17g %.17g %.17g %.17g %.17g\n" % (i + 1, D, RHO, x, y, z))
        f.write("\nVelocities\n\n")
        for i in range(n):
            v = [rng.uniform(-0.05, 0.05) for _ in range(3)]
            f.write("%d %.17g %.17g %.17g 0 0 0\n" % (i + 1, v[0], v[1], v[2]))

def read_dump(path):
    """Last snapshot of a LIGGGHTS 'dump custom' with columns
    id x y z vx vy vz omegax omegay omegaz radius."""
    with open(path) as f:
        lines = f.read().split("\n")
    start = max(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[start].split()[2:]
    rows = []
    for l in lines[start + 1:]:
        if l.strip():
            rows.append(dict(zip(cols, l.split())))
    rows.sort(key=lambda r: int(r["id"]))
    return rows

def convert(n, dump, data, binary):
    side, height, _, _ = geometry(n)
    rows = read_dump(dump)
    if len(rows) != n:
        sys.exit("bed.py: %s holds %d particles, expected N = %d" % (dump, len(rows), n))
    # Round once through float() so both files carry the same doubles.
    p = [[float(r[k]) for k in ("x", "y", "z", "vx", "vy", "vz",
                                "omegax", "omegay", "omegaz", "radius")] for r in rows]
    with open(data, "w") as f:
        f.write("demFoam benchmark: settled bed of %d spheres\n\n" % n)
        f.write("%d atoms\n1 atom types\n\n" % n)
        f.write("%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n%.17g %.17g zlo zhi\n\n"
                % (0.0, side, 0.0, side, 0.0, height))
        f.write("Atoms\n\n")
        for i, q in enumerate(p):
            f.write("%d 1 %.17g %.17g %.17g %.17g %.17g\n" % (i + 1, 2.0 * q[9], RHO, q[0], q[1], q[2]))
        f.write("\nVelocities\n\n")
        for i, q in enumerate(p):
            f.write("%d %.17g %.17g %.17g %.17g %.17g %.17g\n" % ((i + 1,) + tuple(q[3:9])))
    with open(binary, "wb") as f:
        # header: magic, N, box lo[3], box hi[3]; then per particle
        # id (int64), x[3] v[3] omega[3] radius density (11 doubles)
        f.write(MAGIC + struct.pack("<q6d", n, 0.0, 0.0, 0.0, side, side, height))
        for i, q in enumerate(p):
            f.write(struct.pack("<q11d", i + 1, *q, RHO))
    zs = [q[2] for q in p]
    vol = n * math.pi / 6.0 * D ** 3
    top = sorted(zs)[int(0.99 * n)]        # robust bed height: 99th percentile
    print("bed: N=%d side=%.4g m height(99%%)=%.4g m packing~%.3f"
          % (n, side, top, vol / (side * side * top)))

if __name__ == "__main__":
    cmd = sys.argv[1]
    n = int(sys.argv[2])
    if cmd == "lattice":
        lattice(n, sys.argv[3])
    elif cmd == "convert":
        convert(n, sys.argv[3], sys.argv[4], sys.argv[5])
    elif cmd == "geometry":
        side, height, _, _ = geometry(n)
        print("%.17g %.17g" % (side, height))
    else:
        sys.exit("bed.py: unknown command %s (lattice, convert, geometry)" % cmd)
