# SPDX-License-Identifier: GPL-3.0-or-later
"""Read the internalField of an ascii OpenFOAM field file.

    from foamField import internal_field
    internal_field("0.2/U")          # [(ux, uy, uz), ...]
    internal_field("0.2/alpha.water")  # [a, ...]

A nonuniform list gives one value per cell: floats for List<scalar>,
tuples for List<vector>/List<tensor>/...; a uniform field needs the cell
count (n=...) and gives it repeated.  Anything else is an error naming
the file (tests read fields the solvers wrote with writeFormat ascii).
"""
import re

_HEAD = re.compile(r"internalField\s+(uniform|nonuniform)\s*")
_LIST = re.compile(r"List<(\w+)>\s*(\d+)\s*\(")


def _value(text):
    text = text.strip()
    if text.startswith("("):
        return tuple(float(x) for x in text.strip("()").split())
    return float(text)


def internal_field(path, n=None):
    s = open(path).read()
    m = _HEAD.search(s)
    if not m:
        raise ValueError("%s: no internalField" % path)
    if m.group(1) == "uniform":
        if n is None:
            raise ValueError("%s: internalField is uniform; give the cell count" % path)
        return [_value(s[m.end():s.index(";", m.end())])] * n
    lm = _LIST.match(s, m.end())
    if not lm:
        raise ValueError("%s: internalField is not an ascii List<...> N (...)" % path)
    count, body = int(lm.group(2)), s[lm.end():]
    if lm.group(1) == "scalar":
        vals = [float(x) for x in body[:body.index(")")].split()]
    else:
        vals = [tuple(float(x) for x in v.split())
                for v in re.findall(r"\(([^()]*)\)", body)[:count]]
    if len(vals) != count:
        raise ValueError("%s: internalField lists %d values, %d read" % (path, count, len(vals)))
    return vals
