#!/usr/bin/python3
"""Exact least-squares solutions of the NIST StRD linear regression data *as doubles*.

The certified values are those of the decimal data; a program reads the data as doubles, which
differ from the decimals in the 17th digit, and from then on the best it can do is the exact
least-squares solution of those doubles. This script computes that solution in rational
arithmetic (Python fractions: every double is a fraction exactly) and writes, for each data set
and design, every coefficient, its standard deviation, the residual standard deviation and
R-squared to 30 significant digits, plus each one's log relative error (LRE) against the certified
value: how many digits the double data determine.

Designs:
  exact_powers   polynomial sets (Pontius, Filip, Wampler1-5): columns x^k of the double x,
                 exact (what `stats regress --poly x:DEGREE` fits);
  rounded_powers the same powers each rounded to a double first (a CSV of the powers);
  columns        sets with data columns (Norris, NoInt1, NoInt2, Longley).

Run from the repository root:  /usr/bin/python3 tests/data/strd/lls_exact.py > tests/data/strd/lls_exact.json
(takes about 10 s; the output is deterministic).
"""
import json
import math
import sys
from decimal import Decimal, getcontext
from fractions import Fraction
from pathlib import Path

getcontext().prec = 60
HERE = Path(__file__).resolve().parent

# name: (polynomial degree or None, intercept)
SETS = {
    "Norris": (None, True), "Pontius": (2, True), "NoInt1": (None, False),
    "NoInt2": (None, False), "Filip": (10, True), "Longley": (None, True),
    "Wampler1": (5, True), "Wampler2": (5, True), "Wampler3": (5, True),
    "Wampler4": (5, True), "Wampler5": (5, True),
}


def read(name):
    lines = (HERE / f"{name}.dat").read_text().splitlines()
    start = max(i for i, l in enumerate(lines) if l.startswith("Data:"))
    rows = [l.split() for l in lines[start + 1:] if l.strip()]
    est, sd = [], []
    resid_sd = r2 = None
    for l in lines[:start]:
        t = l.split()
        if len(t) == 3 and t[0] == f"B{len(est) + (0 if SETS[name][1] else 1)}":
            est.append(float(t[1]))
            sd.append(float(t[2]))
        elif len(t) == 3 and t[:2] == ["Standard", "Deviation"]:
            resid_sd = float(t[2])
        elif len(t) == 2 and t[0] == "R-Squared":
            r2 = float(t[1])
    return rows, est, sd, resid_sd, r2


def solve(a, b):
    """Gauss-Jordan elimination in fractions: a x = b, a square and nonsingular."""
    n = len(a)
    m = [row[:] + [bi] for row, bi in zip(a, b)]
    for c in range(n):
        p = next(r for r in range(c, n) if m[r][c] != 0)
        m[c], m[p] = m[p], m[c]
        inv = 1 / m[c][c]
        m[c] = [v * inv for v in m[c]]
        for r in range(n):
            if r != c and m[r][c] != 0:
                f = m[r][c]
                m[r] = [v - f * w for v, w in zip(m[r], m[c])]
    return [m[r][n] for r in range(n)]


def sqrt_fraction(q):
    return Decimal(q.numerator).sqrt() / Decimal(q.denominator).sqrt() if q else Decimal(0)


def decimal_of(q):
    return Decimal(q.numerator) / Decimal(q.denominator)


def lre(value, certified):
    value = Decimal(value)
    certified = Decimal(repr(certified))
    if value == certified:
        return 99.0
    if certified == 0:
        return float(-abs(value).log10())
    return float(-(abs(value - certified) / abs(certified)).log10())


def exact_fit(x_cols, y, intercept):
    n = len(y)
    cols = ([[Fraction(1)] * n] if intercept else []) + x_cols
    p = len(cols)
    xtx = [[sum(a * b for a, b in zip(cols[i], cols[j])) for j in range(p)] for i in range(p)]
    xty = [sum(a * b for a, b in zip(cols[i], y)) for i in range(p)]
    beta = solve(xtx, xty)
    resid = [y[i] - sum(beta[j] * cols[j][i] for j in range(p)) for i in range(n)]
    rss = sum(r * r for r in resid)
    df = n - p
    s2 = rss / df
    diag = []
    for j in range(p):
        e = [Fraction(int(k == j)) for k in range(p)]
        diag.append(solve(xtx, e)[j])
    if intercept:
        ybar = sum(y) / n
        tss = sum((v - ybar) ** 2 for v in y)
    else:
        tss = sum(v * v for v in y)
    return {
        "coefficients": [decimal_of(b) for b in beta],
        "sd": [sqrt_fraction(s2 * d) for d in diag],
        "residual_sd": sqrt_fraction(s2),
        "r_squared": decimal_of(1 - rss / tss),
    }


def fmt(d):
    return format(d, ".30g") if d else "0"


def main():
    out = {"generator": "tests/data/strd/lls_exact.py", "sets": {}}
    for name, (degree, intercept) in SETS.items():
        rows, est, sd, resid_sd, r2 = read(name)
        y = [Fraction(float(r[0])) for r in rows]
        designs = {}
        if degree is None:
            designs["columns"] = [[Fraction(float(r[k])) for r in rows]
                                  for k in range(1, len(rows[0]))]
        else:
            x = [Fraction(float(r[1])) for r in rows]
            designs["exact_powers"] = [[v ** k for v in x] for k in range(1, degree + 1)]
            designs["rounded_powers"] = [[Fraction(float(v ** k)) for v in x]
                                         for k in range(1, degree + 1)]
        entry = {}
        for design, cols in designs.items():
            fit = exact_fit(cols, y, intercept)
            lres = [lre(a, c) for a, c in zip(fit["coefficients"], est)]
            lres += [lre(a, c) for a, c in zip(fit["sd"], sd)]
            lres += [lre(fit["residual_sd"], resid_sd), lre(fit["r_squared"], r2)]
            entry[design] = {
                "coefficients": [fmt(v) for v in fit["coefficients"]],
                "sd": [fmt(v) for v in fit["sd"]],
                "residual_sd": fmt(fit["residual_sd"]),
                "r_squared": fmt(fit["r_squared"]),
                "min_lre_vs_certified": round(min(lres), 2),
            }
            print(f"{name} {design}: min LRE of the exact solution vs certified "
                  f"{min(lres):.2f}", file=sys.stderr)
        out["sets"][name] = entry
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
