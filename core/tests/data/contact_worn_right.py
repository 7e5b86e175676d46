"""Extracts contact_worn_right.csv from CONTACT's output of contact_worn_right.inp (and
contact_nonhertzian_rolling_right.csv from contact_nonhertzian_rolling_right.inp, the same tables).

Usage: python3 contact_worn_right.py contact_worn_right.out > contact_worn_right.csv
       python3 contact_worn_right.py contact_nonhertzian_rolling_right.out > contact_nonhertzian_rolling_right.csv

One row per contact patch: the case, the wheelset's y_ws and the prescribed FZ (from the deck's
order, checked against the output), the solved z_ws, the number of patches, the total forces on
the rail in track coordinates, and per patch its contact reference (YCP(R), DELTCP(TR)), its
creepages and its forces FN, FX, FS — CONTACT's units (mm, rad, N, 1/mm) and signs (creepages
rail minus wheel, forces on the rail).
"""
import os
import re
import sys

# CONTACT's output tables are read as for the reference (the script beside this one).
from mbench_a22_contact_ref_out import table_after


def main(path):
    lines = open(path).read().splitlines()
    starts = [i for i, l in enumerate(lines) if re.match(r"^ Case +\d+", l)] + [len(lines)]
    deck = os.path.basename(path).removesuffix(".out")
    notes = {"contact_worn_right": "contact_worn.md"}.get(deck, "contact_nonhertzian.md")
    print("# CONTACT rev. 2707 (github eve70a/CONTACT, commit d431cdb), module 1, full solution of "
          f"core/tests/data/{deck}.inp; see {notes}")
    print("# units: mm, rad, N, 1/mm (CONTACT's); creepages rail minus wheel, forces on the rail; one row per patch")
    print("case,y_ws,z_ws,fz_tr,fx_tr,fy_tr,patches,patch,ycp_r,deltcp,cksi,ceta,cphi,fn,fx,fs")
    for number, (start, end) in enumerate(zip(starts, starts[1:]), 1):
        block = lines[start:end]
        count = next(int(m.group(1)) for l in block if (m := re.search(r"RIGHT WHEEL, +(\d+) CONTACT PATCH", l)))
        y_ws, z_ws = table_after(block, 0, ["Y_WS", "Z_WS"])
        fx_tr, fy_tr, fz_tr = table_after(block, 0, ["FX(TR)", "FY(TR)", "FZ(TR)"])
        patch_starts = [i for i, l in enumerate(block) if "DATA FOR CONTACT PATCH" in l]
        assert len(patch_starts) == count, (number, count, patch_starts)
        for k, at in enumerate(patch_starts, 1):
            ycp_r, deltcp = table_after(block, at, ["YCP(R)", "DELTCP(TR)"])
            cksi, ceta, cphi = table_after(block, at, ["CKSI", "CETA", "CPHI"])
            fn, fx, fs = table_after(block, at, ["FN", "FX", "FS"])
            print(",".join([str(number), y_ws, z_ws, fz_tr, fx_tr, fy_tr, str(count), str(k),
                            ycp_r, deltcp, cksi, ceta, cphi, fn, fx, fs]))


if __name__ == "__main__":
    main(sys.argv[1])
