#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Pressure drop of a frozen bed against Ergun's equation.

usage: ergunCheck.py TIME U HBED LZ [T0]
Prints: dp ergun uFirst uTop
  dp     rho (p_inlet - p_outlet) - rho g LZ  (area averages of the patches,
         averaged over t >= T0 if given, else the last step) [Pa]
  ergun  Ergun's equation with the bed height HBED and the bed's voidage
         (1 - solid volume / volume of the cells below HBED) [Pa]
  uFirst, uTop  superficial velocity eps U_z / U of the first and the top
         bed layer (volume averages), from TIME/{eps,U} and 0/V."""
import glob, sys
from foamField import internal_field
rho, mu, d, g = 1.2, 1.8e-5, 1e-3, 9.81

def series(name):
    f = sorted(glob.glob("postProcessing/%s/*/surfaceFieldValue.dat" % name))[-1]
    return [[float(x) for x in l.split()] for l in open(f) if l[0] != "#"]

t, U, H, Lz = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
t0 = float(sys.argv[5]) if len(sys.argv) > 5 else None
pin, pout = series("pInlet"), series("pOutlet")
sel = [k for k in range(len(pin)) if (pin[k][0] >= t0 if t0 is not None else k == len(pin) - 1)]
dp = sum(rho * (pin[k][1] - pout[k][1]) for k in sel) / len(sel) - rho * g * Lz

C, V = internal_field("0/C"), internal_field("0/V")
eps = internal_field(t + "/eps", len(V))      # uniform (no particle): n given
Uc = internal_field(t + "/U")
bed = [c for c in range(len(V)) if C[c][2] < H]
e = sum(eps[c] * V[c] for c in bed) / sum(V[c] for c in bed)
ergun = (150 * mu * (1 - e)**2 * U / (e**3 * d * d) + 1.75 * rho * (1 - e) * U * U / (e**3 * d)) * H

def layer(zc):
    cs = [c for c in range(len(V)) if abs(C[c][2] - zc) < 1e-6]
    return sum(eps[c] * Uc[c][2] * V[c] for c in cs) / sum(V[c] for c in cs) / U

zs = sorted({round(C[c][2], 9) for c in bed})
print(dp, ergun, layer(zs[0]), layer(zs[-1]), e)
