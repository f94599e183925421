#!/usr/bin/env python3
# Every law at rest (issue 52 item 1), through scene files: each kind alone on a still table for 10 s,
# at `rigid` and `full`, under every scene contact law, started touching (the default) and settled
# (contact.start "settled"). Reported: the slide of the centre of gravity from t = 0 and the largest
# nodal speed at the end (final_state.json), against the bounds (0.1 mm, 1 mm/s), and for a
# settled start the simulated time it took (summary.json settled_start).
#
#   python3 scripts/rest_check.py build/examples/furniture_quake [--jobs 2] [--out docs/contact/rest_check.md]
#
# Scenes and results in $FFEM_REST_OUT (default /tmp/ffem_rest).
import argparse, concurrent.futures as cf, csv, json, os, subprocess, sys, time

OUT = os.environ.get('FFEM_REST_OUT', '/tmp/ffem_rest')
KINDS = ['locker', 'tall_cabinet', 'desk', 'table', 'side_table', 'office_chair', 'block']
LAWS = ['paper', 'paper_anisotropic', 'spring_dashpot', 'hunt_crossley', 'stick_slip', 'stiff']
BLOCK = {'width': 0.4, 'depth': 0.2, 'height': 0.8, 'mass_kg': 50.0}
SLIDE_MM, SPEED_MM_S = 0.1, 1.0  # issue 52's bounds


def run(binary, kind, fid, law, start):
    tag = f"{kind}_{fid}_{law}_{start}"
    params = BLOCK if kind == 'block' else {}
    sc = {"name": tag, "items": [{"kind": kind, "name": "it", "fidelity": fid, "params": params}],
          "ground_motion": {"source": "points", "x": [[0, 0], [20, 0]]}, "duration": 10.0, "dt": 0.001,
          "contact": {"law": law, "start": start}, "outputs": {"figures": False}}
    path = os.path.join(OUT, tag + '.json')
    json.dump(sc, open(path, 'w'))
    p = subprocess.run([binary, path, '--out', path[:-5], '--overwrite', '--quiet', '--no-figures'],
                       capture_output=True, text=True)
    if p.returncode not in (0, 3):
        return {'kind': kind, 'fidelity': fid, 'law': law, 'start': start, 'status': f"exit {p.returncode}"}
    summ = json.load(open(path[:-5] + '/summary.json'))
    item = summ['final_state'][0]
    settled = summ.get('settled_start') or {}
    return {'kind': kind, 'fidelity': fid, 'law': law, 'start': start, 'status': summ['status'],
            'slide_mm': 1e3 * item['slide_m'], 'speed_mm_s': 1e3 * item['max_node_speed_m_s'],
            'tilt_deg': item['tilt_deg'], 'settling_s': settled.get('settling_time_s'),
            'wall_s': summ['wall_seconds']}


def cell(r):
    if r['status'] != 'completed': return r['status']
    ok = r['slide_mm'] <= SLIDE_MM and r['speed_mm_s'] <= SPEED_MM_S
    s = f"{r['slide_mm']:.2g}, {r['speed_mm_s']:.2g}"
    if r['settling_s'] is not None: s += f" ({r['settling_s']:.2f} s)"
    return s if ok else f"**{s}**"


def table(rows, command, wall):
    by = {(r['kind'], r['fidelity'], r['law'], r['start']): r for r in rows}
    lines = [f"# Every law at rest, 10 s (generated)\n",
             f"Written by `{command}` in {wall:.0f} s of wall time. Each cell: the slide of the centre of gravity "
             f"from t = 0 (mm) and the largest nodal speed at the end (mm/s); in bold where either is past issue 52's "
             f"bounds ({SLIDE_MM} mm, {SPEED_MM_S} mm/s); for a settled start (`contact.start` `settled`) the "
             f"simulated time it settled in. How to read it: docs/contact/verification_contact.md, \"A settled start\".\n"]
    for fid in ('rigid', 'full'):
        for start in ('touching', 'settled'):
            lines += [f"\n### {fid}, started {start}\n", "| kind | " + " | ".join(LAWS) + " |", "|---|" + "---|" * len(LAWS)]
            for kind in KINDS:
                cells = [cell(by[k]) if (k := (kind, fid, law, start)) in by else '' for law in LAWS]
                if any(cells): lines.append(f"| {kind} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


if __name__ == '__main__':
    ap = argparse.ArgumentParser()
    ap.add_argument('binary')
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--out', default='docs/contact/rest_check.md')
    a = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    binary = os.path.abspath(a.binary)
    jobs = [(k, f, l, s) for k in KINDS for f in ('rigid', 'full') for l in LAWS for s in ('touching', 'settled')
            if not (k == 'block' and f == 'full')]  # a block is rigid only
    started = time.time()
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        rows = list(ex.map(lambda j: run(binary, *j), jobs))
    wall = time.time() - started
    command = "python3 scripts/rest_check.py build/examples/furniture_quake --jobs " + str(a.jobs)
    open(a.out, 'w').write(table(rows, command, wall))
    with open(a.out[:-3] + '.csv', 'w', newline='') as f:
        w = csv.DictWriter(f, fieldnames=['kind', 'fidelity', 'law', 'start', 'status', 'slide_mm', 'speed_mm_s',
                                          'tilt_deg', 'settling_s', 'wall_s'])
        w.writeheader()
        w.writerows(rows)
    print(f"{len(rows)} runs in {wall:.0f} s: {a.out}")
