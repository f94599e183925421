#!/usr/bin/env python3
# Why a full (finite-element) frame slides differently from its rigid twin under `stiff` (issue 52 item 4):
# the harmonic sliding case of scripts/full_vs_rigid.py (eta 2, 1 Hz, mu 0.5; mu 0.2 for tall kinds), run
# at `full` under variations of the time integration, each reporting over the last period:
#   p-p       peak-to-peak slide of the base centre (m) against the rigid item's and the exact 1-DOF's;
#   airborne  the share of steps whose floor force is zero (the whole item off the floor);
#   peak N/W  the largest floor force over the weight;
#   ledger    the energy ledger's imbalance at the end, relative to its scale (numerical dissipation shows
#             here: the paper's Newmark, gamma 5/6, damps what the items' contact excites).
#
#   python3 scripts/sliding_chatter.py build/examples/furniture_quake [--kinds desk,table,locker]
import argparse, csv, json, math, os, subprocess, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import full_vs_rigid as fvr
import harmonic_sliding

VARIANTS = [  # name, fidelity, scene changes
    ('rigid', 'rigid', {}),
    ('full, paper Newmark, dt 1 ms', 'full', {}),
    ('full, every step refactorised', 'full', {'refresh_every': 0.001}),
    ('full, dt 0.5 ms', 'full', {'dt': 5e-4}),
    ('full, dt 0.25 ms', 'full', {'dt': 2.5e-4}),
    ('full, average acceleration', 'full', {'integrator': {'scheme': 'average_acceleration'}}),
    ('full, generalized-alpha 0.5', 'full', {'integrator': {'scheme': 'generalized_alpha', 'rho_inf': 0.5}}),
    # Structural damping (integrator.stiffness_damping, s): a mode at f Hz is damped at pi f c of critical.
    ('full, stiffness damping 2e-4 s', 'full', {'integrator': {'stiffness_damping': 2e-4}}),
    ('full, stiffness damping 1e-3 s', 'full', {'integrator': {'stiffness_damping': 1e-3}}),
    ('full, stiffness damping 1e-3 s, dt 0.5 ms', 'full', {'integrator': {'stiffness_damping': 1e-3}, 'dt': 5e-4}),
    # A reused factorisation refreshed when a member's frame drifts from its body's rotation: 5e-4 rad is
    # the scene default (every variant above has it); 0 never refreshes on drift, as the paper's code.
    ('full, no frame drift refresh', 'full', {'integrator': {'frame_drift_refresh': 0.0}}),
    ('full, dt 0.1 ms', 'full', {'dt': 1e-4}),
    # The same 2 % structural damping at smaller steps: does the hopping frame's slide converge in dt?
    ('full, stiffness damping 2e-4 s, dt 0.25 ms', 'full', {'integrator': {'stiffness_damping': 2e-4}, 'dt': 2.5e-4}),
    ('full, stiffness damping 2e-4 s, dt 0.1 ms', 'full', {'integrator': {'stiffness_damping': 2e-4}, 'dt': 1e-4}),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('binary')
    ap.add_argument('--kinds', default='desk,table,locker')
    ap.add_argument('--variants', default='', help='|-separated prefixes of the variants to run (default: all)')
    ap.add_argument('--mu', type=float, default=None, help='friction coefficient (default 0.5; 0.2 for tall kinds)')
    ap.add_argument('--law', default='stiff', help='contact law (default stiff)')
    ap.add_argument('--floor-stiffness', type=float, default=None, help='contact.floor.stiffness (N/m per node)')
    ap.add_argument('--floor-damping', type=float, default=None, help='contact.floor.damping (N s/m per node)')
    a = ap.parse_args()
    os.makedirs(fvr.OUT, exist_ok=True)
    print('| kind | variant | p-p m | against rigid | airborne | peak N/W | ledger |')
    print('|---|---|---|---|---|---|---|')
    for kind in a.kinds.split(','):
        mu = a.mu if a.mu is not None else 0.2 if kind in fvr.TALL else 0.5
        A, w = 2 * mu * fvr.G, 2 * math.pi
        pts = [[0.0, 0.0], [fvr.SETTLE, 0.0]] + [[fvr.SETTLE + k * 0.002, A * math.sin(w * k * 0.002)]
                                                for k in range(1, int(4 / 0.002) + 2)]
        exact = harmonic_sliding.coulomb_p2p(A, w, mu, 4)
        rigid = None
        for name, fid, changes in VARIANTS:
            if a.variants and fid != 'rigid' and not any(name.startswith(v) for v in a.variants.split('|')):
                continue
            sc = fvr.scene(kind, fid, a.law, None, mu, {"x": pts}, fvr.SETTLE + 4.0,
                           [{"name": "p", "item": "it", "point": [0, 0, 0.0]}])
            floor = {k: v for k, v in (('stiffness', a.floor_stiffness), ('damping', a.floor_damping)) if v is not None}
            if floor: sc['contact']['floor'] = floor
            sc.update(changes)
            path = os.path.join(fvr.OUT, f"chatter_{kind}_{name.replace(' ', '_').replace(',', '')}.json")
            od = path[:-5]
            json.dump(sc, open(path, 'w'))
            p = subprocess.run([a.binary, path, '--out', od, '--overwrite', '--quiet', '--no-figures',
                                '--output-interval', str(sc.get('dt', 1e-3))], capture_output=True, text=True)
            if p.returncode not in (0, 3) or not os.path.isfile(od + '/summary.json'):
                print(f"| {kind} | {name} | failed (exit {p.returncode}) | | | | |", flush=True)
                continue
            summ = json.load(open(od + '/summary.json'))
            t0 = fvr.SETTLE + 3.0 - 1e-9
            xs = [float(r['p_x']) for r in csv.DictReader(open(od + '/markers.csv')) if float(r['t']) >= t0]
            fz = [float(r['it|floor_fz']) for r in csv.DictReader(open(od + '/contact_forces.csv')) if float(r['t']) >= t0]
            if summ['status'] != 'completed' or not xs:
                print(f"| {kind} | {name} | {summ['status']} at {summ.get('t_end_s', 0):.2f} s: {summ.get('diagnosis', '')[:80]} | | | | |",
                      flush=True)
                continue
            pp = max(xs) - min(xs)
            if fid == 'rigid':
                rigid = pp
                weight_rigid = sum(fz) / len(fz)
            W = weight_rigid
            vs = f"{100 * (pp / rigid - 1):+.1f} %" if rigid else ''
            status = '' if summ['status'] == 'completed' else f" ({summ['status']})"
            print(f"| {kind} | {name}{status} | {pp:.4f} (1-DOF {exact:.4f}) | {vs} | {sum(1 for f in fz if f <= 0) / len(fz):.2f} | "
                  f"{max(fz) / W:.1f} | {summ['energy_imbalance_relative']:+.3f} |", flush=True)


if __name__ == '__main__':
    main()
