"""Makes core/tests/data/conicity_contact.csv: CONTACT's rolling radius of each wheel of the Manchester
benchmark wheelset (S1002 on UIC60 1:40) at lateral displacements y_ws = -10 ... 10 mm (every 0.1 mm), zero roll
and yaw, under a light vertical load (the point where the wheel first touches, approximately).

Usage:
  python3 conicity_contact.py decks RUN_DIR      # writes RUN_DIR/conicity_{right,left}.inp
  (copy MBench_S1002_v3.prw, MBench_UIC60_v3.prr from CONTACT's examples/ into RUN_DIR, then in it
   OMP_NUM_THREADS=1 MALLOC_PERTURB_=255 contact_linux64 2 conicity_right  (and conicity_left))
  python3 conicity_contact.py csv RUN_DIR > conicity_contact.csv
  python3 conicity_contact.py conicity conicity_contact.csv > conicity_contact_tan_gamma.csv

CONTACT: github eve70a/CONTACT rev. 2707, commit d431cdbd125084c79bd59df83b4ac4c63c570ac9, built by
../shared/tools/contact/build.sh (gfortran, reference LAPACK). Decks: those of CONTACT's
examples/mbench_a22_{right,left}.inp, case 1 (gauge 1435 mm at 14 mm below the rail top, no cant,
flange backs 1360 mm apart at -70 mm, r0 = 460 mm, G = 82 GPa, nu = 0.28), changed to: frictionless
normal problem (T = 0), vertical force FZ = 500 N, grid DX = DS = 0.1 mm, roll = yaw = 0, y_ws as
listed.
"""
import re
import sys

LOAD_N = 500.0
Y_MM = [round(0.1 * k, 1) for k in range(-100, 101)]

CASE = """
% y_ws = {y:.1f} mm, zero roll and yaw, FZ = {fz:.0f} N, frictionless
  1 MODULE
 {c}200100    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS
 0022033    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL
 0000321    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN
    999     100    30    1     1e-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2
  0.100   0.100   1.000   90d   8.0   4.0       DX, DS, DQREL, A_SEP, D_SEP, D_COMB
   14.0     0    1435.0   0.000                GAUGHT, GAUGSQ, GAUGWD, CANT
  'MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
  1360.0  -70.0   460.0                         FBDIST, FBPOS, NOMRAD
  'MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH
  0.0  {y:.4f}  {fz:.1f}  0.0  0.0  0.0         S, Y, FZ, ROLL, YAW, PITCH
 2000. 0.0    0.0   0.0        0.0  -4.34811810 VS,VY,VZ, VROLL,VYAW,VPITCH
"""


def decks(run_dir):
    for side, c in (("right", 1), ("left", 0)):
        with open(f"{run_dir}/conicity_{side}.inp", "w") as f:
            f.write("% Rolling radii for the equivalent conicity (wheel_rail_contact core/tests/data/conicity_contact.py)\n")
            for y in Y_MM:
                f.write(CASE.format(y=y, fz=LOAD_N, c=c))
            f.write("\n  0 MODULE\n")


def value(lines, start, stop, name):
    """The value under `name` in the first header line holding it within [start, stop)."""
    for i in range(start, stop):
        header = lines[i].split()
        if name in header:
            return lines[i + 1].split()[header.index(name)]
    raise ValueError(f"no {name} in lines {start}-{stop}")


def patches(text):
    """(case, patch, z_ws, fn, ycp_r, ycp_w, zcp_w, deltcp_tr) per patch per case."""
    lines = text.splitlines()
    starts = [i for i, l in enumerate(lines) if re.match(r"^ Case +\d+", l)] + [len(lines)]
    for case, (a, b) in enumerate(zip(starts, starts[1:]), 1):
        z_ws = value(lines, a, b, "Z_WS")
        heads = [i for i in range(a, b) if "CONTACT REFERENCE LOCATION" in lines[i]] + [b]
        for patch, (p, q) in enumerate(zip(heads, heads[1:]), 1):
            yield [case, patch, z_ws, value(lines, p, q, "FN"), value(lines, p, q, "YCP(R)"),
                   value(lines, p, q, "YCP(W)"), value(lines, p, q, "ZCP(W)"), value(lines, p, q, "DELTCP(TR)")]


def csv(run_dir):
    print("# CONTACT rev. 2707 (github eve70a/CONTACT, commit d431cdbd125084c79bd59df83b4ac4c63c570ac9, Apache-2.0), "
          "module 1, run by core/tests/data/conicity_contact.py (decks and command in its docstring)")
    print(f"# S1002 on UIC60 1:40 (MBench_*_v3), Manchester A-2.2 track and wheelset, roll = yaw = 0, FZ = {LOAD_N:.0f} N "
          "per wheel, frictionless (T = 0), DX = DS = 0.1 mm; CONTACT's units (mm, N, rad); one row per contact patch")
    print("# rolling radius = 460 mm + zcp_w (the wheel profile's z, downward, at the patch's contact reference)")
    print("wheel,case,y_ws,patch,z_ws,fn,ycp_r,ycp_w,zcp_w,deltcp_tr")
    for side in ("right", "left"):
        with open(f"{run_dir}/conicity_{side}.out") as f:
            for row in patches(f.read()):
                print(",".join([side, str(row[0]), f"{Y_MM[row[0] - 1]:.1f}"] + [str(v) for v in row[1:]]))


def contact_delta_r(path):
    """CONTACT's (y, delta r = r_right - r_left) [m], from the heaviest patch of each wheel."""
    best = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("wheel"):
                continue
            side, _, y, _, _, fn, _, _, zcp_w, _ = line.strip().split(",")
            key = (side, float(y))
            if key not in best or float(fn) > best[key][0]:
                best[key] = (float(fn), float(zcp_w))
    ys = sorted({y for _, y in best})
    return [y * 1e-3 for y in ys], [(best[("right", y)][1] - best[("left", y)][1]) * 1e-3 for y in ys]


def wavelength(ys, dr, amplitude, dx, e=0.75, r0=0.46):
    """Klingel's kinematic motion y'' = -dr(y) / (2 e r0), from y = A, y' = 0, by classical
    Runge-Kutta in x with step dx [m]: the wavelength between the first and third zero crossings."""
    def f(y):
        # linear interpolation in the samples
        lo, hi = 0, len(ys) - 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if ys[mid] <= y:
                lo = mid
            else:
                hi = mid
        t = (y - ys[lo]) / (ys[hi] - ys[lo])
        return -(dr[lo] + t * (dr[hi] - dr[lo])) / (2.0 * e * r0)

    x, y, v, crossings = 0.0, amplitude, 0.0, []
    while len(crossings) < 3:
        k1y, k1v = v, f(y)
        k2y, k2v = v + 0.5 * dx * k1v, f(y + 0.5 * dx * k1y)
        k3y, k3v = v + 0.5 * dx * k2v, f(y + 0.5 * dx * k2y)
        k4y, k4v = v + dx * k3v, f(y + dx * k3y)
        y1 = y + dx / 6.0 * (k1y + 2 * k2y + 2 * k3y + k4y)
        v = v + dx / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v)
        if (y > 0) != (y1 > 0):
            crossings.append(x + dx * y / (y - y1))
        x, y = x + dx, y1
    return crossings[2] - crossings[0]


def conicity(path):
    import math
    ys, dr = contact_delta_r(path)
    print("# Equivalent conicity of CONTACT's delta r (conicity_contact.csv, heaviest patch per wheel, linear between "
          "its 0.1 mm samples) by EN 15302's principle: Klingel's wavelength lambda of the kinematic motion "
          "y'' = -dr(y)/(2 e r0) (e = 0.75 m, r0 = 0.46 m; they cancel) integrated by classical Runge-Kutta with "
          "dx = 0.1 mm (between the 1st and 3rd zero crossings), tan gamma_e = e r0 (2 pi / lambda)^2; "
          "made by conicity_contact.py conicity; tan_gamma_e_dx_1mm: the same with dx = 1 mm (the step's effect)")
    print("amplitude_mm,tan_gamma_e,tan_gamma_e_dx_1mm,wavelength_m")
    for a_mm in (0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5, 5.5, 6, 7, 8, 9):
        lam = wavelength(ys, dr, a_mm * 1e-3, 1e-4)
        coarse = wavelength(ys, dr, a_mm * 1e-3, 1e-3)
        k = lambda l: 0.75 * 0.46 * (2 * math.pi / l) ** 2
        print(f"{a_mm},{k(lam):.6f},{k(coarse):.6f},{lam:.5f}")


if __name__ == "__main__":
    {"decks": decks, "csv": csv, "conicity": conicity}[sys.argv[1]](sys.argv[2])
