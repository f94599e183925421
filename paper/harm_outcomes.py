#!/usr/bin/env python3
"""The storey study's table (issue 50 item 5): per variant (a storey, free standing or fastened), how many
of its rooms had an occupant struck, struck seriously (a strike above a threshold: docs/harm/occupants.md),
an exit blocked at the end and an item fall, with Wilson 95 % intervals.

    python3 paper/harm_outcomes.py STUDY_FOLDER > paper/results/<study>/harm_outcomes.md

Reads the study's run records (STUDY_FOLDER/runs/*.json: each occupant's strikes, each exit's outcome)
and study.json; writes Markdown to stdout and harm_outcomes.csv beside the records."""
import csv
import glob
import json
import os
import sys
from collections import Counter, defaultdict

from study_tables import fallen, wilson


COLUMNS = [("struck", "an occupant struck"), ("seriously", "struck seriously"),
           ("head", "struck on the head"), ("exit_blocked_ever", "an exit blocked at some time"),
           ("exit_blocked", "an exit blocked at the end"),
           ("fell", "an item fell")]


def count(folder):
    study = json.load(open(os.path.join(folder, "study.json")))
    variants = [v["name"] for v in study["compare"]]
    counts = defaultdict(Counter)
    for path in sorted(glob.glob(os.path.join(folder, "runs", "*.json"))):
        r = json.load(open(path))
        c = counts[variants[r["variant"]]]
        c["runs"] += 1
        c["completed"] += r["status"] == "completed"
        people = r.get("occupants", [])
        c["struck"] += any(o["struck"] for o in people)
        c["seriously"] += any(o["seriously"] for o in people)
        c["head"] += any(s["zone"] == "head" for o in people for s in o["strikes"])
        c["exit_blocked_ever"] += any(e["first_blocked_at_s"] is not None for e in r.get("exits", []))
        c["exit_blocked"] += any(e["blocked"] for e in r.get("exits", []))
        c["fell"] += any(fallen(b) for b in r["bodies"])
    return variants, counts


def main(folder):
    variants, counts = count(folder)
    with open(os.path.join(folder, "harm_outcomes.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["variant", "runs", "completed"] + [x for c, _ in COLUMNS for x in (c, c + "_lo", c + "_hi")])
        for v in variants:
            c = counts[v]
            row = [v, c["runs"], c["completed"]]
            for col, _ in COLUMNS:
                lo, hi = wilson(c[col], c["runs"])
                row += [c[col], f"{lo:.3f}", f"{hi:.3f}"]
            w.writerow(row)
    print("| variant | runs | " + " | ".join(title for _, title in COLUMNS) + " |")
    print("|---|---|" + "---|" * len(COLUMNS))
    for v in variants:
        c = counts[v]
        cells = []
        for col, _ in COLUMNS:
            lo, hi = wilson(c[col], c["runs"])
            cells.append(f"{c[col]} [{lo:.2f}, {hi:.2f}]")
        print(f"| {v} | {c['runs']} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
