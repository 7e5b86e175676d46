#!/usr/bin/env python3
"""Worked cases of Polach's method, computed independently of the Rust library.

Follows the paper's formulas literally, with ERRATA.md's corrections: Kalker's c_jj (29, E1),
C (28), epsilon (7), F (14), the split (3) with the sign convention E4, s_yC (21), C_s (32, E2),
epsilon_s (25), K_M (20) *as printed* with delta (12), F_yS (24). The Kalker coefficients are
interpolated from data/kalker_coefficients.csv as CONTACT's linrol does (linear in g, then the
CSV header's rule in nu) and, for g < 0.1, blended as documented in src/kalker_coefficients.rs.

Run:  python3 core/tests/data/polach_worked_cases.py > core/tests/data/polach_worked_cases.csv
The Rust test core/tests/library/polach_worked_cases.rs reads the CSV and matches it to 1e-12.
"""
import csv
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
TABLE = HERE.parents[2] / "data" / "kalker_coefficients.csv"


def kalker_rows():
    rows = []
    with open(TABLE) as f:
        for line in f:
            if line.startswith("#") or line.startswith("branch"):
                continue
            fields = line.strip().split(",")
            rows.append((fields[0], float(fields[1]), [float(x) for x in fields[2:]]))
    return rows


def at_poisson(values, nu):
    """1/C quadratic (Lagrange) in nu through 0, 0.25, 0.5."""
    c0, c1, c2 = values
    inverse = 8 * (nu - 0.25) * (nu - 0.5) / c0 - 16 * (nu - 0.5) * nu / c1 + 8 * nu * (nu - 0.25) / c2
    return 1 / inverse


def table_coefficients(branch, g, nu):
    """As CONTACT's linrol: linear in g between the rows of one branch at each tabulated nu,
    then the quadratic rule in nu."""
    rows = [r for r in kalker_rows() if r[0] == branch or (r[0] == "a/b" and r[1] == 1.0)]
    rows.sort(key=lambda r: r[1])
    for (_, g0, v0), (_, g1, v1) in zip(rows, rows[1:]):
        if g0 <= g <= g1:
            t = (g - g0) / (g1 - g0)
            at_g = [lo + (hi - lo) * t for lo, hi in zip(v0, v1)]
            return [at_poisson(at_g[3 * k:3 * k + 3], nu) for k in range(3)]
    raise ValueError(g)


def asymptotes(g, a_shorter, nu):
    if a_shorter:
        return [math.pi ** 2 / (4 * (1 - nu)), math.pi ** 2 / 4,
                math.pi * math.sqrt(g) / (3 * (1 - nu)) * (1 + nu * (math.log(16 / g) - 5))]
    lam = math.log(16 / g ** 2)
    c11 = 2 * math.pi / ((lam - 2 * nu) * g) * (1 + (3 - math.log(4)) / (lam - 2 * nu))
    d = (1 - nu) * lam + 2 * nu
    c22 = 2 * math.pi / g * (1 + (1 - nu) * (3 - math.log(4)) / d) / d
    c23 = 2 * math.pi / (3 * g ** 1.5 * ((1 - nu) * lam - 2 + 4 * nu))
    return [c11, c22, c23]


def kalker(a_over_b, nu):
    a_shorter = a_over_b <= 1
    g = a_over_b if a_shorter else 1 / a_over_b
    branch = "a/b" if a_shorter else "b/a"
    if g >= 0.1:
        return table_coefficients(branch, g, nu)
    edge_table = table_coefficients(branch, 0.1, nu)
    edge_asym = asymptotes(0.1, a_shorter, nu)
    asym = asymptotes(g, a_shorter, nu)
    return [asym[k] * (1 + (edge_table[k] / edge_asym[k] - 1) * g / 0.1) for k in range(3)]


def polach(xi, eta, phi, Q, a, b, f, G, nu):
    c11, c22, c23 = kalker(a / b, nu)
    s = math.sqrt(xi ** 2 + eta ** 2)                                      # (4)
    s_yc = eta + phi * a if abs(eta + phi * a) > abs(eta) else eta         # (21)
    s_c = math.sqrt(xi ** 2 + s_yc ** 2)                                   # (22)
    c_jj = math.sqrt((c11 * xi / s) ** 2 + (c22 * eta / s) ** 2) if s > 0 else c22  # (29), E1
    C = 3 * c_jj * G / (8 * a)                                             # (28)
    eps = 2 / 3 * C * math.pi * a ** 2 * b * s_c / (Q * f)                 # (7)
    F = 2 * Q * f / math.pi * (eps / (1 + eps ** 2) + math.atan(eps))      # (14)
    k_s = 1 + 6.3 * (1 - math.exp(-a / b))                                 # (24)
    C_s = 4 * c23 * G * math.sqrt(b) / (math.pi * a ** 1.5)                # (32), E2
    eps_s = 2 * C_s * math.pi * a ** 2 * b * abs(s_yc) / (3 * Q * f * k_s)  # (25)
    delta = (eps_s ** 2 - 1) / (eps_s ** 2 + 1)                           # (12)
    k_m = eps_s * (delta ** 3 / 3 - delta ** 2 / 2 + 1 / 6) - math.sqrt((1 - delta ** 2) ** 3) / 3  # (20)
    f_ys = 9 / 16 * a * Q * f * k_m * k_s * phi / s_c                      # (24)
    return -F * xi / s_c, -F * eta / s_c + f_ys                            # (3), (23), E4


CASES = [
    # xi, eta, phi [1/m], Q [N], a [m], b [m], f, G [Pa], nu
    (2e-3, 0.0, 0.0, 106.7e3, 6.304e-3, 12.61e-3, 0.33, 82e9, 0.28),     # CONTACT case 1 contact, xi only
    (0.0, -6.25e-4, 0.625, 82e3, 8e-3, 4e-3, 0.3, 82e9, 0.28),           # CONTACT case 2: eta with spin
    (1.5e-3, -0.8e-3, 0.4, 80e3, 6.3e-3, 4.1e-3, 0.35, 82e9, 0.25),      # combined, table between rows
    (-4e-4, 1e-3, -1.2, 60e3, 3e-3, 9e-3, 0.4, 80e9, 0.3),               # spin against eta: s_yC = eta
    (3e-4, 2e-4, 0.8, 120e3, 15e-3, 1e-3, 0.3, 82e9, 0.28),              # a/b = 15: asymptote blend
]


def main():
    writer = csv.writer(__import__("sys").stdout, lineterminator="\n")
    writer.writerow(["xi", "eta", "phi", "Q", "a", "b", "f", "G", "nu", "Fx", "Fy"])
    for case in CASES:
        fx, fy = polach(*case)
        writer.writerow([repr(v) for v in case] + [repr(fx), repr(fy)])


if __name__ == "__main__":
    main()
