#!/usr/bin/env python3
"""The paper's statements on configuration 3 as probabilities over a study's realisations (issue 14).

    python3 paper/studies/summarise.py STUDY_DIR [STUDY_DIR ...] [--out paper/results/distribution.md]

Each STUDY_DIR is the results folder of one of paper/studies/config3_<case>_30.json, run with
`furniture_study` (or its committed copy, paper/results/study_config3_<case>/: only its
realisations.csv and summary.json are read); the case is read from summary.json's study name. For every statement of the paper that
a final state can decide (paper/RESULTS.md, "Configuration 3"), it counts the realisations in which the
statement holds, gives the fraction with its Wilson 95 % interval, and says whether the committed
single run (paper/results/config3_<case>/final_state.json) has it. Continuous outcomes (slides, largest
tilts) get their median, 16 % and 84 % quantiles and the committed run's rank among the realisations.
Standard library only.
"""
import argparse
import csv
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(os.path.dirname(HERE), "results")
Z95 = 1.959963984540054


def wilson(k, n, z=Z95):
    if n == 0:
        return float("nan"), float("nan")
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z / den * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return max(0.0, centre - half), min(1.0, centre + half)


def fallen(b):
    # Off its feet at some time: tipped past 60 deg or came down more than 5 cm (off the item it stood on),
    # whatever it ends as: the study's damage state "fallen" (has_fallen, scene/run_summary.hpp).
    return b["max_tilt_deg"] > 60 or b["lift"] < -0.05


# (case, text, RESULTS.md row, test on the bodies by name)
STATEMENTS = [
    ("kobe50_1d", "the upper cabinet shifts only slightly (stays on, slide < 0.1 m)", 1,
     lambda b: not fallen(b["separated_cabinets/upper"]) and b["separated_cabinets/upper"]["slide"] < 0.1),
    ("kobe50_1d", "nothing falls", 1, lambda b: not any(fallen(x) for x in b.values())),
    ("kobe50_1d", "the desk moves about 10 cm (slide >= 5 cm)", 3, lambda b: b["desk"]["slide"] >= 0.05),
    ("kobe100_1d", "the upper cabinet falls", 4, lambda b: fallen(b["separated_cabinets/upper"])),
    ("kobe100_1d", "the tall cabinet falls", 5, lambda b: fallen(b["tall_cabinet"])),
    ("kobe100_1d", "the tall cabinet ends leaning on the desk", 5,
     lambda b: b["tall_cabinet"]["resting_on"] == "desk"),
    ("kobe100_3d", "the upper cabinet falls", 8, lambda b: fallen(b["separated_cabinets/upper"])),
    ("kobe100_3d", "the tall cabinet falls", 7, lambda b: fallen(b["tall_cabinet"])),
    ("kobe100_3d", "the tall cabinet ends on the desk", 7, lambda b: b["tall_cabinet"]["resting_on"] == "desk"),
]
CONTINUOUS = [("tall_cabinet", "slide"), ("tall_cabinet", "max_tilt_deg"), ("separated_cabinets/upper", "slide"),
              ("separated_cabinets/upper", "max_tilt_deg"), ("desk", "slide"), ("office_chair", "slide")]


def quantile(xs, q):  # type 7, as the study's distributions.csv
    xs = sorted(xs)
    h = (len(xs) - 1) * q
    lo = math.floor(h)
    return xs[lo] + (h - lo) * (xs[min(lo + 1, len(xs) - 1)] - xs[lo])


def load_study(folder):
    """The case and, per completed realisation, its bodies' outcomes from realisations.csv."""
    summary = json.load(open(os.path.join(folder, "summary.json")))
    name = summary.get("study", {}).get("name") if isinstance(summary.get("study"), dict) else summary.get("study")
    case = name.replace("config3_", "").rsplit("_", 1)[0]
    rows = list(csv.DictReader(open(os.path.join(folder, "realisations.csv"))))
    done = []
    for r in rows:
        if r["status"] != "completed":
            continue
        bodies = {}
        for col, value in r.items():
            if "." not in col:
                continue
            body, key = col.rsplit(".", 1)
            if key in ("state", "slide_m", "max_tilt_deg", "lift_m", "resting_on"):
                b = bodies.setdefault(body, {})
                b[{"slide_m": "slide", "lift_m": "lift"}.get(key, key)] = value if key in ("state", "resting_on") else float(value)
        done.append(bodies)
    return case, summary, rows, done


def committed(case):
    path = os.path.join(RESULTS, "config3_" + case, "final_state.json")
    if not os.path.isfile(path):
        return None
    out = {}
    for b in json.load(open(path)):
        out[b["item"]] = {"state": b["state"], "slide": b["slide_m"], "max_tilt_deg": b["max_tilt_deg"],
                          "lift": b["lift_m"], "resting_on": b["resting_on"]}
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("studies", nargs="+")
    ap.add_argument("--out", default=os.path.join(RESULTS, "distribution.md"))
    a = ap.parse_args()
    lines = ["# Configuration 3 as a distribution: the paper's statements over perturbed realisations", "",
             "Written by `python3 paper/studies/summarise.py` from the study folders of",
             "`paper/studies/config3_<case>_30.json` (`furniture_study`). Each realisation moves every item by",
             "U(-10, 10) mm in x and y, turns it by U(-1, 1) deg and scales its friction coefficients by",
             "1 + U(-0.1, 0.1), from the study seed and its index; the contact law, fidelity (`full`), motion and",
             "every other setting are the committed scenes'. Fraction: realisations in which the statement holds,",
             "with its Wilson 95 % interval. Committed run: paper/results/config3_<case>/final_state.json.", ""]
    for folder in a.studies:
        case, summary, runs, bodies = load_study(folder)
        one = committed(case)
        lines += ["## " + case + " (" + str(len(bodies)) + " of " + str(len(runs)) + " realisations completed)", "",
                  "| statement (RESULTS.md row) | holds in | fraction [95 % interval] | committed run |",
                  "|---|---|---|---|"]
        for c, text, row, test in STATEMENTS:
            if c != case:
                continue
            k = sum(1 for b in bodies if test(b))
            lo, hi = wilson(k, len(bodies))
            mine = "-" if one is None else ("holds" if test(one) else "does not hold")
            lines.append("| %s (%d) | %d of %d | %.2f [%.2f, %.2f] | %s |" % (text, row, k, len(bodies),
                                                                         k / len(bodies), lo, hi, mine))
        lines += ["", "| outcome | median | 16 %% - 84 %% | min - max | committed run (rank of %d) |" % len(bodies),
                  "|---|---|---|---|---|"]
        for name, key in CONTINUOUS:
            xs = [b[name][key] for b in bodies]
            unit = "m" if key == "slide" else "deg"
            mine = "-"
            if one is not None:
                v = one[name][key]
                mine = "%.3g %s (%d)" % (v, unit, 1 + sum(1 for x in xs if x < v))
            lines.append("| %s %s | %.3g | %.3g - %.3g | %.3g - %.3g | %s |" % (
                name, key.replace("_deg", ""), quantile(xs, 0.5), quantile(xs, 0.16), quantile(xs, 0.84),
                min(xs), max(xs), mine))
        lines += ["", "Wall time per realisation: mean %.0f s (%s worker(s); summary.json)." %
                  (summary.get("mean_run_seconds", float("nan")), summary.get("workers", "?")), ""]
    with open(a.out, "w") as f:
        f.write("\n".join(lines))
    print("wrote " + a.out)


if __name__ == "__main__":
    sys.exit(main())
