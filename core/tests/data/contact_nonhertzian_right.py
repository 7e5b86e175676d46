"""Makes core/tests/data/contact_nonhertzian_right.csv from CONTACT's output of
contact_nonhertzian_right.inp (see contact_nonhertzian.md).

Usage: python3 contact_nonhertzian_right.py contact_nonhertzian_right.out > contact_nonhertzian_right.csv

Per contact patch: the case's y_ws, FZ, Z_WS and patch count; the contact reference YCP(R),
DELTCP(TR); the wheel's point YCP(W), ZCP(W); FN; and the pressure centroid from the detailed
output (OUTPUT digit 5: PN of every element in contact, rows at local s = "Y"): s_pc = sum(PN s) /
sum(PN) in the patch's plane, and on the rail ypc_r = YCP(R) + s_pc cos DELTCP (the plane's s axis
runs along +y turned by the contact angle); its peak pressure PMAX. CONTACT's units (mm, rad, N,
N/mm² = MPa).
"""
import math, re, sys
t = open(sys.argv[1]).read()
cases = re.split(r'\n Case +(\d+)\n', t)
print("# CONTACT rev. 2707 (github eve70a/CONTACT, commit d431cdb), module 1, full (non-Hertzian) frictionless normal solution of core/tests/data/contact_nonhertzian_right.inp; see contact_nonhertzian.md")
print("# units: mm, rad, N (CONTACT's); one row per contact patch; ycp_r, deltcp: CONTACT's contact reference (its interpenetration centre of gravity); ycp_w, zcp_w the wheel's point there; s_pc, ypc_r its pressure centroid (in the patch's plane; on the rail); pmax its peak pressure [MPa]")
print("case,y_ws,fz,z_ws,patches,patch,ycp_r,deltcp,ycp_w,zcp_w,fn,s_pc,ypc_r,pmax")
for i in range(1, len(cases), 2):
    case, body = cases[i], cases[i + 1]
    n = re.search(r'RIGHT WHEEL, +(\d+) CONTACT PATCH', body).group(1)
    ws = re.search(r'S_WS.*\n\s+(\S+)\s+(\S+)\s+(\S+)', body)
    fz = re.search(r'FX\(TR\)\s+FY\(TR\)\s+FZ\(TR\).*\n\s+(\S+)\s+(\S+)\s+(\S+)', body).group(3)
    patches = re.split(r'----- DATA FOR CONTACT PATCH +\d+ -----', body)[1:]
    for k, p in enumerate(patches, 1):
        ref = re.search(r'DELTCP\(TR\)\s+YCP\(R\)\s+ZCP\(R\)\n(.*)', p).group(1).split()
        w = re.search(r'YCP\(W\)\s+ZCP\(W\)\n(.*)', p).group(1).split()
        fn = re.search(r'\n\s+FN\s+FX.*\n(.*)', p).group(1).split()[0]
        pmax = re.search(r'APPROACH\s+PMAX\s*\n(.*)', p).group(1).split()[4]
        total = moment = 0.0
        for blk in re.finditer(r'\n Y = +(\S+) +ROW.*\n\n((?:.*\n)+?)\n', p):
            s = float(blk.group(1))
            for line in blk.group(2).strip().splitlines():
                f = line.split()
                if len(f) >= 3:
                    total += float(f[2]); moment += float(f[2]) * s
        s_pc = moment / total
        ypc = float(ref[4]) + s_pc * math.cos(float(ref[3]))
        print(','.join([case, ws.group(2), str(float(fz)), ws.group(3), n, str(k), ref[4], ref[3], w[1], w[2], fn, f"{s_pc:.4f}", f"{ypc:.4f}", pmax]))
