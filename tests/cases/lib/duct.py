# SPDX-License-Identifier: GPL-3.0-or-later
"""Readers for the duct case of tests/cases/insertionRamp (water through a
40 x 10 x 10 mm duct of 16 x 4 x 4 cells, spheres fed at the inlet), shared
by its checks and by tests/cases/voidageRelaxation.

  inlet_pressure(case)       {t: inlet pressure} per step (pInlet function object)
  particles_per_step(case)   {t: particles} from the log's demCoupling lines
  first_layer_decomposition  print a cellDecomposition: processor 0 the first
                             layer of cells at the inlet, processor 1 the rest
"""
import glob, re


def inlet_pressure(case):
    p = {}
    for f in sorted(glob.glob(case + "/postProcessing/pInlet/*/surfaceFieldValue.dat")):
        for line in open(f):
            if line.startswith("#") or not line.strip():
                continue
            w = line.split()
            p[round(float(w[0]), 9)] = float(w[1])
    return p


def particles_per_step(case):
    n, t = {}, None
    for line in open(case + "/log.demFoam"):
        if line.startswith("Time = "):
            t = round(float(line.split()[2]), 9)
        m = re.match(r"demCoupling: particles (\d+),", line)
        if m and t is not None:
            n[t] = int(m.group(1))
    return n


def first_layer_decomposition(nx=16, ny=4, nz=4):
    n = nx*ny*nz
    print("FoamFile { version 2.0; format ascii; class labelList; object cellDecomposition; }")
    print(n)
    print("(")
    for c in range(n):
        print(0 if c % nx == 0 else 1)
    print(")")


if __name__ == "__main__":
    first_layer_decomposition()
