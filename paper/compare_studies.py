#!/usr/bin/env python3
"""Pairs two runs of one study (the same study seed and realisations, run by two versions of the code
or with two settings that one study file cannot express) realisation by realisation, and prints, per
body and damage state, both rates and their paired difference with Newcombe's method-10 interval, as
furniture_study's comparisons.csv does for variants of one study (study/statistics.hpp,
paired_difference). Also the median and largest change of the continuous outcomes.

    python3 paper/compare_studies.py OLD_DIR NEW_DIR [--slide 0.05] [--tilt 10]

OLD_DIR and NEW_DIR are furniture_study results folders (their realisations.csv). Damage states as the
study defines them (study/report.hpp): slid (final slide above --slide m), tilted (largest tilt above
--tilt deg), overturned (final state), fallen (tipped past 60 deg or came down more than 5 cm, as
study/report.hpp's). Runs that did not complete in both are left out.
"""
import argparse
import csv
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "studies"))
from summarise import fallen, wilson  # noqa: E402  (the study scripts' Wilson interval and `fallen`)


def paired_difference(both, only_a, only_b, neither):
    n = both + only_a + only_b + neither
    pa, pb = (both + only_a) / n, (both + only_b) / n
    la, ua = wilson(both + only_a, n)
    lb, ub = wilson(both + only_b, n)
    margins = (both + only_a) * (only_b + neither) * (both + only_b) * (only_a + neither)
    cross = both * neither - only_a * only_b
    num = cross - 0.5 * n if cross > 0.5 * n else (cross if cross < 0 else 0.0)
    phi = num / math.sqrt(margins) if margins > 0 else 0.0
    dla, dua, dlb, dub = pa - la, ua - pa, pb - lb, ub - pb
    d = pa - pb
    lo = d - math.sqrt(max(0.0, dla * dla - 2 * phi * dla * dub + dub * dub))
    hi = d + math.sqrt(max(0.0, dua * dua - 2 * phi * dua * dlb + dlb * dlb))
    return pa, pb, d, lo, hi


def read(folder):
    with open(f"{folder}/realisations.csv", newline="") as f:
        return {(r["realisation"], r["variant"]): r for r in csv.DictReader(f)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--slide", type=float, default=0.05)
    ap.add_argument("--tilt", type=float, default=10.0)
    a = ap.parse_args()
    old, new = read(a.old), read(a.new)
    keys = sorted(k for k in old if k in new and old[k]["status"] == "completed" and new[k]["status"] == "completed")
    if not keys:
        sys.exit("no realisation completed in both folders")
    bodies = [c[: -len(".state")] for c in old[keys[0]] if c.endswith(".state")]
    states = {
        "slid": lambda r, b: float(r[b + ".slide_m"]) > a.slide,
        "tilted": lambda r, b: float(r[b + ".max_tilt_deg"]) > a.tilt,
        "overturned": lambda r, b: r[b + ".state"] == "overturned",
        "fallen": lambda r, b: fallen({"max_tilt_deg": float(r[b + ".max_tilt_deg"]), "lift": float(r[b + ".lift_m"])}),
    }
    print(f"{len(keys)} realisations completed in both (old: {a.old}, new: {a.new})")
    print("| body | state | old | new | new - old [95 %] | distinguishable |")
    print("|---|---|---:|---:|---|---|")
    for b in bodies:
        for s, test in states.items():
            t = [(test(old[k], b), test(new[k], b)) for k in keys]
            both = sum(x and y for x, y in t)
            only_old = sum(x and not y for x, y in t)
            only_new = sum(y and not x for x, y in t)
            neither = len(t) - both - only_old - only_new
            po, pn, d, lo, hi = paired_difference(both, only_old, only_new, neither)
            dist = "yes" if lo > 0 or hi < 0 else "no"
            print(f"| {b} | {s} | {po:.3f} | {pn:.3f} | {-d:+.3f} [{-hi:+.3f}, {-lo:+.3f}] | {dist} |")
    print()
    print("| body | outcome | median old | median new | median abs change | largest abs change |")
    print("|---|---|---:|---:|---:|---:|")
    for b in bodies:
        for o in ("slide_m", "max_tilt_deg"):
            xo = [float(old[k][f"{b}.{o}"]) for k in keys]
            xn = [float(new[k][f"{b}.{o}"]) for k in keys]
            ch = [abs(y - x) for x, y in zip(xo, xn)]
            print(f"| {b} | {o} | {statistics.median(xo):.3g} | {statistics.median(xn):.3g} | "
                  f"{statistics.median(ch):.3g} | {max(ch):.3g} |")


if __name__ == "__main__":
    main()
