"""The figures and tables of docs/coupling-stability.md from the stability map's CSV
(docs/coupling-stability/map.csv, written by `cargo run --release -p lab --bin
coupling_stability_map`) and the creep time constants' estimate of the largest stable step.

    .venv/bin/python scripts/coupling_stability_plot.py

writes docs/coupling-stability/map.png and largest_stable_step.png and prints the doc's tables.

The estimate (derived in docs/coupling-stability.md, "The estimate"): the wheel's spin about its
axle is the stiffest mode the master sees, τ_Ω = I_s V / Σ f11 r² (the two wheels' patches,
f11 = G a b C11, r the rolling radius), against τ_y = m V / Σ f22 and τ_ψ = I V / d_ψ for the
lateral and yaw creep damping; a fixed-step master bounds the step by the smallest:

    Gauss–Seidel:               h < 2 τ_Ω                       (z = 1 − h/τ)
    Jacobi (one step late):     h < τ_Ω                         (z² − z + h/τ = 0)
    Gauss–Seidel, relaxation:   h/τ_Ω < 2 coth(V h / (2 L_x))   (L_x the longitudinal relaxation length)
"""

import csv
import json
import math
import pathlib
import tomllib
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "coupling-stability"
MASTERS = ["jacobi", "gauss_seidel", "linearly_implicit"]
RUNGS = ["kalker_linear", "polach", "exact_table"]
# A bounded run is clean when its peak spin creepage stays within this factor of the reference
# run's: beyond it the spin mode rings or limit-cycles on the saturating creep law.
CLEAN_FACTOR = 1.25
# The start off centre of the map's runs [m] and the reference step [s] (the binary's).
INITIAL_DISPLACEMENT = 3e-3
REFERENCE_STEP = 1e-5


def read_map(path=OUT / "map.csv"):
    """{(rung, relaxation, master): {(speed, step): row}} and {(rung, relaxation, speed): reference row}."""
    runs, references = defaultdict(dict), {}
    with open(path) as file:
        for row in csv.DictReader(file):
            speed, step = float(row["speed_m_per_s"]), float(row["step_s"])
            row["bounded"] = row["bounded"] == "true"
            row["distance"] = float(row["distance"]) if row["distance"] else math.nan
            row["peak_spin_creepage"] = float(row["peak_spin_creepage"])
            if step == REFERENCE_STEP:
                references[(row["rung"], row["relaxation"], speed)] = row
            else:
                runs[(row["rung"], row["relaxation"], row["master"])][(speed, step)] = row
    return runs, references


def clean(row, reference):
    return row["bounded"] and row["peak_spin_creepage"] <= CLEAN_FACTOR * reference["peak_spin_creepage"]


def largest(cells, speed, steps, accept):
    """The largest step h such that every step ≤ h is accepted (0 if the smallest is not)."""
    best = 0.0
    for step in steps:
        if not accept(cells[(speed, step)]):
            break
        best = step
    return best


def time_constants():
    """Per second of speed [s/(m/s)]: τ_Ω/V, τ_y/V, τ_ψ/V at y = 0 and at |y| = 3 mm, and the
    patches' longitudinal relaxation length L_x = √(ab) C11 (2 − ν)/4 at y = 0 [m] (the contact
    unit's default, src/scene/relaxation.rs)."""
    with open(ROOT / "data" / "wheelset" / "passenger_coach.toml", "rb") as file:
        wheelset = {k: v["value"] for k, v in tomllib.load(file)["wheelset"].items()}
    with open(ROOT / "data" / "wheelset" / "contact_data.json") as file:
        data = json.load(file)
    shear, poisson = data["shear_modulus"], data["poisson_ratio"]
    result = {}
    for sample in data["samples"]:
        y = sample["lateral"]
        if not any(abs(y - at) < 1e-9 for at in (0.0, INITIAL_DISPLACEMENT)):
            continue
        patches = [p for side in ("left", "right") for p in sample[side]]
        area = [p["semi_axis_a"] * p["semi_axis_b"] for p in patches]
        f11 = [shear * ab * p["c11"] for ab, p in zip(area, patches)]
        f22 = sum(shear * ab * p["c22"] for ab, p in zip(area, patches))
        spin = sum(f * p["rolling_radius"] ** 2 for f, p in zip(f11, patches))
        f11_y = sum(f * p["track_lateral"] for f, p in zip(f11, patches))
        yaw = sum(f * p["track_lateral"] ** 2 for f, p in zip(f11, patches)) - f11_y ** 2 / sum(f11)
        result[y] = {
            "spin": wheelset["spin_inertia"] / spin,
            "lateral": wheelset["mass"] / f22,
            "yaw": wheelset["yaw_inertia"] / yaw,
            "relaxation_length": float(np.mean([math.sqrt(ab) * p["c11"] * (2 - poisson) / 4
                                                for ab, p in zip(area, patches) if p["normal_force"] > 1e3])),
        }
    return result[0.0], result[INITIAL_DISPLACEMENT]


def estimate(master, relaxation, speed, spin_per_speed, relaxation_length):
    """The largest stable step [s] of the module doc's estimate (None: unconditionally stable)."""
    tau = spin_per_speed * speed
    if master == "linearly_implicit":
        return None
    if master == "jacobi":
        return tau
    if relaxation == "off":
        return 2 * tau
    # h/τ = 2 coth(V h/(2 L)), by bisection on h (the left side rises from 0, the right falls to 2).
    low, high = 0.0, 1.0
    for _ in range(200):
        h = 0.5 * (low + high)
        if h / tau < 2 / math.tanh(speed * h / (2 * relaxation_length)):
            low = h
        else:
            high = h
    return low


def plot_map(runs, references, speeds, steps):
    fig, axes = plt.subplots(len(MASTERS), 2 * len(RUNGS), figsize=(12, 6.2), sharex=True, sharey=True)
    norm = matplotlib.colors.LogNorm(1e-5, 1)
    for j, (rung, relaxation) in enumerate((r, o) for r in RUNGS for o in ("off", "on")):
        for i, master in enumerate(MASTERS):
            ax, cells = axes[i][j], runs[(rung, relaxation, master)]
            grid = np.full((len(speeds), len(steps)), np.nan)
            for a, speed in enumerate(speeds):
                for b, step in enumerate(steps):
                    row = cells[(speed, step)]
                    if row["bounded"]:
                        grid[a, b] = max(row["distance"], 1e-5)
                        if not clean(row, references[(rung, relaxation, speed)]):
                            ax.plot(b, a, "o", mfc="none", mec="black", ms=7)
                    else:
                        ax.plot(b, a, "x", color="black", ms=6)
            image = ax.imshow(grid, origin="lower", cmap="viridis_r", norm=norm, aspect="auto")
            if i == 0:
                ax.set_title(f"{rung}\nrelaxation {relaxation}", fontsize=8)
            if j == 0:
                ax.set_ylabel(f"{master}\nV [m/s]", fontsize=8)
            if i == len(MASTERS) - 1:
                ax.set_xlabel("h [ms]", fontsize=8)
    axes[0][0].set_yticks(range(len(speeds)), [f"{v:g}" for v in speeds], fontsize=7)
    axes[0][0].set_xticks(range(len(steps)), [f"{h * 1e3:g}" for h in steps])
    for ax in axes[-1]:
        ax.tick_params(axis="x", labelrotation=90, labelsize=6)
    bar = fig.colorbar(image, ax=axes, shrink=0.8, pad=0.01)
    bar.set_label("distance from the 10 µs run: max |y − y_ref| / y0", fontsize=8)
    fig.suptitle("Coupled wheelset + 2 contact units, 0.5 s from y0 = 3 mm: × unbounded, "
                 f"○ bounded but the spin creepage peaks > {CLEAN_FACTOR} × the reference's", fontsize=9)
    fig.savefig(OUT / "map.png", dpi=70)


def plot_largest(runs, references, speeds, steps, centred, off_centre):
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    colours = {"jacobi": "tab:red", "gauss_seidel": "tab:blue", "linearly_implicit": "tab:green"}
    markers = {"kalker_linear": "o", "polach": "s", "exact_table": "^"}
    fine = np.geomspace(speeds[0], speeds[-1], 100)
    for ax, relaxation in zip(axes, ("off", "on")):
        for master in MASTERS:
            for k, rung in enumerate(RUNGS):
                cells = runs[(rung, relaxation, master)]
                found = [largest(cells, v, steps, lambda row, v=v: clean(row, references[(rung, relaxation, v)]))
                         for v in speeds]
                # Below the grid's smallest step: drawn at half of it; the grid's largest: an arrow up.
                shown = [h if h > 0 else steps[0] / 2 for h in found]
                ax.plot(np.array(speeds) * (1 + 0.06 * (k - 1)), np.array(shown) * 1e3, markers[rung],
                        color=colours[master], mfc="none" if rung != "kalker_linear" else colours[master],
                        label=f"{master}, {rung}", ms=5, ls=":", lw=0.8)
            bounds = [[estimate(master, relaxation, v, tc["spin"], centred["relaxation_length"]) for v in fine]
                      for tc in (centred, off_centre)]
            if bounds[0][0] is not None:
                ax.fill_between(fine, np.array(bounds[0]) * 1e3, np.array(bounds[1]) * 1e3, color=colours[master],
                                alpha=0.2, lw=0)
        ax.axhline(steps[0] * 1e3, color="grey", lw=0.5)
        ax.axhline(steps[-1] * 1e3, color="grey", lw=0.5)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("V [m/s]")
        ax.set_title(f"creep_relaxation = {relaxation}", fontsize=9)
        ax.grid(True, which="both", lw=0.3)
    axes[0].set_ylabel("largest clean step [ms]")
    axes[1].legend(fontsize=6, ncol=1, loc="lower right")
    fig.suptitle("Largest step with every smaller step clean (points; half the grid's smallest: none) against the "
                 "estimate from τ_Ω = I_s V/Σ f11 r² (bands: y = 0 … 3 mm)", fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "largest_stable_step.png", dpi=70)


def main():
    runs, references = read_map()
    speeds = sorted({v for cells in runs.values() for v, _ in cells})
    steps = sorted({h for cells in runs.values() for _, h in cells})
    centred, off_centre = time_constants()
    print("time constants per speed [µs/(m/s)] at y = 0 | 3 mm: spin "
          f"{centred['spin'] * 1e6:.2f} | {off_centre['spin'] * 1e6:.2f}, lateral {centred['lateral'] * 1e6:.1f} | "
          f"{off_centre['lateral'] * 1e6:.1f}, yaw {centred['yaw'] * 1e6:.1f} | {off_centre['yaw'] * 1e6:.1f}; "
          f"L_x = {centred['relaxation_length'] * 1e3:.2f} mm")
    print("\n| rung | relaxation | master | " + " | ".join(f"{v:g} m/s" for v in speeds) + " |")
    print("|---" * (3 + len(speeds)) + "|")
    for rung in RUNGS:
        for relaxation in ("off", "on"):
            for master in MASTERS:
                cells = runs[(rung, relaxation, master)]
                row = []
                for v in speeds:
                    reference = references[(rung, relaxation, v)]
                    found = largest(cells, v, steps, lambda r: clean(r, reference))
                    bounded = largest(cells, v, steps, lambda r: r["bounded"])
                    text = f"{found * 1e3:g}" if found else "–"
                    row.append(text if bounded == found else f"{text} ({bounded * 1e3:g})")
                print(f"| {rung} | {relaxation} | {master} | " + " | ".join(row) + " |")
    print("\nestimate [ms]:")
    for master in ("jacobi", "gauss_seidel"):
        for relaxation in ("off", "on"):
            values = [[estimate(master, relaxation, v, tc["spin"], centred["relaxation_length"])
                       for tc in (centred, off_centre)] for v in speeds]
            print(f"| {master} | {relaxation} | " + " | ".join(f"{a * 1e3:.3g}–{b * 1e3:.3g}" for a, b in values) + " |")
    print("\ndistance at h = 10 ms, linearly implicit (rung, relaxation: per speed):")
    for rung in RUNGS:
        for relaxation in ("off", "on"):
            cells = runs[(rung, relaxation, "linearly_implicit")]
            print(f"| {rung} | {relaxation} | " + " | ".join(f"{cells[(v, steps[-1])]['distance']:.1e}" for v in speeds) + " |")
    plot_map(runs, references, speeds, steps)
    plot_largest(runs, references, speeds, steps, centred, off_centre)


if __name__ == "__main__":
    main()
