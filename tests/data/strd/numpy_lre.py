#!/usr/bin/python3
"""LREs of NumPy's least squares on the NIST StRD linear regression sets (docs/regression.md).

For each set: the smallest log relative error (LRE, correct significant digits) over the
coefficients, and over the residual SD and R-squared, of
  lstsq    numpy.linalg.lstsq on the design as doubles (powers rounded to doubles), default rcond;
  polyfit  numpy.polyfit(x, y, degree) for the polynomial sets (it scales the columns; rcond
           len(x) * eps).
Run from the repository root: /usr/bin/python3 tests/data/strd/numpy_lre.py
"""
import math
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SETS = {"Norris": (None, True), "Pontius": (2, True), "NoInt1": (None, False),
        "NoInt2": (None, False), "Filip": (10, True), "Longley": (None, True),
        "Wampler1": (5, True), "Wampler2": (5, True), "Wampler3": (5, True),
        "Wampler4": (5, True), "Wampler5": (5, True)}


def read(name, intercept):
    lines = (HERE / f"{name}.dat").read_text().splitlines()
    start = max(i for i, l in enumerate(lines) if l.startswith("Data:"))
    data = np.array([[float(v) for v in l.split()] for l in lines[start + 1:] if l.strip()])
    est = []
    resid_sd = r2 = None
    for l in lines[:start]:
        t = l.split()
        if len(t) == 3 and t[0] == f"B{len(est) + (0 if intercept else 1)}":
            est.append(float(t[1]))
        elif len(t) == 3 and t[:2] == ["Standard", "Deviation"]:
            resid_sd = float(t[2])
        elif len(t) == 2 and t[0] == "R-Squared":
            r2 = float(t[1])
    return data, np.array(est), resid_sd, r2


def lre(x, c):
    if x == c:
        return 99.0
    if c == 0:
        return -math.log10(abs(x))
    return max(0.0, -math.log10(abs(x - c) / abs(c)))


def summary(b, y, design, est, resid_sd, r2, intercept):
    r = y - design @ b
    df = len(y) - design.shape[1]
    s = math.sqrt(r @ r / df)
    tss = ((y - y.mean()) ** 2).sum() if intercept else (y ** 2).sum()
    rsq = 1 - (r @ r) / tss
    return min(lre(v, c) for v, c in zip(b, est)), min(lre(s, resid_sd), lre(rsq, r2))


def main():
    print(f"numpy {np.__version__}")
    print("set       lstsq b  lstsq s,R2  polyfit b  polyfit s,R2")
    for name, (degree, intercept) in SETS.items():
        data, est, resid_sd, r2 = read(name, intercept)
        y = data[:, 0]
        if degree is None:
            x_cols = data[:, 1:]
        else:
            x_cols = np.column_stack([data[:, 1] ** k for k in range(1, degree + 1)])
        design = np.column_stack([np.ones(len(y)), x_cols]) if intercept else x_cols
        b = np.linalg.lstsq(design, y, rcond=None)[0]
        ls = summary(b, y, design, est, resid_sd, r2, intercept)
        pf = ("", "")
        if degree is not None:
            bp = np.polyfit(data[:, 1], y, degree)[::-1]
            pf = summary(bp, y, design, est, resid_sd, r2, intercept)
            pf = (f"{pf[0]:.1f}", f"{pf[1]:.1f}")
        print(f"{name:9} {ls[0]:7.1f} {ls[1]:11.1f} {pf[0]:>10} {pf[1]:>13}")


if __name__ == "__main__":
    main()
