#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Fluidised plateau: time-averaged pressure drop against the buoyant weight
of the particles per area.

usage: plateauCheck.py T1 T2 LZ
Prints: dp W dpRaw
  dpRaw  mean of rho (p_inlet - p_outlet) - rho g LZ over T1 <= t <= T2
         (area averages of the patches, every step) [Pa]
  dp     dpRaw minus the change of the particles' momentum over the window,
         (P(T2) - P(T1))/((T2 - T1) A): the time-averaged momentum balance of
         the column, free of the bed's slow oscillation [Pa]
  W      sum m_i g (1 - rho_f/rho_p,i)/A at T2 [Pa]
A = the mesh volume (0/V, postProcess -func writeCellVolumes) / LZ."""
import glob, math, sys
from foamField import internal_field
rho, g = 1.2, 9.81

def series(name):
    f = sorted(glob.glob("postProcessing/%s/*/surfaceFieldValue.dat" % name))[-1]
    return [[float(x) for x in l.split()] for l in open(f) if l[0] != "#"]

def values(path, n=1):
    """The list of a cloud field (N(...) or the uniform form N{v})"""
    s = open(path).read()
    i = s.index("}")
    body = s[s.index("\n", i):]
    k = body.find("{")
    if k >= 0 and (body.find("(") < 0 or k < body.find("(")):
        cnt = int(body[:k].split()[-1])
        return [float(body[k + 1:body.index("}", k)])] * cnt
    j = body.index("(")
    v = [float(x) for x in body[j + 1:body.index("\n)", j)].replace("(", " ").replace(")", " ").split()]
    return [v[k:k + n] for k in range(0, len(v), n)] if n > 1 else v

def timeDir(t):
    return min(glob.glob("[0-9]*"), key=lambda d: abs(float(d) - t) if d.replace(".", "").replace("e-", "").isdigit() else 1e9)

def momentum(t):
    c = timeDir(t) + "/lagrangian/demCloud/"
    d, rp, U = values(c + "d"), values(c + "rho"), values(c + "U", 3)
    m = [r * math.pi * x**3 / 6 for x, r in zip(d, rp)]
    return sum(mi * u[2] for mi, u in zip(m, U)), m, rp

t1, t2, Lz = float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
A = sum(internal_field("0/V")) / Lz
pin, pout = series("pInlet"), series("pOutlet")
sel = [k for k in range(len(pin)) if t1 - 1e-9 <= pin[k][0] <= t2 + 1e-9]
dpRaw = sum(rho * (pin[k][1] - pout[k][1]) for k in sel) / len(sel) - rho * g * Lz
P1, _, _ = momentum(t1)
P2, m, rp = momentum(t2)
W = sum(mi * g * (1 - rho / r) for mi, r in zip(m, rp)) / A
print((dpRaw - (P2 - P1) / ((t2 - t1) * A)), W, dpRaw)
