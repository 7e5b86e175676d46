"""Extracts core/tests/data/mbench_a22_contact_ref_out.csv from CONTACT's published outputs.

Usage: python3 mbench_a22_contact_ref_out.py CONTACT_CHECKOUT > mbench_a22_contact_ref_out.csv

CONTACT_CHECKOUT is a checkout of github eve70a/CONTACT (rev. 2707, commit
d431cdbd125084c79bd59df83b4ac4c63c570ac9, 2025-07-23, Apache-2.0); the script reads its
examples/mbench_a22_{right,left}.ref_out (Manchester benchmark case A-2.2, one patch per case)
and writes, per wheel and case, the values of the blocks named in the header, in CONTACT's units
(mm, rad, N, mm/s, 1/mm for CPHI) and sign conventions (creepages rail minus wheel, forces on the
rail).
"""
import re
import sys

COLUMNS = [
    ("WHEEL-SET POSITION AND VELOCITY", ["Y_WS", "Z_WS", "ROLL_WS", "YAW_WS"]),
    ("TOTAL FORCES ON RAIL", ["FX(TR)", "FY(TR)", "FZ(TR)"]),
    ("CONTACT REFERENCE LOCATION", ["XCP(TR)", "YCP(TR)", "ZCP(TR)", "DELTCP(TR)", "YCP(R)", "ZCP(R)"]),
    ("XCP(W)", ["XCP(W)", "YCP(W)", "ZCP(W)"]),
    ("KINEMATIC CONSTANTS", ["VELOC", "CKSI", "CETA", "CPHI"]),
    ("TOTAL FORCES, TORSIONAL MOMENT", ["FN", "FX", "FS"]),
]


def table_after(lines, start, names):
    """The values under the header line that follows `start` and holds every name."""
    for i in range(start, len(lines)):
        header = lines[i].split()
        if all(n in header for n in names):
            values = lines[i + 1].split()
            return [values[header.index(n)] for n in names]
    raise ValueError(f"no table with {names} after line {start}")


def cases(text):
    lines = text.splitlines()
    starts = [i for i, l in enumerate(lines) if re.match(r"^ Case +\d+", l)]
    for number, start in enumerate(starts, 1):
        row = [str(number)]
        for block, names in COLUMNS:
            at = next(i for i in range(start, len(lines)) if block in lines[i])
            # the block's own title line holds no values: search from it
            row += table_after(lines, at if block == names[0] else at + 1, names)
        yield row


def main(checkout):
    print("# CONTACT rev. 2707 (github eve70a/CONTACT, commit d431cdbd125084c79bd59df83b4ac4c63c570ac9, "
          "2025-07-23, Apache-2.0), examples/mbench_a22_{right,left}.ref_out, extracted by "
          "mbench_a22_contact_ref_out.py")
    print("# Manchester benchmark case A-2.2, one patch per case; CONTACT's units (mm, rad, N, mm/s, rad/mm) "
          "and signs (creepages rail minus wheel; forces on the rail, FX FS in the patch's tangent plane)")
    names = [n.lower().replace("(", "_").replace(")", "") for _, ns in COLUMNS for n in ns]
    print(",".join(["wheel", "case"] + names))
    for side in ("right", "left"):
        with open(f"{checkout}/examples/mbench_a22_{side}.ref_out") as f:
            for row in cases(f.read()):
                print(",".join([side] + row))


if __name__ == "__main__":
    main(sys.argv[1])
