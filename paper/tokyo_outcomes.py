#!/usr/bin/env python3
"""The Tokyo 2015 device test against the model (issue 49): per item, variant and JMA intensity, how many
of the study's rooms had the item fall (tipped past 60 deg, or came down more than 5 cm), move 30 cm or
more without falling (the test's "equivalent to overturning"), move 10 to 30 cm, or move less than 10 cm,
and how many had a device on it break; Wilson 95 % intervals on the fallen count.

    python3 paper/tokyo_outcomes.py STUDY_FOLDER > paper/results/study_tokyo_2015_devices/tokyo_outcomes.md

The study's scene scales the record to JMA intensity `base` (ground_motion.scale_to.jma) and its levels
multiply that, so a level k is the intensity base + 2 log10 k. Reads STUDY_FOLDER/study.json and the run
records STUDY_FOLDER/runs/*.json; writes Markdown to stdout and tokyo_outcomes.csv beside the records."""
import csv
import glob
import json
import math
import os
import sys
from collections import Counter, defaultdict

from study_tables import fallen, wilson

ITEMS = ("chest", "cupboard")


def outcome(body):
    if fallen(body):
        return "fell"
    if body["slide_m"] >= 0.30:
        return "moved_30cm"
    return "moved_10_30cm" if body["slide_m"] >= 0.10 else "moved_under_10cm"


def main(folder, base):
    study = json.load(open(os.path.join(folder, "study.json")))
    variants = [v["name"] for v in study["compare"]]
    levels = study["intensity"]["levels"]
    per_level = study["realisations"]
    counts = defaultdict(Counter)
    for path in sorted(glob.glob(os.path.join(folder, "runs", "*.json"))):
        r = json.load(open(path))
        level = r["realisation"] // per_level
        bodies = {b["item"]: b for b in r["bodies"]}
        for item in ITEMS:
            c = counts[(item, variants[r["variant"]], level)]
            c["runs"] += 1
            c[outcome(bodies[item])] += 1
            c["device_broke"] += any(d["broke"] for d in r.get("restraints", []) if d["item"] == item)
    columns = ["fell", "moved_30cm", "moved_10_30cm", "moved_under_10cm", "device_broke"]
    with open(os.path.join(folder, "tokyo_outcomes.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["item", "variant", "level", "jma_intensity", "runs"] + columns + ["fell_lo", "fell_hi"])
        for item in ITEMS:
            for v in variants:
                for i, level in enumerate(levels):
                    c = counts[(item, v, i)]
                    lo, hi = wilson(c["fell"], c["runs"])
                    w.writerow([item, v, level, f"{base + 2 * math.log10(level):.2f}", c["runs"]] +
                               [c[k] for k in columns] + [f"{lo:.3f}", f"{hi:.3f}"])
    for item in ITEMS:
        print(f"\n**{item}**\n")
        print("| variant | JMA intensity | runs | fell [95 %] | moved >= 30 cm | 10-30 cm | < 10 cm | a device broke |")
        print("|---|---|---|---|---|---|---|---|")
        for v in variants:
            for i, level in enumerate(levels):
                c = counts[(item, v, i)]
                lo, hi = wilson(c["fell"], c["runs"])
                print(f"| {v} | {base + 2 * math.log10(level):.2f} | {c['runs']} | {c['fell']} [{lo:.2f}, {hi:.2f}] | "
                      f"{c['moved_30cm']} | {c['moved_10_30cm']} | {c['moved_under_10cm']} | {c['device_broke']} |")


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    main(sys.argv[1], float(sys.argv[2]) if len(sys.argv) == 3 else 6.0)
