#!/usr/bin/env python3
"""The fastening study's table (issue 49 item 6): per variant and level, how many of its rooms had the
tall cabinet and the upper cabinet fall (tipped past 60 deg, or came down more than 5 cm), and how many
had a device on the tall cabinet or on the separated cabinets break, with Wilson 95 % intervals.

    python3 paper/restraint_outcomes.py STUDY_FOLDER > paper/results/<study>/restraint_outcomes.md

Reads the study's run records (STUDY_FOLDER/runs/*.json, which hold each restraint's outcome) and
study.json; writes Markdown to stdout and restraint_outcomes.csv beside the records."""
import csv
import glob
import json
import os
import sys
from collections import Counter, defaultdict

from study_tables import fallen, wilson


def main(folder):
    study = json.load(open(os.path.join(folder, "study.json")))
    variants = [v["name"] for v in study["compare"]]
    levels = study["intensity"]["levels"]
    per_level = study["realisations"] * max(1, len(study.get("ground_motions", [])) or 1)
    counts = defaultdict(Counter)
    for path in sorted(glob.glob(os.path.join(folder, "runs", "*.json"))):
        r = json.load(open(path))
        key = (variants[r["variant"]], r["realisation"] // per_level)
        bodies = {b["item"]: b for b in r["bodies"]}
        devices = r.get("restraints", [])
        c = counts[key]
        c["runs"] += 1
        c["completed"] += r["status"] == "completed"
        c["tall_fell"] += fallen(bodies["tall_cabinet"])
        c["upper_fell"] += fallen(bodies["separated_cabinets/upper"])
        c["tall_device_broke"] += any(d["broke"] for d in devices if d["item"] == "tall_cabinet")
        c["separated_device_broke"] += any(d["broke"] for d in devices if d["item"].startswith("separated_cabinets"))
    columns = ["tall_fell", "upper_fell", "tall_device_broke", "separated_device_broke"]
    with open(os.path.join(folder, "restraint_outcomes.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["variant", "level", "runs"] + [x for c in columns for x in (c, c + "_lo", c + "_hi")])
        for v in variants:
            for i, level in enumerate(levels):
                c = counts[(v, i)]
                row = [v, level, c["runs"]]
                for col in columns:
                    lo, hi = wilson(c[col], c["runs"])
                    row += [c[col], f"{lo:.3f}", f"{hi:.3f}"]
                w.writerow(row)
    print("| variant | level | runs | tall cabinet fell | upper cabinet fell | a tall-cabinet device broke | "
          "a separated-cabinets device broke |")
    print("|---|---|---|---|---|---|---|")
    for v in variants:
        for i, level in enumerate(levels):
            c = counts[(v, i)]
            cells = []
            for col in columns:
                lo, hi = wilson(c[col], c["runs"])
                cells.append(f"{c[col]} [{lo:.2f}, {hi:.2f}]")
            print(f"| {v} | {level} | {c['runs']} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
