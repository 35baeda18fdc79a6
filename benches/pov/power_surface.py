#!/usr/bin/env python3
"""Writes the POV-Ray twins of scenes/torus-sheets16.scene and torus-sheets20.scene.

Each scene's surface is g^k - eps for the torus quartic
g = (x^2 + y^2 + z^2 + 3)^2 - 16 (x^2 + y^2) (major radius 2, minor 1), so its real set is
g = eps^(1/k) (and g = -eps^(1/k) for even k): tori 0.01 apart in depth at the outer
equator, the "sheets that nearly touch" of issue 11. Every coefficient of the expansion is an
integer or a power of two, exact in f64, so POV-Ray's `polynomial` and `render`'s expansion
of the scene's equation hold the same numbers. The expansion is exact (Python integers and
Fractions); no dependency beyond the standard library.

Usage: python3 benches/pov/power_surface.py   (rewrites benches/pov/torus-sheets*.pov)
"""
from fractions import Fraction
from pathlib import Path


def mul(p, q):
    r = {}
    for (a, ca) in p.items():
        for (b, cb) in q.items():
            e = (a[0] + b[0], a[1] + b[1], a[2] + b[2])
            r[e] = r.get(e, 0) + ca * cb
    return {e: c for e, c in r.items() if c != 0}


def power(p, k):
    r = {(0, 0, 0): 1}
    for _ in range(k):
        r = mul(r, p)
    return r


S = {(2, 0, 0): 1, (0, 2, 0): 1, (0, 0, 2): 1, (0, 0, 0): 3}
G = mul(S, S)
for e in [(2, 0, 0), (0, 2, 0)]:
    G[e] = G.get(e, 0) - 16
G = {e: c for e, c in G.items() if c != 0}

HEADER = """// POV-Ray 3.7 equivalent of scenes/torus-sheets{deg}.scene, for benches/vs-povray.sh; written
// by benches/pov/power_surface.py (do not edit): ((x^2+y^2+z^2+3)^2 - 16(x^2+y^2))^{k} - {eps},
// expanded exactly (every coefficient exact in f64). `sturm`: POV-Ray's Sturm-sequence solver.
// Right-handed, z up: `right -x` flips POV-Ray's left-handed default.
#version 3.7;
global_settings {{ assumed_gamma 1.0 }}
camera {{
  location <0, -8, 5>
  sky <0, 0, 1>
  up <0, 0, 1>
  right <-1, 0, 0>
  angle 50
  look_at <0, 0, 0>
}}
background {{ rgb 0.2 }}
light_source {{ <5, -5, 10> rgb 1 }}
polynomial {{
  {deg},
"""

FOOTER = """  sturm
  clipped_by { box { <-3.1, -3.1, -1.1>, <3.1, 3.1, 1.1> } }
  bounded_by { box { <-3.1, -3.1, -1.1>, <3.1, 3.1, 1.1> } }
  pigment { rgb <0.8, 0.3, 0.2> }
  finish { ambient 0.1 diffuse 0.7 phong 0.5 phong_size 40 }
}
"""

for k, eps in [(4, Fraction(1, 16)), (5, Fraction(1, 32))]:
    p = power(G, k)
    p[(0, 0, 0)] = p.get((0, 0, 0), 0) - eps
    deg = 4 * k
    terms = []
    for e in sorted(p):
        c = Fraction(p[e])
        f = float(c)
        assert Fraction(f) == c, f"coefficient {c} of {e} not exact in f64"
        terms.append(f"    xyz({e[0]}, {e[1]}, {e[2]}): {f!r}")
    text = HEADER.format(deg=deg, k=k, eps=eps) + ",\n".join(terms) + "\n" + FOOTER
    out = Path(__file__).with_name(f"torus-sheets{deg}.pov")
    out.write_text(text)
    print(f"{out}: {len(terms)} terms")
