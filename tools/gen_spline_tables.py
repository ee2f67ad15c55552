#!/usr/bin/env python3
"""Derive the exact Bernstein-Bezier (BB) tables of the FCC six-direction box
spline and emit sparse/FccSplineTables.h.

Usage:
    python3 tools/gen_spline_tables.py              # header to stdout
    python3 tools/gen_spline_tables.py OUT.h        # write header to OUT.h
    python3 tools/gen_spline_tables.py --check F.h  # regenerate, exit 1 if F.h differs

Everything is exact rational arithmetic (stdlib `fractions`), no third-party
packages.  See docs/SPLINE.md for the derivation and conventions.

Pipeline
  1. Exact box-spline evaluator (de Boor-Hollig recurrence, memoized) at
     rational points in general position; self-tested in 1D and 2D.
  2. For the canonical tetrahedra tau0 / tau4 of an even unit cube and every
     FCC point k in [-3,3]^3, fit the cubic of M_fcc(x - k) on the tet from 20
     generic interior points (exact solve), verify it at extra points, keep
     its 20 BB coefficients.  Stencil = the k with a nonzero piece; the union
     must be the 19 offsets of the paper (Kim et al., Fig. 4), in that order.
  3. Assert M_fcc facts (values at lattice points, partition of unity,
     support, C^1 across faces).
  4. Quadratic BB tables of M_xi = D_xi M_fcc (xi in 110, 101, 011) by
     differentiating the cubic pieces, cross-checked exactly against the
     five-direction backward-difference formula.
  5. Scale to integers (common denominators D3, D2) and emit code.
"""

import sys
import random
from fractions import Fraction as Fr
from math import factorial, gcd

# ----------------------------------------------------------------------------
# Small exact linear algebra
# ----------------------------------------------------------------------------


def mat_inverse(A):
    """Exact inverse of a square matrix of Fractions (Gauss-Jordan)."""
    n = len(A)
    M = [[Fr(v) for v in row] + [Fr(int(i == j)) for j in range(n)]
         for i, row in enumerate(A)]
    for col in range(n):
        piv = next((r for r in range(col, n) if M[r][col] != 0), None)
        if piv is None:
            raise ValueError("singular matrix")
        M[col], M[piv] = M[piv], M[col]
        inv = 1 / M[col][col]
        M[col] = [v * inv for v in M[col]]
        for r in range(n):
            if r != col and M[r][col] != 0:
                f = M[r][col]
                M[r] = [a - f * b for a, b in zip(M[r], M[col])]
    return [row[n:] for row in M]


def rank(vectors):
    M = [[Fr(v) for v in vec] for vec in vectors]
    rk, ncol = 0, len(M[0]) if M else 0
    for col in range(ncol):
        piv = next((r for r in range(rk, len(M)) if M[r][col] != 0), None)
        if piv is None:
            continue
        M[rk], M[piv] = M[piv], M[rk]
        for r in range(len(M)):
            if r != rk and M[r][col] != 0:
                f = M[r][col] / M[rk][col]
                M[r] = [a - f * b for a, b in zip(M[r], M[rk])]
        rk += 1
    return rk


def det(A):
    n = len(A)
    M = [[Fr(v) for v in row] for row in A]
    d = Fr(1)
    for col in range(n):
        piv = next((r for r in range(col, n) if M[r][col] != 0), None)
        if piv is None:
            return Fr(0)
        if piv != col:
            M[col], M[piv] = M[piv], M[col]
            d = -d
        d *= M[col][col]
        for r in range(col + 1, n):
            f = M[r][col] / M[col][col]
            M[r] = [a - f * b for a, b in zip(M[r], M[col])]
    return d


def matvec(A, x):
    return tuple(sum(a * b for a, b in zip(row, x)) for row in A)


def lcm(a, b):
    return a * b // gcd(a, b)


# ----------------------------------------------------------------------------
# 1. Box-spline evaluator
# ----------------------------------------------------------------------------

_subset_info = {}
_box_memo = {}


def _info(dirs):
    """Per direction set: spanning?, basis indices, inverse basis, bbox, |det|."""
    info = _subset_info.get(dirs)
    if info is not None:
        return info
    n = len(dirs[0])
    basis = []
    for i, d in enumerate(dirs):
        if rank([dirs[b] for b in basis] + [d]) == len(basis) + 1:
            basis.append(i)
        if len(basis) == n:
            break
    spans = len(basis) == n
    inv = absdet = None
    if spans:
        B = [[dirs[b][r] for b in basis] for r in range(n)]  # columns = dirs
        inv = mat_inverse(B)
        absdet = abs(det(B))
    lo = tuple(sum(min(0, d[r]) for d in dirs) for r in range(n))
    hi = tuple(sum(max(0, d[r]) for d in dirs) for r in range(n))
    info = (spans, basis, inv, absdet, lo, hi)
    _subset_info[dirs] = info
    return info


def box(dirs, x):
    """M_dirs(x), exact.  dirs: tuple of integer direction tuples; x: tuple of
    Fractions in general position (on no knot plane, i.e. no hyperplane spanned
    by n-1 directions through an integer point)."""
    key = (dirs, x)
    val = _box_memo.get(key)
    if val is not None:
        return val
    spans, basis, inv, absdet, lo, hi = _info(dirs)
    n, m = len(x), len(dirs)
    if not spans or any(xi <= l or xi >= h for xi, l, h in zip(x, lo, hi)):
        val = Fr(0)
    else:
        tb = matvec(inv, x)  # x = sum_b tb[b] * dirs[basis[b]]
        if m == n:  # half-open parallelepiped
            val = Fr(1) / absdet if all(0 <= t < 1 for t in tb) else Fr(0)
        else:
            t = [Fr(0)] * m
            for b, tv in zip(basis, tb):
                t[b] = tv
            acc = Fr(0)
            for i, xi in enumerate(dirs):
                sub = dirs[:i] + dirs[i + 1:]
                if t[i] != 0:
                    acc += t[i] * box(sub, x)
                if t[i] != 1:
                    acc += (1 - t[i]) * box(sub, tuple(a - b for a, b in zip(x, xi)))
            val = acc / (m - n)
    _box_memo[key] = val
    return val


XI = ((1, 1, 0), (1, 0, 1), (0, 1, 1), (1, -1, 0), (0, 1, -1), (-1, 0, 1))
XI_C = (1, 1, 1)
# knot-plane normals: cross products of all independent pairs of XI
NORMALS = sorted({tuple(c) for a in XI for b in XI
                  for c in [(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                             a[0] * b[1] - a[1] * b[0])] if any(c)})


def generic(x):
    """True if x lies on no (integer-shifted) knot plane of any sub-box-spline."""
    return all((sum(n * v for n, v in zip(nv, x))).denominator != 1 for nv in NORMALS)


def m_fcc(x):
    # x must be generic (checked once per sample point; invariant under the
    # integer shifts x - k used below)
    return 2 * box(XI, tuple(a + c for a, c in zip(x, XI_C)))


DERIV_DIRS = ((1, 1, 0), (1, 0, 1), (0, 1, 1))  # d[0]=d110, d[1]=d101, d[2]=d011
DERIV_NAMES = ("110", "101", "011")


def m_xi_backward(xi, x):
    """M_xi(x) = 2 M_{XI\\xi}(x+xc) - 2 M_{XI\\xi}(x+xc-xi)  (paper, Sec. 4.2)."""
    sub = tuple(d for d in XI if d != xi)
    y = tuple(a + c for a, c in zip(x, XI_C))
    return 2 * box(sub, y) - 2 * box(sub, tuple(a - b for a, b in zip(y, xi)))


def self_test_box():
    h = ((1,), (1,))  # hat on [0,2]
    for v, e in [(Fr(1, 3), Fr(1, 3)), (Fr(3, 2), Fr(1, 2)), (Fr(5, 2), 0), (Fr(-1, 7), 0)]:
        assert box(h, (v,)) == e, ("hat", v)
    c = ((1,), (1,), (1,), (1,))  # cubic B-spline on [0,4]
    assert box(c, (Fr(1, 2),)) == Fr(1, 48)
    assert box(c, (Fr(3, 2),)) == Fr(23, 48)
    assert box(c, (Fr(2, 1) + Fr(1, 5),)) == Fr(2, 3) - Fr(1, 25) + Fr(1, 250)
    # Courant element (linear hat, peak 1 at (1,1))
    ce = ((1, 0), (0, 1), (1, 1))

    def courant(a, b):  # reference, offsets from the peak
        if a >= 0 and b >= 0 or a <= 0 and b <= 0:
            return max(Fr(0), 1 - max(abs(a), abs(b)))
        return max(Fr(0), 1 - abs(a) - abs(b))
    for a, b in [(Fr(1, 7), Fr(1, 5)), (Fr(1, 7), Fr(-1, 5)), (Fr(-2, 7), Fr(3, 11)),
                 (Fr(-3, 7), Fr(-2, 9)), (Fr(9, 7), Fr(1, 3))]:
        assert box(ce, (1 + a, 1 + b)) == courant(a, b), ("courant", a, b)
    # partition of unity of the Courant element on Z^2
    x = (Fr(2, 7), Fr(5, 11))
    assert sum(box(ce, (x[0] - i, x[1] - j)) for i in range(-3, 4) for j in range(-3, 4)) == 1


# ----------------------------------------------------------------------------
# BB machinery on a tetrahedron
# ----------------------------------------------------------------------------


def multi_indices(d):
    """(i,j,k,l) for v0..v3: i from d down, j from d-i down, k from d-i-j down."""
    out = []
    for i in range(d, -1, -1):
        for j in range(d - i, -1, -1):
            for k in range(d - i - j, -1, -1):
                out.append((i, j, k, d - i - j - k))
    return out


MI3, MI2 = multi_indices(3), multi_indices(2)
IDX3 = {a: n for n, a in enumerate(MI3)}
IDX2 = {a: n for n, a in enumerate(MI2)}


def bernstein(alpha, lam):
    d = sum(alpha)
    v = Fr(factorial(d))
    for a, l in zip(alpha, lam):
        v = v * l ** a / factorial(a)
    return v


def bb_eval(coefs, mis, lam):
    return sum(c * bernstein(a, lam) for c, a in zip(coefs, mis))


def bary_to_point(verts, lam):
    return tuple(sum(l * v[r] for l, v in zip(lam, verts)) for r in range(3))


def point_to_bary(verts, x):
    A = [[verts[i][r] - verts[0][r] for i in (1, 2, 3)] for r in range(3)]
    l123 = matvec(mat_inverse(A), tuple(x[r] - verts[0][r] for r in range(3)))
    return (1 - sum(l123),) + tuple(l123)


def dir_to_bary(verts, u):
    """Barycentric direction a (sum a = 0) with u = sum a_i v_i."""
    A = [[verts[i][r] - verts[0][r] for i in (1, 2, 3)] for r in range(3)]
    a123 = matvec(mat_inverse(A), u)
    return (-sum(a123),) + tuple(a123)


def bb_derivative(coefs3, verts, u):
    """Quadratic BB coefficients of D_u p for the cubic p (BB coefs3 on verts)."""
    a = dir_to_bary(verts, u)
    out = []
    for beta in MI2:
        acc = Fr(0)
        for i in range(4):
            up = list(beta)
            up[i] += 1
            acc += a[i] * coefs3[IDX3[tuple(up)]]
        out.append(3 * acc)
    return out


def sample_points(verts, count, rng, face=None):
    """Distinct rational points strictly inside the tet (generic: on no knot
    plane), or strictly inside the face given as a tuple of 3 vertex indices
    (a face may itself lie on a knot plane; face points are only used to
    compare polynomial pieces, never fed to the box-spline evaluator)."""
    pts = []
    while len(pts) < count:
        w = [rng.randint(1, 997) for _ in range(4)]
        if face is not None:
            w = [wi if i in face else 0 for i, wi in enumerate(w)]
        lam = tuple(Fr(wi, sum(w)) for wi in w)
        x = bary_to_point(verts, lam)
        if (face is not None or generic(x)) and lam not in pts:
            pts.append(lam)
    return pts


class TetFitter:
    """Fits polynomials of degree 3 (or 2) in BB form on one tetrahedron."""

    def __init__(self, verts, rng, n_check=10):
        self.verts = verts
        self.pts = sample_points(verts, 20 + n_check, rng)
        self.xs = [bary_to_point(verts, l) for l in self.pts]
        self.inv, self.chk = {}, {}
        for deg, mis in ((3, MI3), (2, MI2)):
            n = len(mis)
            A = [[bernstein(a, lam) for a in mis] for lam in self.pts]
            self.inv[deg] = mat_inverse(A[:n])
            self.chk[deg] = A[n:]  # Bernstein values at the check points

    def fit(self, f, deg):
        """BB coefficients of f on the tet; asserts f is that polynomial at the
        remaining sample points (so f is polynomial of degree deg there)."""
        mis = MI3 if deg == 3 else MI2
        n = len(mis)
        vals = [f(x) for x in self.xs]
        if not any(vals):
            return [Fr(0)] * n
        coefs = list(matvec(self.inv[deg], vals[:n]))
        for row, v in zip(self.chk[deg], vals[n:]):
            assert sum(c * b for c, b in zip(coefs, row)) == v, "not one polynomial piece"
        return coefs


# ----------------------------------------------------------------------------
# 2.-4. Derivation
# ----------------------------------------------------------------------------

TETS = {
    "t0": ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)),   # corner tet of even cube
    "t4": ((1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1)),   # central tet of even cube
}

PAPER_STENCIL = [
    (0, 0, 0), (2, 0, 0), (0, 2, 0), (0, 0, 2), (2, 1, 1), (0, 1, 1), (0, 1, -1),
    (0, -1, -1), (0, -1, 1), (1, 2, 1), (1, 0, 1), (-1, 0, 1), (-1, 0, -1), (1, 0, -1),
    (1, 1, 2), (1, 1, 0), (-1, 1, 0), (-1, -1, 0), (1, -1, 0)]

BOX_RANGE = [(a, b, c) for a in range(-3, 4) for b in range(-3, 4) for c in range(-3, 4)
             if (a + b + c) % 2 == 0]


def sub(x, k):
    return tuple(a - b for a, b in zip(x, k))


def cubic_pieces(fitter):
    """{k: 20 BB coefs} for all FCC k in [-3,3]^3 with a nonzero piece."""
    out = {}
    for k in BOX_RANGE:
        c = fitter.fit(lambda x: m_fcc(sub(x, k)), 3)
        if any(c):
            out[k] = c
    return out


def check_c1(verts_a, pieces_a, verts_b, pieces_b, rng):
    """Value and gradient of every M_fcc(.-k) piece agree on the shared face."""
    shared = [v for v in verts_a if v in verts_b]
    assert len(shared) == 3
    face = tuple(verts_a.index(v) for v in shared)
    lams = sample_points(verts_a, 15, rng, face=face)
    lbs = [point_to_bary(verts_b, bary_to_point(verts_a, l)) for l in lams]
    B3a = [[bernstein(a, l) for a in MI3] for l in lams]
    B3b = [[bernstein(a, l) for a in MI3] for l in lbs]
    B2a = [[bernstein(a, l) for a in MI2] for l in lams]
    B2b = [[bernstein(a, l) for a in MI2] for l in lbs]

    def ev(c, rows):
        return [sum(x * y for x, y in zip(c, row)) for row in rows]
    zero = [Fr(0)] * 20
    for k in set(pieces_a) | set(pieces_b):
        ca, cb = pieces_a.get(k, zero), pieces_b.get(k, zero)
        assert ev(ca, B3a) == ev(cb, B3b), ("C0", k)
        for u in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
            assert (ev(bb_derivative(ca, verts_a, u), B2a) ==
                    ev(bb_derivative(cb, verts_b, u), B2b)), ("C1", k, u)


def derive():
    self_test_box()
    rng = random.Random(20240601)
    fitters = {name: TetFitter(v, rng) for name, v in TETS.items()}
    cubic = {name: cubic_pieces(f) for name, f in fitters.items()}

    # --- stencil ------------------------------------------------------------
    union = set(cubic["t0"]) | set(cubic["t4"])
    assert union == set(PAPER_STENCIL) and len(PAPER_STENCIL) == 19, sorted(union)
    stencil = PAPER_STENCIL

    # --- facts about M_fcc --------------------------------------------------
    for name, verts in TETS.items():
        for k, c in cubic[name].items():
            # support: piece nonzero only if the tet meets |x-k|_inf < 2
            assert all(min(abs(v[r] - k[r]) for v in verts) < 2 for r in range(3))
            for vi, v in enumerate(verts):
                e = [0, 0, 0, 0]
                e[vi] = 3
                val = c[IDX3[tuple(e)]]  # vertex value = corner BB coefficient
                y = sub(v, k)
                if sum(y) % 2 == 0:  # FCC point
                    ay = sorted(abs(t) for t in y)
                    want = (Fr(1, 2) if ay == [0, 0, 0] else
                            Fr(1, 24) if ay == [0, 1, 1] else Fr(0))
                    assert val == want, ("lattice value", name, k, v, val)
        # partition of unity: sum over the stencil of every BB coefficient = 1
        for a in range(20):
            assert sum(c[a] for c in cubic[name].values()) == 1, ("PU", name)
    assert cubic["t0"][(0, 0, 0)][0] == Fr(1, 2)  # M_fcc(0) = 1/2
    # partition of unity / support directly from the evaluator at generic points
    for x in [(Fr(3, 7), Fr(-5, 11), Fr(13, 17)), (Fr(-29, 13), Fr(7, 19), Fr(2, 23))]:
        assert generic(x)
        tot = Fr(0)
        for a in range(-4, 5):
            for b in range(-4, 5):
                for cc in range(-4, 5):
                    if (a + b + cc) % 2 == 0:
                        y = sub(x, (a, b, cc))
                        v = m_fcc(y)
                        if max(abs(t) for t in y) >= 2:
                            assert v == 0, ("support", y)
                        tot += v
        assert tot == 1, ("PU direct", x, tot)

    # --- C^1 across faces ---------------------------------------------------
    # tau1: corner tet of the even cube at (1,1,0); tau0': corner tet at the
    # origin of the odd cube [-1,0]x[0,1]^2 (shares the face x=0 with tau0).
    extra = {
        "t1": ((1, 1, 0), (0, 1, 0), (1, 0, 0), (1, 1, 1)),
        "t0x": ((0, 0, 0), (-1, 0, 0), (0, 1, 0), (0, 0, 1)),
    }
    ep = {n: cubic_pieces(TetFitter(v, rng)) for n, v in extra.items()}
    check_c1(TETS["t0"], cubic["t0"], TETS["t4"], cubic["t4"], rng)
    check_c1(TETS["t4"], cubic["t4"], extra["t1"], ep["t1"], rng)
    check_c1(TETS["t0"], cubic["t0"], extra["t0x"], ep["t0x"], rng)

    # --- derivative kernels ---------------------------------------------------
    quad = {}
    for name, verts in TETS.items():
        quad[name] = []
        for xi in DERIV_DIRS:
            tab = {}
            for k, c in cubic[name].items():
                q = bb_derivative(c, verts, xi)
                if any(q):
                    tab[k] = q
            # cross-check against the 5-direction backward difference formula
            for k in BOX_RANGE:
                q = fitters[name].fit(lambda x: m_xi_backward(xi, sub(x, k)), 2)
                assert q == tab.get(k, [Fr(0)] * 10), ("deriv mismatch", name, xi, k)
            assert set(tab) <= set(cubic[name]) <= set(stencil)
            for a in range(10):
                assert sum(q[a] for q in tab.values()) == 0, ("deriv PU", name, xi)
            quad[name].append(tab)

    # --- common denominators ------------------------------------------------
    d3 = d2 = 1
    for name in TETS:
        for c in cubic[name].values():
            for v in c:
                d3 = lcm(d3, v.denominator)
        for tab in quad[name]:
            for q in tab.values():
                for v in q:
                    d2 = lcm(d2, v.denominator)
    return stencil, cubic, quad, d3, d2


# ----------------------------------------------------------------------------
# 5. Code generation
# ----------------------------------------------------------------------------


def flit(n):
    return "%d.0f" % n


def lin_comb(terms):
    """terms: list of (int weight, str expr) -> 'w*e + ...' (zero terms skipped)."""
    parts = []
    for w, e in terms:
        if w == 0:
            continue
        mag = "" if abs(w) == 1 else flit(abs(w)) + "*"
        if not parts:
            parts.append(("-" if w < 0 else "") + mag + e)
        else:
            parts.append(("- " if w < 0 else "+ ") + mag + e)
    return " ".join(parts) if parts else "0.0f"


def wrap(lhs, rhs, comment, indent="    ", width=96):
    words = rhs.split(" ")
    lines, cur = [], indent + lhs + " = "
    cont = " " * len(cur)
    for i, w in enumerate(words):
        piece = w if i == 0 else " " + w
        if len(cur) + len(piece) > width and cur.strip() and i > 0 and w in ("+", "-"):
            lines.append(cur)
            cur = cont + w
        else:
            cur += piece
    lines.append(cur + ";" + ("  /* %s */" % comment if comment else ""))
    return lines


def mi_str(a):
    return "(%s)" % ",".join(str(v) for v in a)


def decasteljau(fname, ctype, arg, deg):
    L = ["FCC_FUNC float %s(%s %s, FCC_VEC4 l)" % (fname, ctype, arg), "{"]
    comps = ("l.x", "l.y", "l.z", "l.w")
    prev = {a: "%s.b[%d]" % (arg, n) for n, a in enumerate(multi_indices(deg))}
    for d in range(deg - 1, -1, -1):
        cur = {}
        for n, a in enumerate(multi_indices(d)):
            terms = []
            for i in range(4):
                up = list(a)
                up[i] += 1
                terms.append("%s*%s" % (comps[i], prev[tuple(up)]))
            expr = " + ".join(terms)
            if d == 0:
                L.append("    return %s;" % expr)
            else:
                name = "p%d_%d" % (d, n)
                L.append("    float %s = %s;" % (name, expr))
                cur[a] = name
        prev = cur
    L.append("}")
    return L


def decasteljau_step(fname, ctype, arg, deg):
    """One de Casteljau step: the degree deg-1 coefficients at l (blossoming, FccRay.h)."""
    rtype = "FccQuadratic" if deg == 3 else "FCC_VEC4"
    L = ["FCC_FUNC %s %s(%s %s, FCC_VEC4 l)" % (rtype, fname, ctype, arg), "{",
         "    %s r;" % rtype]
    comps = ("l.x", "l.y", "l.z", "l.w")
    prev = {a: "%s.b[%d]" % (arg, n) for n, a in enumerate(multi_indices(deg))}
    for n, a in enumerate(multi_indices(deg - 1)):
        terms = []
        for i in range(4):
            up = list(a)
            up[i] += 1
            terms.append("%s*%s" % (comps[i], prev[tuple(up)]))
        target = "r.b[%d]" % n if deg == 3 else "r.%s" % "xyzw"[n]
        L.append("    %s = %s;" % (target, " + ".join(terms)))
    L.append("    return r;")
    L.append("}")
    return L


def generate():
    stencil, cubic, quad, d3, d2 = derive()
    sidx = {k: i for i, k in enumerate(stencil)}
    out = []
    w = out.append
    w("/* sparse/FccSplineTables.h -- GENERATED by tools/gen_spline_tables.py; DO NOT EDIT.")
    w(" * Regenerate: python3 tools/gen_spline_tables.py sparse/FccSplineTables.h")
    w(" * Verify:     python3 tools/gen_spline_tables.py --check sparse/FccSplineTables.h")
    w(" *")
    w(" * Exact Bernstein-Bezier (BB) tables of the FCC six-direction box spline")
    w(" *   M_fcc(x) = 2 M_Xi(x + (1,1,1)),  Xi = {110, 101, 011, 1-10, 01-1, -101},")
    w(" * spline s(x) = sum_j c_j M_fcc(x - j) over FCC points j (j.x+j.y+j.z even).")
    w(" * Derivative kernels M_xi = D_xi M_fcc (xi = 110, 101, 011; unnormalized):")
    w(" *   d_xi(x) = sum_j c_j M_xi(x - j),  grad s = 0.5*(d110+d101-d011,")
    w(" *                                                   d110+d011-d101,")
    w(" *                                                   d101+d011-d110).")
    w(" *")
    w(" * Canonical pieces (even unit cube, canonical FCC origin o = (0,0,0)):")
    w(" *   tau0 (corner): v0=(0,0,0) v1=(1,0,0) v2=(0,1,0) v3=(0,0,1)   [x+y+z <= 1]")
    w(" *   tau4 (centre): v0=(1,0,0) v1=(0,1,0) v2=(0,0,1) v3=(1,1,1)")
    w(" * Samples: s.v[i] = c at site o + R*offset_i, offset_i = (fcc_stencil_dx[i],")
    w(" *   fcc_stencil_dy[i], fcc_stencil_dz[i]) (Kim et al. Fig. 4 order).")
    w(" * BB index order (i,j,k,l) = weights on (v0,v1,v2,v3): i from d down to 0,")
    w(" *   then j from d-i down, then k from d-i-j down, l = d-i-j-k.")
    w(" *   cubic:     b[0]=(3,0,0,0) b[1]=(2,1,0,0) b[2]=(2,0,1,0) b[3]=(2,0,0,1) b[4]=(1,2,0,0) ...")
    w(" *   quadratic: b[0]=(2,0,0,0) b[1]=(1,1,0,0) b[2]=(1,0,1,0) b[3]=(1,0,0,1) b[4]=(0,2,0,0) ...")
    w(" * fcc_cubic_*  return BB coefficients * FCC_CUBIC_DENOM, fcc_derivs_* return")
    w(" * BB coefficients * FCC_DERIV_DENOM (d[0]=d110, d[1]=d101, d[2]=d011): the TRUE")
    w(" * values are the de Casteljau result DIVIDED BY the respective DENOM.")
    w(" * fcc_decasteljau3/2 evaluate at barycentric l = (l0,l1,l2,l3) w.r.t. (v0..v3).")
    w(" * Derivatives are w.r.t. the canonical frame; apply R to map back.")
    w(" * Requires (defined by the including dialect header): FCC_FUNC, FCC_VEC4,")
    w(" *   FccSamples, FccCubic, FccQuadratic, FccDerivs, FCC_CONST_INT_ARRAY,")
    w(" *   FCC_ARRAY_OPEN, FCC_ARRAY_CLOSE.")
    for name, label in (("t0", "tau0"), ("t4", "tau4")):
        used = [sidx[k] for k in stencil if k in cubic[name]]
        w(" * %s uses samples %s (%d of 19)." % (label, ",".join(map(str, used)), len(used)))
    w(" */")
    w("#ifndef FCC_SPLINE_TABLES_H")
    w("#define FCC_SPLINE_TABLES_H")
    w("")
    w("#define FCC_STENCIL_SIZE 19")
    w("#define FCC_CUBIC_DENOM %s" % flit(d3))
    w("#define FCC_DERIV_DENOM %s" % flit(d2))
    w("")
    for ax, nm in enumerate("xyz"):
        vals = ", ".join(str(k[ax]) for k in stencil)
        w("FCC_CONST_INT_ARRAY(fcc_stencil_d%s, 19) FCC_ARRAY_OPEN(int, 19) %s FCC_ARRAY_CLOSE;"
          % (nm, vals))
    stats = {}
    for name, label in (("t0", "tau0"), ("t4", "tau4")):
        w("")
        w("/* Cubic BB coefficients of s on %s, times FCC_CUBIC_DENOM. */" % label)
        w("FCC_FUNC FccCubic fcc_cubic_%s(FccSamples s)" % name)
        w("{")
        w("    FccCubic c;")
        nterms = 0
        for a, mi in enumerate(MI3):
            terms = [(int(cubic[name][k][a] * d3), "s.v[%d]" % i)
                     for i, k in enumerate(stencil) if k in cubic[name]]
            nterms += sum(1 for t, _ in terms if t)
            out.extend(wrap("c.b[%d]" % a, lin_comb(terms), mi_str(mi)))
        w("    return c;")
        w("}")
        stats["cubic_" + name] = nterms
    for name, label in (("t0", "tau0"), ("t4", "tau4")):
        w("")
        w("/* Quadratic BB coefficients of d110, d101, d011 on %s, times FCC_DERIV_DENOM. */"
          % label)
        w("FCC_FUNC FccDerivs fcc_derivs_%s(FccSamples s)" % name)
        w("{")
        w("    FccDerivs d;")
        nterms = 0
        for di, tab in enumerate(quad[name]):
            w("    /* d[%d] = d%s */" % (di, DERIV_NAMES[di]))
            for a, mi in enumerate(MI2):
                terms = [(int(tab[k][a] * d2), "s.v[%d]" % i)
                         for i, k in enumerate(stencil) if k in tab]
                nterms += sum(1 for t, _ in terms if t)
                out.extend(wrap("d.d[%d].b[%d]" % (di, a), lin_comb(terms), mi_str(mi)))
        w("    return d;")
        w("}")
        stats["derivs_" + name] = nterms
    w("")
    w("/* Unrolled de Casteljau, l = barycentric (l0,l1,l2,l3) w.r.t. (v0,v1,v2,v3). */")
    out.extend(decasteljau("fcc_decasteljau3", "FccCubic", "c", 3))
    w("")
    out.extend(decasteljau("fcc_decasteljau2", "FccQuadratic", "q", 2))
    w("")
    w("/* One de Casteljau step each: cubic -> quadratic -> linear coefficients at l; with")
    w(" * different points per step they give the blossom (polar form), e.g. a ray segment's")
    w(" * Bernstein coefficients. */")
    out.extend(decasteljau_step("fcc_decasteljau_step3", "FccCubic", "c", 3))
    w("")
    out.extend(decasteljau_step("fcc_decasteljau_step2", "FccQuadratic", "q", 2))
    w("")
    w("#endif /* FCC_SPLINE_TABLES_H */")
    # integer scaling must be exact
    for name in TETS:
        for c in cubic[name].values():
            assert all((v * d3).denominator == 1 for v in c)
        for tab in quad[name]:
            for q in tab.values():
                assert all((v * d2).denominator == 1 for v in q)
    return "\n".join(out) + "\n", stats, d3, d2


def main(argv):
    if len(argv) >= 2 and argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    text, stats, d3, d2 = generate()
    if len(argv) == 3 and argv[1] == "--check":
        try:
            with open(argv[2], "r", newline="") as f:
                old = f.read()
        except OSError as e:
            print("gen_spline_tables: cannot read %s: %s" % (argv[2], e))
            return 1
        if old != text:
            print("gen_spline_tables: %s is out of date; regenerate with "
                  "python3 tools/gen_spline_tables.py %s" % (argv[2], argv[2]))
            return 1
        return 0
    if len(argv) == 1:
        sys.stdout.write(text)
    elif len(argv) == 2 and not argv[1].startswith("-"):
        with open(argv[1], "w", newline="") as f:
            f.write(text)
        sys.stderr.write("wrote %s (D3=%d, D2=%d, terms %s)\n" % (argv[1], d3, d2, stats))
    else:
        sys.stderr.write("usage: gen_spline_tables.py [OUT.h | --check FILE]\n")
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
