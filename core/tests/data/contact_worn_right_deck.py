"""Writes contact_worn_right.inp (stdout): the worn-profile CONTACT deck of core/tests/data/contact_worn.md."""
import sys
Y = [0.0, 8.0, 9.0, 10.0, 11.0, 12.0, 12.5, 13.0, 13.5, 14.0]
LOADS = [20000.0, 80000.0]
YAW = 0.002
V = 2000.0
R0 = 419.1
VPITCH = -V / R0
out = []
w = out.append
w("% Worn profiles: the averaged worn wheel avg_wheel.whl on the averaged worn high rail avg_HR.BAN")
w("% (both measured, MiniProf, from CONTACT's testbank/profiles), right wheel, smoothed with CONTACT's")
w("% weighted smoothing spline (ISMOOTH = 1) at lambda = 5 mm; yaw 2 mrad, rolling at V = 2 m/s on the")
w("% nominal radius 419.1 mm; friction 0.3. Written for wheel-rail-contact's worn-profile tests")
w("% (core/tests/data/contact_worn.md).")
case = 0
for y in Y:
    for fz in LOADS:
        case += 1
        w("")
        w(f"% {case}: y_ws {y} mm, Fz {fz:.0f} N")
        w("")
        w("  1 MODULE")
        w(" 1203100    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS")
        w(" 0022033    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL")
        w(" 0000321    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN")
        w("    999     100    30    1     1e-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS")
        w("  0.300   0.300                                 FSTAT, FKIN")
        w("  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2")
        w("  0.200   0.200   1.000   90d   8.0   4.0      DX, DS, DQREL, A_SEP, D_SEP, D_COMB")
        w(" 15.875     0    1435.1   0.000                GAUGHT, GAUGSQ, GAUGWD, CANT")
        w("  'avg_HR.BAN'      1  1.0   5.0  0  1        RFNAME, MIRRORY, SCALE, SMOOTH, MIRRORZ, PRFOPT")
        w("   1  150d   30d   6d   2.0                   ISMOOTH, ZIGTRS, KNKHGH, KNKLOW, KNKWID")
        w("     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL")
        w(f"  1352.2   0.0  {R0}                         FBDIST, FBPOS, NOMRAD")
        w("  'avg_wheel.whl'   0  1.0   5.0  0  1        WFNAME, MIRRORY, SCALE, SMOOTH, MIRRORZ, PRFOPT")
        w("   1  150d   30d   6d   2.0                   ISMOOTH, ZIGTRS, KNKHGH, KNKLOW, KNKWID")
        w(f"  0.0  {y}  {fz}  0.0  {YAW}  0.0      S, Y, FZ, ROLL, YAW, PITCH")
        w(f" {V} 0.0    0.0   0.0        0.0  {VPITCH:.8f} VS,VY,VZ, VROLL,VYAW,VPITCH")
w("")
w("  0 MODULE")
print("\n".join(out))
