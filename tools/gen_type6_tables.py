#!/usr/bin/env python3
"""Emit sparse/CcType6Tables.h: the weights of the type-6 cubic C1 quasi-interpolating spline
(Sorokina & Zeilfelder, "Local quasi-interpolation by cubic C1 splines on type-6 tetrahedral
partitions", IMA J. Numer. Anal. 27 (2007) 74-101; paper 003 renders it), checked exactly first.

Usage:
    python3 tools/gen_type6_tables.py              # header to stdout
    python3 tools/gen_type6_tables.py OUT.h        # write it
    python3 tools/gen_type6_tables.py --check F.h  # regenerate, exit 1 if F.h differs

Setting. Data f at the integer points; the cube Q of a point v is [v - 1/2, v + 1/2]^3 (data at cube
centres, as in the paper). Q is cut into 24 congruent tetrahedra [centre, face centre, two corners of
that face on one edge] by the six planes x = +-y, y = +-z, x = +-z through its centre. On each the
spline is a cubic in BB form whose 20 coefficients are fixed combinations of the 27 values around v.

The canonical tetrahedron T0 (relative to the centre): v0 = (0,0,0), v1 = (-1/2,0,0) (the centre of
the face towards -x, "front"), v2 = (-1/2,-1/2,1/2), v3 = (-1/2,1/2,1/2) (front-left-top and
front-right-top). Neighbour names: F/B = -x/+x, L/R = -y/+y, D/T = -z/+z, I = the centre itself;
"FLT" = the neighbour at F + L + T. Every other tetrahedron is the image of T0 under one of the 48
symmetries of the cube, with the data carried along.

The coefficient formulas below (the paper's Section 3, as also implemented by M. Orlitzky's
`spline3`) are not trusted as typed: main() proves, exactly (fractions), before writing anything,
  - the averaging (C1) conditions inside the face pyramid give the coefficients not listed directly,
  - the spline is C1 across every face of every tetrahedron of a cube and of its neighbours, for
    random data (value and gradient agree exactly on both sides),
  - it reproduces the trilinear polynomials 1, x, y, z, xy, yz, xz, xyz exactly, and maps x^2 (y^2,
    z^2) to x^2 + h^2/4: quadratics are NOT reproduced (the corner coefficient is the mean of the 8
    values around the corner, the paper's Example 1 value c_0030 = 17/8 for f = 1 + x + xy + xyz).
"""

import itertools
import random
import sys
from fractions import Fraction as Fr
from math import factorial

DIRS = {'I': (0, 0, 0), 'F': (-1, 0, 0), 'B': (1, 0, 0), 'L': (0, -1, 0), 'R': (0, 1, 0), 'D': (0, 0, -1),
        'T': (0, 0, 1)}


def offset(name):
    p = [0, 0, 0]
    for ch in name:
        p = [p[i] + DIRS[ch][i] for i in range(3)]
    return tuple(p)


# (i, j, k, l): weights on (v0, v1, v2, v3). Each entry: [(weight, "names summed")].
LISTED = {
    (3, 0, 0, 0): [(Fr(3, 8), 'I'), (Fr(1, 12), 'T F L R D B'),
                   (Fr(1, 96), 'LT FL FT RT BT FR FD LD BD BR RD BL')],
    (2, 1, 0, 0): [(Fr(3, 8), 'I'), (Fr(7, 48), 'F'), (Fr(1, 12), 'T R L D'), (Fr(1, 48), 'B'),
                   (Fr(1, 64), 'FT FR FL FD'), (Fr(1, 96), 'RT LD LT RD'), (Fr(1, 192), 'BT BR BL BD')],
    (2, 0, 1, 0): [(Fr(3, 8), 'I'), (Fr(7, 48), 'F T L'), (Fr(1, 48), 'R D B LT FL FT'),
                   (Fr(1, 96), 'RT BT FR FD LD BL')],
    (1, 0, 2, 0): [(Fr(1, 4), 'I'), (Fr(1, 6), 'F L T'), (Fr(1, 12), 'LT FL FT')],
    (1, 0, 1, 1): [(Fr(1, 3), 'I'), (Fr(5, 24), 'F T'), (Fr(1, 12), 'FT'), (Fr(1, 24), 'L R'),
                   (Fr(1, 48), 'LT RT FL FR')],
    (0, 3, 0, 0): [(Fr(13, 48), 'I F'), (Fr(5, 96), 'L R T D FL FR FT FD'),
                   (Fr(1, 192), 'RT RD LT LD FRT FRD FLT FLD')],
    (0, 2, 1, 0): [(Fr(13, 48), 'I F'), (Fr(17, 192), 'L T FL FT'), (Fr(1, 96), 'LT FLT'),
                   (Fr(1, 64), 'R D FR FD'), (Fr(1, 192), 'RT LD FRT FLD')],
    (0, 1, 2, 0): [(Fr(5, 24), 'I F'), (Fr(1, 8), 'L T FL FT'), (Fr(1, 24), 'LT FLT')],
    (0, 1, 1, 1): [(Fr(13, 48), 'I F'), (Fr(7, 48), 'T FT'), (Fr(1, 32), 'L R FL FR'),
                   (Fr(1, 96), 'LT RT FLT FRT')],
    (0, 0, 3, 0): [(Fr(1, 8), 'I F L T LT FL FT FLT')],
    (0, 0, 2, 1): [(Fr(5, 24), 'I F T FT'), (Fr(1, 24), 'L FL LT FLT')],
}
VERT = [(Fr(0), Fr(0), Fr(0)), (Fr(-1, 2), Fr(0), Fr(0)), (Fr(-1, 2), Fr(-1, 2), Fr(1, 2)),
        (Fr(-1, 2), Fr(1, 2), Fr(1, 2))]
# FccCubic's order (sparse/FccSplineTables.h): i from 3 down, then j, then k; l = 3 - i - j - k.
BB_ORDER = [(i, j, k, 3 - i - j - k) for i in range(3, -1, -1) for j in range(3 - i, -1, -1)
            for k in range(3 - i - j, -1, -1)]


def as_vector(terms):
    w = {}
    for weight, names in terms:
        for n in names.split():
            o = offset(n)
            w[o] = w.get(o, Fr(0)) + weight
    return w


def mapped(w, f):
    """The weights w with every data offset mapped by f."""
    return {f(o): v for o, v in w.items()}


def coefficients():
    """All 20 coefficient functionals of T0 as {offset: weight}."""
    C = {k: as_vector(v) for k, v in LISTED.items()}
    mirror_y = lambda o: (o[0], -o[1], o[2])  # swaps v2 and v3 (L <-> R)
    for (i, j, k, l), w in list(C.items()):
        if (i, j, l, k) not in C:
            C[(i, j, l, k)] = mapped(w, mirror_y)
    # C1 across the face [v0, v1, v2] with the tetrahedron [v0, v1, v2, FLD corner] = the image of T0
    # under (x, y, z) -> (x, -z, -y): there v3's image is 2 v1 - v3, so the condition is the average
    # c_{i,j+1,k,0} = (c_{i,j,k,1} + c'_{i,j,k,1}) / 2. It must give what is listed, and the rest.
    flip = lambda o: (o[0], -o[2], -o[1])
    for _ in range(3):  # each pass may make the next one's inputs (by the y mirror)
        for (i, j, k) in [(a, b, 2 - a - b) for a in range(3) for b in range(3 - a)]:
            if (i, j, k, 1) not in C:
                continue
            w1 = C[(i, j, k, 1)]
            avg = {}
            for o, v in list(w1.items()) + list(mapped(w1, flip).items()):
                avg[o] = avg.get(o, Fr(0)) + v / 2
            avg = {o: v for o, v in avg.items() if v != 0}
            key = (i, j + 1, k, 0)
            if key in C and C[key] != avg:
                raise SystemExit("gen_type6_tables: %s disagrees with the averaging condition" % (key,))
            C[key] = avg
        for (i, j, k, l), w in list(C.items()):
            if (i, j, l, k) not in C:
                C[(i, j, l, k)] = mapped(w, mirror_y)
    assert sorted(C) == sorted(BB_ORDER), "not all 20 coefficients"
    for key, w in C.items():
        assert sum(w.values()) == 1 and min(w.values()) > 0, key
    return C


def symmetries():
    for p in itertools.permutations(range(3)):
        for s in itertools.product((1, -1), repeat=3):
            yield lambda x, p=p, s=s: tuple(s[i] * x[p[i]] for i in range(3))


def barycentric(V, x):
    A = [[V[j][i] for j in range(4)] + [x[i]] for i in range(3)] + [[Fr(1)] * 4 + [Fr(1)]]
    for c in range(4):
        piv = next(r for r in range(c, 4) if A[r][c] != 0)
        A[c], A[piv] = A[piv], A[c]
        for r in range(4):
            if r != c and A[r][c] != 0:
                f = A[r][c] / A[c][c]
                A[r] = [A[r][q] - f * A[c][q] for q in range(5)]
    return [A[i][4] / A[i][i] for i in range(4)]


def bb_value(V, b, x):
    lam = barycentric(V, x)
    s = Fr(0)
    for idx in BB_ORDER:
        t = Fr(6, factorial(idx[0]) * factorial(idx[1]) * factorial(idx[2]) * factorial(idx[3]))
        for m in range(4):
            t *= lam[m] ** idx[m]
        s += b[idx] * t
    return s


def bb_gradient(V, b, x):
    g = []
    for axis in range(3):
        f = lambda t: bb_value(V, b, tuple(x[i] + (t if i == axis else 0) for i in range(3)))
        g.append(-f(Fr(-1)) / 3 - f(Fr(0)) / 2 + f(Fr(1)) - f(Fr(2)) / 6)  # exact for a cubic
    return g


def verify(C):
    tets = {}
    for M in symmetries():
        verts = tuple(M(v) for v in VERT)
        if frozenset(verts) not in tets:
            tets[frozenset(verts)] = (verts, {k: mapped(w, M) for k, w in C.items()})
    assert len(tets) == 24
    rng = random.Random(17)
    data = {p: Fr(rng.randint(-50, 50)) for p in itertools.product(range(-2, 4), repeat=3)}

    def piece(centre, verts, co, values):
        V = [tuple(centre[i] + v[i] for i in range(3)) for v in verts]
        b = {k: sum(w * values(tuple(centre[i] + o[i] for i in range(3))) for o, w in co[k].items())
             for k in BB_ORDER}
        return V, b

    # C1 across every face shared by two tetrahedra of the cube at 0 and its neighbours at +x, +y, +z.
    pieces = [piece(c, verts, co, data.__getitem__) for c in [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
              for verts, co in tets.values()]
    faces = {}
    for n, (V, b) in enumerate(pieces):
        for drop in range(4):
            faces.setdefault(frozenset(V[:drop] + V[drop + 1:]), []).append(n)
    shared = [(f, ps) for f, ps in faces.items() if len(ps) == 2]
    assert len(shared) == 4 * 36 + 3 * 4, len(shared)
    for f, (p, q) in shared:
        F = list(f)
        w = [Fr(rng.randint(1, 9)) for _ in range(3)]
        x = tuple(sum(w[j] * F[j][i] for j in range(3)) / sum(w) for i in range(3))
        (V1, b1), (V2, b2) = pieces[p], pieces[q]
        if bb_value(V1, b1, x) != bb_value(V2, b2, x) or bb_gradient(V1, b1, x) != bb_gradient(V2, b2, x):
            raise SystemExit("gen_type6_tables: not C1 across the face %s" % sorted(F))
    # Reproduction: the spline of p equals p + shift (exactly) at random points of every tetrahedron.
    cases = [((0, 0, 0), 0), ((1, 0, 0), 0), ((0, 1, 0), 0), ((0, 0, 1), 0), ((1, 1, 0), 0), ((0, 1, 1), 0),
             ((1, 0, 1), 0), ((1, 1, 1), 0), ((2, 0, 0), Fr(1, 4)), ((0, 2, 0), Fr(1, 4)), ((0, 0, 2), Fr(1, 4))]
    for (ex, shift) in cases:
        poly = lambda x, e=ex: Fr(3, 7) * x[0] ** e[0] * x[1] ** e[1] * x[2] ** e[2]
        for verts, co in tets.values():
            V, b = piece((0, 0, 0), verts, co, poly)
            w = [Fr(rng.randint(1, 9)) for _ in range(4)]
            x = tuple(sum(w[j] * V[j][i] for j in range(4)) / sum(w) for i in range(3))
            if bb_value(V, b, x) != poly(x) + Fr(3, 7) * shift:
                raise SystemExit("gen_type6_tables: x^%s is not mapped as stated" % (ex,))
    # The paper's Example 1: f = 1 + x + xy + xyz on the 3^3 points of [0, 2]^3, cube at (1,1,1):
    # c_0030 = 17/8 on T0.
    f = lambda p: 1 + p[0] + p[0] * p[1] + p[0] * p[1] * p[2]
    c0030 = sum(w * f((1 + o[0], 1 + o[1], 1 + o[2])) for o, w in C[(0, 0, 3, 0)].items())
    assert c0030 == Fr(17, 8), c0030


def emit(C):
    order = [(dx, dy, dz) for dz in (-1, 0, 1) for dy in (-1, 0, 1) for dx in (-1, 0, 1)]
    out = []
    w = out.append
    w("/* sparse/CcType6Tables.h -- GENERATED by tools/gen_type6_tables.py; DO NOT EDIT.")
    w(" * Regenerate: python3 tools/gen_type6_tables.py sparse/CcType6Tables.h")
    w(" * Verify:     python3 tools/gen_type6_tables.py --check sparse/CcType6Tables.h")
    w(" *")
    w(" * The type-6 cubic C1 quasi-interpolating spline (Sorokina & Zeilfelder 2007): the 20 BB")
    w(" * coefficients of the canonical tetrahedron T0 = [(0,0,0), (-1/2,0,0), (-1/2,-1/2,1/2),")
    w(" * (-1/2,1/2,1/2)] (relative to the cube's centre, a data point) as integer weights over 192 of")
    w(" * the 27 values at offsets (dx, dy, dz) in {-1,0,1}^3, index (dx+1) + 3 (dy+1) + 9 (dz+1).")
    w(" * Row r is FccCubic's coefficient r: (i,j,k,l) with i from 3 down, then j, then k.")
    w(" * The generator proves C1 continuity, trilinear reproduction and x^2 -> x^2 + h^2/4 first.")
    w(" */")
    w("#ifndef FCC_CC_TYPE6_TABLES_H")
    w("#define FCC_CC_TYPE6_TABLES_H")
    w("")
    w("#define FCC_TYPE6_DENOM 192.0f")
    w("")
    w("FCC_CONST_INT_ARRAY(cc_type6_weights, 540) FCC_ARRAY_OPEN(int, 540)")
    rows = []
    for r, idx in enumerate(BB_ORDER):
        ints = [C[idx].get(o, Fr(0)) * 192 for o in order]
        assert all(v.denominator == 1 for v in ints)
        rows.append("    " + ", ".join("%d" % int(v) for v in ints) + "  /* (%d,%d,%d,%d) */" % idx)
    for n, row in enumerate(rows):
        text = row.split("  /*")
        w(text[0] + ("," if n + 1 < len(rows) else "") + "  /*" + text[1])
    w("FCC_ARRAY_CLOSE;")
    w("")
    # The same rows unrolled: only the non-zero terms (244 of 540), with the weights as literals. A GPU
    # compiler may copy a constant array indexed in a loop into every thread's memory; these are sums
    # of registers. Each starts from 0.0f and adds its terms in index order, as the loop over a row
    # does, less the zero terms (which add +-0 to it): the same value for finite samples.
    w("/* The rows as sums of their non-zero terms: b[r] = row r . v / FCC_TYPE6_DENOM (test_type6 holds")
    w(" * them to the table's loop bit for bit). */")
    w("#define CC_TYPE6_ROWS(b, v) \\")
    for r, idx in enumerate(BB_ORDER):
        ints = [int(C[idx].get(o, Fr(0)) * 192) for o in order]
        terms = " + ".join("%d.0f * v[%d]" % (x, i) for i, x in enumerate(ints) if x != 0)
        w("  b[%d] = (0.0f + %s) * (1.0f / FCC_TYPE6_DENOM);%s" % (r, terms, " \\" if r + 1 < len(BB_ORDER) else ""))
    w("")
    w("#endif /* FCC_CC_TYPE6_TABLES_H */")
    return "\n".join(out) + "\n"


def main(argv):
    C = coefficients()
    verify(C)
    text = emit(C)
    if len(argv) == 3 and argv[1] == "--check":
        with open(argv[2], "r", newline="") as f:
            if f.read() != text:
                print("gen_type6_tables: %s is stale; regenerate with python3 tools/gen_type6_tables.py %s"
                      % (argv[2], argv[2]))
                return 1
        return 0
    if len(argv) == 2 and not argv[1].startswith("-"):
        with open(argv[1] + ".tmp", "w", newline="") as f:
            f.write(text)
        import os
        os.replace(argv[1] + ".tmp", argv[1])
        return 0
    if len(argv) == 1:
        sys.stdout.write(text)
        return 0
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
