#!/usr/bin/env python3
"""Two studies of the same rooms at two fidelities, room by room (issue 49: `full` against `rigid` in
the fastening study): for each variant and room, each cabinet's fate (fell: tipped past 60 deg or came
down more than 5 cm; resting on another item; its largest tilt and its slide) and each device's outcome
(when and how it broke; the largest force of any, as a share of its strength in the sense that fails it),
side by side.

    python3 paper/fidelity_pairs.py FULL_STUDY_FOLDER RIGID_STUDY_FOLDER > paper/results/<study>/rooms_full_and_rigid.md

Both folders are furniture_study outputs (their study.json and run records runs/*.json; a study stopped
part-way has records of its finished runs only). Their studies must draw the same rooms: the same base
scene, seed, perturbations, levels, number of realisations and variant names; the script stops
otherwise. Runs are paired by variant and realisation; a room finished in only one is left out."""
import glob
import json
import os
import sys

from study_tables import fallen

BODIES = ["tall_cabinet", "separated_cabinets/upper", "separated_cabinets/lower"]


SAME_ROOMS = ["scene", "seed", "perturbations", "intensity", "realisations", "ground_motions"]


def load(folder):
    study = json.load(open(os.path.join(folder, "study.json")))
    variants = [v["name"] for v in study["compare"]]
    levels = study["intensity"]["levels"]
    runs = {}
    for path in glob.glob(os.path.join(folder, "runs", "*.json")):
        rec = json.load(open(path))
        if rec["status"] == "stopped":
            continue
        level = levels[rec["realisation"] // study["realisations"]]
        runs[(variants[rec["variant"]], level, rec["realisation"] % study["realisations"])] = rec
    return study, runs


def fate(rec, body):
    b = {x["item"]: x for x in rec["bodies"]}[body]
    held = f" (on {b['resting_on']})" if b.get("resting_on") and not fallen(b) else ""
    return f"{'**fell**' if fallen(b) else 'stood'}{held} {b['max_tilt_deg']:.1f} deg, {100 * b['slide_m']:.0f} cm"


def devices(rec):
    out = []
    for d in rec.get("restraints", []):
        if d["broke"]:
            out.append(f"{d['name']} broke at {d['broke_at_s']:.2f} s ({d['failure']})")
    peak = max((d["peak_ratio"] for d in rec.get("restraints", [])), default=None)
    if peak is None:
        return "-"
    return ("; ".join(out) + "; " if out else "all held; ") + f"largest force {100 * peak:.0f} % of its strength"


def main(full_folder, rigid_folder):
    (full_study, full), (rigid_study, rigid) = load(full_folder), load(rigid_folder)
    for key in SAME_ROOMS:
        if full_study.get(key) != rigid_study.get(key):
            sys.exit(f"the two studies differ in '{key}': not the same rooms")
    if [v["name"] for v in full_study["compare"]] != [v["name"] for v in rigid_study["compare"]]:
        sys.exit("the two studies' variants differ")
    print("| variant | level | room | fidelity | tall cabinet | upper cabinet | lower cabinet | devices |")
    print("|---|---|---|---|---|---|---|---|")
    order = [v["name"] for v in full_study["compare"]]
    for key in sorted(set(full) & set(rigid), key=lambda k: (order.index(k[0]), k[1], k[2])):
        for name, rec in (("full", full[key]), ("rigid", rigid[key])):
            cells = [fate(rec, b) for b in BODIES]
            print(f"| {key[0]} | {key[1]} | {key[2]} | {name} | " + " | ".join(cells) + f" | {devices(rec)} |")
    missing = sorted(set(full) ^ set(rigid))
    if missing:
        print(f"\nFinished in one study only (left out): {', '.join(f'{v} {l} room {r}' for v, l, r in missing)}.")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
