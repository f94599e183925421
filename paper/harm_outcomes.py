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


tops = defaultdict(list)  # per variant: each run's most energetic strike (J)

COLUMNS = [("struck", "an occupant struck"), ("seriously", "struck seriously"),
           ("head", "struck on the head"), ("exit_blocked_ever", "an exit blocked at some time"),
           ("exit_blocked", "an exit blocked at the end"),
           ("fell", "an item fell")]


def count(folder):
    study = json.load(open(os.path.join(folder, "study.json")))
    variants = [v["name"] for v in study["compare"]]
    counts = defaultdict(Counter)
    tops.clear()
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
        for b in r["bodies"]:
            c["fell:" + b["item"]] += fallen(b)
        c["strikes"] += sum(len(o["strikes"]) for o in people)
        top = max((s["kinetic_energy_j"] for o in people for s in o["strikes"]), default=0.0)
        tops[variants[r["variant"]]].append(top)
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
    items = sorted({k[5:] for c in counts.values() for k in c if k.startswith("fell:")})
    print()
    print("Items that fell (tipped past 60 deg or came down more than 5 cm), runs of each variant; and each run's")
    print("most energetic strike (the item's kinetic energy at its onset, J): median and largest over the runs.")
    print()
    print("| variant | " + " | ".join(items) + " | strikes a run | most energetic strike: median, largest (J) |")
    print("|---|" + "---|" * (len(items) + 2))
    for v in variants:
        c = counts[v]
        t = sorted(tops[v])
        med = t[len(t) // 2] if len(t) % 2 else 0.5 * (t[len(t) // 2 - 1] + t[len(t) // 2]) if t else 0.0
        print(f"| {v} | " + " | ".join(str(c["fell:" + i]) for i in items) +
              f" | {c['strikes'] / max(1, c['runs']):.1f} | {med:.1f}, {max(t, default=0.0):.1f} |")


if __name__ == "__main__":
    main(sys.argv[1])
