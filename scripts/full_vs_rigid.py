#!/usr/bin/env python3
# Full against rigid, measured through scene files (issue 52 item 4): for each kind, at `full` and
# `rigid`, under `stiff` and `paper` (at `full` the paper's law both with the default `implicit`, all:
# every item's floor contact inside the step, and with "rigid": the paper's explicit contact for its FE
# items, as its reproductions run), the same five checks:
#   rest    gravity alone, 10 s: slide of the centre of gravity and the largest nodal speed at the end;
#   ramp    table acceleration along Y rising at 1 m/s^2 per s: the acceleration at which a base edge
#           first lifts 1 mm (the quasi-static onset of rocking, g b/h for a rigid block);
#   hold    a slower ramp (HOLD_RAMP_RATE) up to a level, then the level held HOLD_S: the least level that overturns, by
#           bisection (the quasi-static threshold, g b/h for a rigid block: the ramp's onset without a lift to
#           define it, which at `full` also counts the base's partial uplift before the body rocks);
#   sudden  a constant acceleration along Y applied within 1 ms and held 3 s: the least that overturns
#           (largest tilt past OVERTURN_DEG), by bisection;
#   pulse   a rectangular pulse along Y of PULSE_S: the least amplitude that overturns (Housner's
#           threshold for a rigid block), by bisection;
#   slide   harmonic table motion along X, eta mu g sin(2 pi t), eta 2 and 3: the peak-to-peak slide
#           over the last of 4 periods against an exact 1-DOF Coulomb block (scripts/harmonic_sliding.py).
# Friction: mu 1.0 for ramp, sudden and pulse (the items tip, not slide); 0.5 for slide, 0.2 for the tall
# kinds (at eta 3 and mu 0.5 the table would pull them with up to 0.5 g, near their tipping threshold
# along X; at mu 0.2 at most 0.2 g, far below it).
#
#   python3 scripts/full_vs_rigid.py build/examples/furniture_quake [--jobs 2] [--kinds locker,table]
#       [--checks rest,ramp,hold,sudden,pulse,slide] [--configs "rigid stiff,full stiff"]
#       [--out docs/contact/full_vs_rigid.md] [--frame-drift RAD]
#   python3 scripts/full_vs_rigid.py --table-from docs/contact/full_vs_rigid.csv --checks rest,ramp,slide
#       (the table again from a run's CSV, without running)
#
# Writes the table (markdown, and the CSV beside it); scenes and results in $FFEM_MATRIX_OUT (default
# /tmp/ffem_matrix). The block (rigid only) carries its closed forms: g b/h for ramp and sudden.
# --frame-drift RAD sets every scene's integrator.frame_drift_refresh (without it: the scene default, 5e-4).
import argparse, concurrent.futures as cf, csv, json, math, os, subprocess, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harmonic_sliding

G = 9.80665
SETTLE = 0.3
# Overturned: tilted past the outputs' "overturned" tilt (scene/run_summary.hpp, 60 deg). Not 20 deg: the
# squat kinds tilt further than that and come back (a rigid side table up to 50 deg under a 0.25 s pulse).
OVERTURN_DEG = 60.0
PULSE_S = 0.25
RAMP_RATE = 1.0  # m/s^2 per s: the ramp of `ramp`
# `hold`'s ramp is slower: near its threshold a full item's base uplifts along an equilibrium path whose
# stiffness falls to zero, so at 1 m/s^2 per s a full locker tipped at 2.694 m/s^2 that holds at 2.705
# when ramped at 0.25 (held 6 s). A rigid item has no such path: its threshold is the same at either rate.
HOLD_RAMP_RATE = 0.25
# A level 0.3 % above a rigid locker's threshold has lifted its heel 0.3 m (past tipping) 2.8 s after the
# level is reached (measured; the tilt grows as cosh(lambda t)), so 6 s of hold resolve the bisection.
HOLD_S = 6.0
OUT = os.environ.get('FFEM_MATRIX_OUT', '/tmp/ffem_matrix')
FRAME_DRIFT = None  # integrator.frame_drift_refresh of every scene (--frame-drift); None: the scene's
# kind: (outer depth D along Y, extra params); the block is 0.4 wide, 0.2 deep, 0.8 tall, 50 kg.
KINDS = {
    'locker': (0.515, {}), 'tall_cabinet': (0.4, {}), 'desk': (0.7, {}), 'table': (0.75, {}),
    'side_table': (0.34, {}), 'office_chair': (0.52, {}),
    'block': (0.2, {'width': 0.4, 'depth': 0.2, 'height': 0.8, 'mass_kg': 50.0}),
}
TALL = {'locker', 'tall_cabinet', 'block'}
# (fidelity, law, implicit) columns; None: the default (every item inside the step).
CONFIGS = [('rigid', 'stiff', None), ('full', 'stiff', None), ('rigid', 'paper', None),
           ('full', 'paper', None), ('full', 'paper', 'rigid')]


def config_name(fid, law, implicit):
    return f"{fid} {law}" + (f" implicit {implicit}" if implicit else "")


def scene(kind, fid, law, implicit, mu, motion, duration, markers):
    D, extra = KINDS[kind]
    params = dict(extra, mu_floor_long=mu, mu_floor_short=mu)
    contact = {"law": law}
    if implicit: contact["implicit"] = implicit
    sc = {"name": f"{kind} {fid} {law}", "items": [{"kind": kind, "name": "it", "fidelity": fid, "params": params}],
          "ground_motion": dict(source="points", **motion), "duration": duration, "dt": 0.001,
          "contact": contact, "outputs": {"figures": False, "markers": markers}}
    if FRAME_DRIFT is not None:
        sc["integrator"] = {"frame_drift_refresh": FRAME_DRIFT}
    return sc


def run(tag, sc):
    path = os.path.join(OUT, tag.replace(' ', '_') + '.json')
    od = path[:-5]
    json.dump(sc, open(path, 'w'))
    p = subprocess.run(sys_binary + [path, '--out', od, '--overwrite', '--quiet', '--no-figures'], capture_output=True, text=True)
    if p.returncode not in (0, 3):
        raise RuntimeError(f"{path}: exit {p.returncode}: {p.stderr.strip()[-400:]}")
    summ = json.load(open(od + '/summary.json'))
    state = json.load(open(od + '/final_state.json'))
    item = state[0]  # final_state.json: one entry per body
    return od, summ, item


def overturns(tag, sc):
    """True, False, or None (the run stopped before it showed either). A run that stopped after the item
    tilted past OVERTURN_DEG (a tumbling body's contact creating energy: the energy check's "diverged") has
    overturned: 'stopped' counts as True and is reported beside the threshold."""
    _, summ, item = run(tag, sc)
    if summ['status'] != 'completed':
        return 'stopped' if item['max_tilt_deg'] > OVERTURN_DEG else None
    return item['max_tilt_deg'] > OVERTURN_DEG


def threshold(make, lo, hi, iterations, tag):
    """Least amplitude that overturns: the bracket widened until lo holds and hi tips, then bisected."""
    runs, stopped = 0, 0

    def tips(a):
        nonlocal runs, stopped
        r = overturns(f"{tag}_{a:.5f}", make(a)); runs += 1
        stopped += r == 'stopped'
        return r

    for _ in range(8):
        r = tips(lo)
        if r is None: return None, runs, stopped
        if not r: break
        lo *= 0.8
    for _ in range(8):
        r = tips(hi)
        if r is None: return None, runs, stopped
        if r: break
        hi *= 1.25
    else:
        return math.inf, runs, stopped
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        r = tips(mid)
        if r is None: return None, runs, stopped
        if r: hi = mid
        else: lo = mid
    return 0.5 * (lo + hi), runs, stopped


def check_rest(kind, fid, law, implicit):
    sc = scene(kind, fid, law, implicit, 0.5, {"x": [[0, 0], [10, 0]]}, 10.0, [])
    _, summ, item = run(f"rest_{kind}_{fid}_{law}_{implicit}", sc)
    return {'rest_slide_mm': 1e3 * item['slide_m'], 'rest_speed_mm_s': 1e3 * item['max_node_speed_m_s'],
            'rest_wall_s': summ['wall_seconds']}


def check_ramp(kind, fid, law, implicit):
    D, _ = KINDS[kind]
    rate, top = RAMP_RATE, 1.2 * G
    t_end = SETTLE + top / rate
    motion = {"x": [[0, 0]], "y": [[0, 0], [SETTLE, 0], [t_end, top]]}
    markers = [{"name": "front", "item": "it", "point": [0, -D / 2, 0]}, {"name": "back", "item": "it", "point": [0, D / 2, 0]}]
    od, summ, item = run(f"ramp_{kind}_{fid}_{law}_{implicit}", scene(kind, fid, law, implicit, 1.0, motion, t_end, markers))
    rows = list(csv.DictReader(open(od + '/markers.csv')))
    z0 = {m: float(rows[0][f'{m}_z']) for m in ('front', 'back')}
    for r in rows:
        t = float(r['t'])
        if t > SETTLE and max(float(r[f'{m}_z']) - z0[m] for m in z0) > 1e-3:
            return {'ramp_onset': rate * (t - SETTLE)}
    return {'ramp_onset': math.inf}


def check_hold(kind, fid, law, implicit, guess):
    def make(a):
        t_level = SETTLE + a / HOLD_RAMP_RATE
        return scene(kind, fid, law, implicit, 1.0, {"x": [[0, 0]], "y": [[0, 0], [SETTLE, 0], [t_level, a], [t_level + HOLD_S, a]]},
                     t_level + HOLD_S, [])
    lo, hi, it = (0.05 * G, 1.5 * G, 10) if guess is None else (0.9 * guess, 1.1 * guess, 6)
    a, runs, stopped = threshold(make, lo, hi, it, f"hold_{kind}_{fid}_{law}_{implicit}")
    return {'hold': a, 'hold_runs': runs, 'hold_stopped': stopped}


def check_sudden(kind, fid, law, implicit, guess):
    def make(a):
        return scene(kind, fid, law, implicit, 1.0, {"x": [[0, 0]], "y": [[0, 0], [SETTLE, 0], [SETTLE + 1e-3, a], [SETTLE + 3.0, a]]},
                     SETTLE + 3.0, [])
    lo, hi, it = (0.05 * G, 1.5 * G, 10) if guess is None else (0.9 * guess, 1.1 * guess, 6)
    a, runs, stopped = threshold(make, lo, hi, it, f"sudden_{kind}_{fid}_{law}_{implicit}")
    return {'sudden': a, 'sudden_runs': runs, 'sudden_stopped': stopped}


def check_pulse(kind, fid, law, implicit, guess):
    def make(a):
        return scene(kind, fid, law, implicit, 1.0,
                     {"x": [[0, 0]], "y": [[0, 0], [SETTLE, 0], [SETTLE + 1e-3, a], [SETTLE + PULSE_S, a], [SETTLE + PULSE_S + 1e-3, 0]]},
                     SETTLE + PULSE_S + 3.0, [])
    lo, hi, it = (0.1 * G, 3.0 * G, 10) if guess is None else (0.9 * guess, 1.1 * guess, 6)
    a, runs, stopped = threshold(make, lo, hi, it, f"pulse_{kind}_{fid}_{law}_{implicit}")
    return {'pulse': a, 'pulse_runs': runs, 'pulse_stopped': stopped}


def check_slide(kind, fid, law, implicit):
    mu = 0.2 if kind in TALL else 0.5
    out = {}
    for eta in (2, 3):
        A = eta * mu * G; w = 2 * math.pi
        pts = [[0.0, 0.0], [SETTLE, 0.0]] + [[SETTLE + k * 0.002, A * math.sin(w * k * 0.002)] for k in range(1, int(4 / 0.002) + 2)]
        sc = scene(kind, fid, law, implicit, mu, {"x": pts}, SETTLE + 4.0, [{"name": "p", "item": "it", "point": [0, 0, 0.0]}])
        od, summ, item = run(f"slide{eta}_{kind}_{fid}_{law}_{implicit}", sc)
        rows = list(csv.DictReader(open(od + '/markers.csv')))
        xs = [float(r['p_x']) for r in rows if float(r['t']) >= SETTLE + 3.0 - 1e-9]
        exact = harmonic_sliding.coulomb_p2p(A, w, mu, 4)
        out[f'slide{eta}'] = (max(xs) - min(xs)) if summ['status'] == 'completed' else None
        out[f'slide{eta}_exact'] = exact
    return out


def measure(kind, fid, law, implicit, checks, guesses):
    t0 = time.time()
    r = {'kind': kind, 'config': config_name(fid, law, implicit)}
    if 'rest' in checks: r.update(check_rest(kind, fid, law, implicit))
    if 'ramp' in checks: r.update(check_ramp(kind, fid, law, implicit))
    if 'hold' in checks: r.update(check_hold(kind, fid, law, implicit, guesses.get('hold')))
    if 'sudden' in checks: r.update(check_sudden(kind, fid, law, implicit, guesses.get('sudden')))
    if 'pulse' in checks: r.update(check_pulse(kind, fid, law, implicit, guesses.get('pulse')))
    if 'slide' in checks: r.update(check_slide(kind, fid, law, implicit))
    r['wall_s'] = time.time() - t0
    print(f"{kind:13s} {r['config']:26s} done in {r['wall_s']:.0f} s", flush=True)
    return r


def fmt(x, spec='.3f'):
    if x is None: return 'diverged'
    if isinstance(x, float) and math.isinf(x): return 'none'
    return format(x, spec)


def rel(x, ref):
    if x is None or ref is None or math.isinf(x) or math.isinf(ref) or ref == 0: return ''
    return f" ({100 * (x / ref - 1):+.1f} %)"


def table(rows, checks, configs=CONFIGS):
    by = {(r['kind'], r['config']): r for r in rows}
    lines = []
    for kind in dict.fromkeys(r['kind'] for r in rows):
        lines += [f"\n### {kind}\n", "| configuration | " + " | ".join(
            {'rest': 'rest: slide mm, node mm/s', 'ramp': 'ramp onset m/s^2',
             'hold': f'ramp and hold {HOLD_S:g} s m/s^2', 'sudden': 'sudden load m/s^2',
             'pulse': f'pulse {PULSE_S} s m/s^2', 'slide': 'slide p-p eta 2 / eta 3, m (1-DOF)'}[c] for c in checks) + " |",
                  "|---|" + "---|" * len(checks)]
        for fid, law, implicit in configs:
            r = by.get((kind, config_name(fid, law, implicit)))
            if r is None: continue
            ref = by.get((kind, config_name('rigid', law, None)), {}) if fid == 'full' else {}
            cells = []
            for c in checks:
                if c == 'rest':
                    cells.append(f"{r['rest_slide_mm']:.2g} mm, {r['rest_speed_mm_s']:.2g} mm/s")
                elif c == 'slide':
                    cells.append(" / ".join(f"{fmt(r.get(f'slide{e}'), '.4f')}{rel(r.get(f'slide{e}'), r[f'slide{e}_exact'])}" for e in (2, 3))
                                 + f" ({r['slide2_exact']:.4f} / {r['slide3_exact']:.4f})")
                else:
                    key = {'ramp': 'ramp_onset'}.get(c, c)
                    cells.append(fmt(r.get(key)) + rel(r.get(key), ref.get(key))
                                 + (" *" if (r.get(f'{c}_stopped') or 0) > 0 else ""))
            lines.append(f"| {r['config']} | " + " | ".join(cells) + " |")
        if kind == 'block':
            D, ex = KINDS['block']
            lines.append(f"\nClosed form (rigid block, centre of gravity at H/2): ramp, hold and sudden load g b/h = {G * (D / 2) / (ex['height'] / 2):.3f} m/s^2.")
    return "\n".join(lines) + "\n"


if __name__ == '__main__':
    ap = argparse.ArgumentParser()
    ap.add_argument('binary', nargs='?')
    ap.add_argument('--table-from', help="a run's CSV: write its table again, without running")
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--kinds', default=','.join(KINDS))
    ap.add_argument('--checks', default='rest,ramp,sudden,pulse,slide')
    ap.add_argument('--out', default='docs/contact/full_vs_rigid.md')
    ap.add_argument('--configs', default=None, help='a comma-separated subset of the columns, e.g. "rigid stiff,full stiff"')
    ap.add_argument('--frame-drift', type=float, default=None, help='integrator.frame_drift_refresh of every scene (rad)')
    a = ap.parse_args()
    FRAME_DRIFT = a.frame_drift
    configs = CONFIGS
    if a.configs:
        names = [c.strip() for c in a.configs.split(',')]
        configs = [c for c in CONFIGS if config_name(*c) in names]
        if len(configs) != len(names):
            ap.error(f"--configs: {a.configs!r}: known columns are {', '.join(config_name(*c) for c in CONFIGS)}")
    if a.table_from:
        def number(v):
            try:
                return float(v)
            except ValueError:
                return v if v != '' else None
        rows = [{k: number(v) for k, v in r.items()} for r in csv.DictReader(open(a.table_from))]
        sys.stdout.write(table(rows, a.checks.split(','), configs))
        sys.exit(0)
    if not a.binary:
        ap.error('the furniture_quake binary is needed (or --table-from CSV)')
    sys_binary = [os.path.abspath(a.binary)]
    os.makedirs(OUT, exist_ok=True)
    checks = a.checks.split(',')
    kinds = a.kinds.split(',')
    rows = []
    started = time.time()
    # The rigid columns first: their thresholds bracket the full items' bisections.
    with cf.ProcessPoolExecutor(a.jobs) as pool:
        rigid = [(k, f, l, i) for k in kinds for f, l, i in configs if f == 'rigid']
        for r in pool.map(measure, *zip(*rigid), [checks] * len(rigid), [{}] * len(rigid)):
            rows.append(r)
        guess = {(r['kind'], r['config'].split()[1]): r for r in rows}
        full = [(k, f, l, i) for k in kinds if k != 'block' for f, l, i in configs if f == 'full']
        gs = [{c: guess[(k, l)].get(c) for c in ('hold', 'sudden', 'pulse') if guess[(k, l)].get(c) not in (None, math.inf)} for k, f, l, i in full]
        for r in pool.map(measure, *zip(*full), [checks] * len(full), gs):
            rows.append(r)
    keys = sorted({k for r in rows for k in r})
    with open(os.path.splitext(a.out)[0] + '.csv', 'w', newline='') as f:
        w = csv.DictWriter(f, keys); w.writeheader(); w.writerows(rows)
    with open(a.out, 'w') as f:
        f.write("# Full against rigid, measured (generated)\n\n"
                f"Written by `python3 scripts/full_vs_rigid.py {a.binary} --jobs {a.jobs} --kinds {a.kinds} --checks {a.checks}"
                + (f" --configs \"{a.configs}\"" if a.configs else "")
                + (f" --frame-drift {a.frame_drift:g}" if a.frame_drift is not None else "") + "` "
                f"in {time.time() - started:.0f} s of wall time; what each check is: the script's header. The percentages "
                "of a full row are against the rigid row of the same law; those of the slides against the exact 1-DOF "
                "Coulomb block. `none`: no overturn up to the bracket's top. `*`: at least one run of that bisection "
                "stopped (the energy check) after its item had tilted past 60 deg; it counts as overturned. How to read it: docs/contact/verification_contact.md, "
                "\"Full items against rigid ones, through scene files\".\n")
        f.write(table(rows, checks, configs))
    print(f"wrote {a.out}")
