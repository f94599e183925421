#!/usr/bin/env python3
"""Configuration 3 under the paper's three JMA-Kobe cases, every item at fidelity full, auto and
rigid, with the scene's own contact law (the paper's) and with `stiff`: 3 x 3 x 2 = 18 runs.

    python3 paper/compare_contact.py [--furniture-quake PATH] [--scratch DIR] [--cases a,b,c]
                                     [--fidelities full,auto,rigid] [--laws paper,stiff]
                                     [--duration S] [--skip-existing] [--nice N]
                                     [--not-run FIDELITY:LAW,...] [--plane-contact-at surfaces]

Writes the scene variants and the runs' outputs to --scratch (default /tmp/ffem_contact_comparison),
runs them one after the other (niced), and writes paper/results/contact_comparison.md (a table per
case: rows = bodies, columns = fidelity x law, cells "state, slide m, tilt deg") and
paper/results/contact_comparison.csv (one row per run and body: every final_state field, the run's
wall seconds and status). Standard library only. When the JMA-Kobe records the scenes name are
absent it says so in one line and exits 0. With --plane-contact-at surfaces every variant's items touch
the floor and walls at their members' surfaces (docs/contact/contact.md, "At the surface": a rigid
item's envelope, a flexible item's cube of corners per node); the files are then
contact_comparison_surfaces.md and .csv.
"""
import argparse
import copy
import csv
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
CASES = ["kobe50_1d", "kobe100_1d", "kobe100_3d"]
CASE_TITLE = {"kobe50_1d": "(i) 50 % JMA-Kobe, 1-D", "kobe100_1d": "(ii) 100 % JMA-Kobe, 1-D",
              "kobe100_3d": "(iii) 100 % JMA-Kobe, 3-D"}
FIDELITIES = ["full", "auto", "rigid"]
LAWS = ["paper", "stiff"]
# Keys of the scene's contact object kept for the stiff law (scene_file.md, `contact`): the law, the
# friction settings and how rigid pairs meet (the scenes' `members`, which the stiff columns have always
# used: the default was `members` until 2026-12-04). The paper law's penalty keys are errors for stiff;
# `implicit` is left to the default (every item's floor and wall contact inside the implicit step), and
# so, as before, is `plane_contact_at` (the surfaces: the stiff columns run there, not at the scenes'
# centre lines; noted in results/contact_comparison.md).
STIFF_TOP_KEYS = {"law", "stick_length", "velocity_regularisation", "rigid_pairs"}
STIFF_OVERRIDE_KEYS = {"mu", "mu_long"}


def default_quake():
    for p in (os.path.join(REPO, "build-paper", "furniture_quake"),
              os.path.join(REPO, "build", "examples", "furniture_quake"),
              os.path.join(REPO, "build", "furniture_quake")):
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return p
    return os.path.join(REPO, "build-paper", "furniture_quake")


def stiff_contact(contact):
    out = {k: v for k, v in contact.items() if k in STIFF_TOP_KEYS}
    out["law"] = "stiff"
    # Two full items' pairs as the committed columns ran them: explicit (the default until 2026-12-06;
    # solved together, docs/contact/implicit_contact.md "Flexible groups", the full columns cost 2.5 times).
    out["flexible_pairs"] = "explicit"
    for pair in ("floor", "wall", "item"):
        if pair in contact:
            kept = {k: v for k, v in contact[pair].items() if k in STIFF_OVERRIDE_KEYS}
            if kept:
                out[pair] = kept
    return out


def variant(scene, scene_dir, fidelity, law, plane_contact_at="centre_lines"):
    s = copy.deepcopy(scene)
    for it in s["items"]:
        it["fidelity"] = fidelity
    if law == "stiff":
        s["contact"] = stiff_contact(s.get("contact", {}))
    if plane_contact_at != "centre_lines":
        s.setdefault("contact", {})["plane_contact_at"] = plane_contact_at
    # Record paths are relative to the scene file: make them absolute for the scratch copy.
    files = s.get("ground_motion", {}).get("files", {})
    for ax, f in files.items():
        files[ax] = os.path.normpath(os.path.join(scene_dir, f))
    if "file" in s.get("ground_motion", {}):
        s["ground_motion"]["file"] = os.path.normpath(os.path.join(scene_dir, s["ground_motion"]["file"]))
    out = s.setdefault("outputs", {})
    out["figures"] = False
    out["vtu_every"] = 0
    if fidelity == "rigid":  # a rigid body has no sectional forces
        out["sectional_forces"] = []
    s["name"] = "%s [%s, %s]" % (s.get("name", ""), fidelity, law)
    return s


def records_of(scene, scene_dir):
    g = scene.get("ground_motion", {})
    fs = list(g.get("files", {}).values()) + ([g["file"]] if "file" in g else [])
    return [os.path.normpath(os.path.join(scene_dir, f)) for f in fs]


def cell(r, summ):
    if r is None:
        return "-" if summ else "not run"
    if summ.get("status") != "completed":  # the state at the stop is not an outcome
        return "(%s at %.2f s)" % (summ.get("status", "?"), summ.get("t_end_s", float("nan")))
    return "%s, %.3f, %.1f" % (r["state"], r["slide_m"], r["tilt_deg"])


def run_variant(a, name, scene):
    """Writes the scene to a.scratch/name.json and runs it into a.scratch/name (unless a.skip_existing and
    it has a summary.json): its summary and final states, or a failed status and none."""
    spath, odir = os.path.join(a.scratch, name + ".json"), os.path.join(a.scratch, name)
    with open(spath, "w") as f:
        json.dump(scene, f, indent=2)
    summ = os.path.join(odir, "summary.json")
    if not (a.skip_existing and os.path.isfile(summ)):
        os.makedirs(odir, exist_ok=True)
        # --overwrite: odir already holds this script's stderr.log (kept by the program).
        cmd = ["nice", "-n", str(a.nice), a.furniture_quake, spath, "--out", odir, "--quiet", "--overwrite"]
        if getattr(a, "duration", None):
            cmd += ["--duration", str(a.duration)]
        t0 = time.time()
        with open(os.path.join(odir, "stderr.log"), "w") as err:
            rc = subprocess.call(cmd, stdout=subprocess.DEVNULL, stderr=err)
        print("== %s: exit %d, %.1f s" % (name, rc, time.time() - t0), flush=True)
    summary, final = {"status": "failed (no summary.json)"}, []
    if os.path.isfile(summ):
        with open(summ) as f:
            summary = json.load(f)
    fpath = os.path.join(odir, "final_state.json")
    if os.path.isfile(fpath):
        with open(fpath) as f:
            final = json.load(f)
    return summary, final


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--furniture-quake", default=os.environ.get("FURNITURE_QUAKE") or default_quake())
    ap.add_argument("--scratch", default="/tmp/ffem_contact_comparison")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--fidelities", default=",".join(FIDELITIES))
    ap.add_argument("--laws", default=",".join(LAWS))
    ap.add_argument("--duration", type=float, default=None, help="shorten every run (a trial)")
    ap.add_argument("--skip-existing", action="store_true", help="reuse runs whose summary.json exists")
    ap.add_argument("--nice", type=int, default=int(os.environ.get("NICE", "10")))
    ap.add_argument("--results", default=os.path.join(HERE, "results"))
    ap.add_argument("--not-run", default="", help="columns left out of the runs, shown as 'not run' "
                    "(e.g. full:stiff, whose 12 s runs take about 40 min each)")
    ap.add_argument("--plane-contact-at", default="centre_lines", choices=["centre_lines", "surfaces"])
    a = ap.parse_args()
    suffix = "" if a.plane_contact_at == "centre_lines" else "_" + a.plane_contact_at
    not_run = {tuple(x.split(":")) for x in a.not_run.split(",") if x}
    cases = a.cases.split(",")
    fids = a.fidelities.split(",")
    laws = a.laws.split(",")

    scenes = {}
    for c in cases:
        path = os.path.join(HERE, "scenes", "config3_%s.json" % c)
        with open(path) as f:
            scenes[c] = (json.load(f), os.path.dirname(path))
    missing = sorted({r for c in cases for r in records_of(*scenes[c]) if not os.path.isfile(r)})
    if missing:
        print("compare_contact.py: JMA-Kobe records not found (%s): skipped" % ", ".join(missing))
        return 0
    if not os.access(a.furniture_quake, os.X_OK):
        print("compare_contact.py: no furniture_quake at %s (give --furniture-quake)" % a.furniture_quake,
              file=sys.stderr)
        return 2

    os.makedirs(a.scratch, exist_ok=True)
    runs = []  # (case, fidelity, law, summary, final_state)
    for c in cases:
        scene, scene_dir = scenes[c]
        for fid in fids:
            for law in laws:
                if (fid, law) in not_run:
                    continue
                name = "config3_%s_%s_%s%s" % (c, fid, law, suffix)
                summary, final = run_variant(a, name, variant(scene, scene_dir, fid, law, a.plane_contact_at))
                runs.append((c, fid, law, summary, final))

    os.makedirs(a.results, exist_ok=True)
    fields = ["item", "state", "slide_m", "tilt_deg", "max_tilt_deg", "lift_m", "resting_on",
              "cog_dx_m", "cog_dy_m", "cog_dz_m"]
    with open(os.path.join(a.results, "contact_comparison%s.csv" % suffix), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "fidelity", "law", "contact_law"] + fields + ["wall_s", "status", "t_end_s"])
        for c, fid, law, summ, final in runs:
            claw = summ.get("scene", {}).get("contact", {}).get("law", "")
            for r in final:
                d = r.get("cog_displacement_m", [None] * 3)
                row = [r.get(k, "") for k in fields[:7]] + list(d)
                w.writerow([c, fid, law, claw] + row + ["%.2f" % summ.get("wall_seconds", float("nan")),
                                                         summ.get("status", ""), summ.get("t_end_s", "")])
            if not final:
                w.writerow([c, fid, law, claw] + [""] * len(fields) + ["", summ.get("status", ""), ""])

    cols = [(fid, law) for fid in fids for law in laws]
    md = ["# Configuration 3 under JMA-Kobe: outcomes by fidelity and contact law", "",
          "Written by `paper/compare_contact.py` (furniture_quake: `%s`). Every item at the same fidelity;"
          % a.furniture_quake,
          "`paper` = the scene's own law (%s), `stiff` = `\"contact\": {\"law\": \"stiff\"}`. `auto` leaves"
          % ", ".join(sorted({scenes[c][0].get("contact", {}).get("law", "paper") for c in cases})),
          "an item rigid unless a sectional force of it is asked for: here the desk stays flexible.",
          "Cell: final state, slide (m), final tilt (deg) at 12 s; a run that stopped early (status not",
          "`completed`) shows its status and when it stopped. Last row: wall time of the run (s) and status.",
          "Per-body numbers of every run, stopped ones included: contact_comparison%s.csv." % suffix,
          "Floor and wall contact at the items' members' %s (`plane_contact_at`)."
          % ("centre lines" if not suffix else "surfaces"), ""]
    for c in cases:
        md += ["## Case %s" % CASE_TITLE.get(c, c), ""]
        md.append("| body | " + " | ".join("%s, %s" % fc for fc in cols) + " |")
        md.append("|---|" + "---|" * len(cols))
        by = {(fid, law): (summ, {r["item"]: r for r in final}) for cc, fid, law, summ, final in runs if cc == c}
        bodies = []
        for fc in cols:
            for b in by.get(fc, ({}, {}))[1]:
                if b not in bodies:
                    bodies.append(b)
        for b in bodies:
            md.append("| %s | " % b + " | ".join(cell(by.get(fc, ({}, {}))[1].get(b), by.get(fc, ({}, {}))[0])
                                                 for fc in cols) + " |")
        md.append("| wall s | " + " | ".join(
            "%.1f (%s)" % (by[fc][0].get("wall_seconds", float("nan")), by[fc][0].get("status", "?"))
            if fc in by else "not run" for fc in cols) + " |")
        md.append("")
    with open(os.path.join(a.results, "contact_comparison%s.md" % suffix), "w") as f:
        f.write("\n".join(md))
    print("wrote %s and its .csv" % os.path.join(a.results, "contact_comparison%s.md" % suffix))
    return 0


if __name__ == "__main__":
    sys.exit(main())
