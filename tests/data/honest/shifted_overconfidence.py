#!/usr/bin/env python3
"""How much verify over-states the joint probability when it is read at a
stricter point (Tmax - dt, Rmax - dr), against the validation's 95 % Wilson
lower bound at (Tmax, Rmax): max over the grid of
verify(T - dt, R - dr) - validate_ci_low(T, R). At most ~0 means that deciding
at the stricter point is conservative on this mission. Reads the verify.json and
validate.json that `vipars report` (tests/data/honest/measure.sh) writes.

usage: shifted_overconfidence.py REPORT_DIR [DT_S DR_M]   (default 0.5 0.02)
"""
import json
import sys


def main() -> int:
    folder = sys.argv[1]
    dt = float(sys.argv[2]) if len(sys.argv) > 2 else 0.5
    dr = float(sys.argv[3]) if len(sys.argv) > 3 else 0.02
    v = json.load(open(f"{folder}/verify.json"))["grid"]
    w = json.load(open(f"{folder}/validate.json"))["grid"]
    t, r = v["tmax"], v["rmax"]
    si = round(dt / (t[1] - t[0])) if len(t) > 1 else 0
    sj = round(dr / (r[1] - r[0])) if len(r) > 1 else 0
    worst = max(v["p_joint"][i - si][j - sj] - w["p_joint_ci_low"][i][j]
                for i in range(si, len(t)) for j in range(sj, len(r)))
    print(f"{folder}: shift {dt} s / {dr} m: max verify - validation lower bound {worst:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
