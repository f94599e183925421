#!/usr/bin/env python3
# Harmonic sliding of one item through a scene file, against an exact 1-DOF Coulomb block (independent of
# the toolkit): python3 scripts/harmonic_sliding.py build/examples/furniture_quake KIND:FIDELITY:LAW:ETA ...
# e.g. table:full:stiff:2 table:rigid:stiff:2. Prints the peak-to-peak slide over the last of 4 periods at
# 1 Hz (mu 0.5, dt 1 ms), the 1-DOF value, the wall time and the factorisations. Scenes and results go to
# $FFEM_HARMONIC_OUT (default /tmp/ffem_harmonic). docs/contact/verification_contact.md, issue 52.

# The 1-DOF block: explicit steps of 1e-5 s with the stops caught inside a step (2e-6 s: the same to 2e-10).
import csv, json, math, os, subprocess, sys
g = 9.80665
def coulomb_p2p(A, w, mu, periods):
    dt = 1e-5; T = 2*math.pi/w; mug = mu*g; x = v = 0.0; lo, hi = 1e300, -1e300; stuck = True
    n = round(periods*T/dt)
    for i in range(n):
        t = i*dt; a = A*math.sin(w*(t + 0.5*dt))
        if stuck and abs(a) > mug: stuck = False
        if not stuck:
            d = (1.0 if v > 0 else -1.0) if v != 0 else (-1.0 if a > 0 else 1.0)
            v1 = v + (-a - mug*d)*dt
            if v != 0 and v1*v < 0:
                x += 0.5*v*(v/(v - v1))*dt; v = 0.0; stuck = abs(a) <= mug
            else:
                x += 0.5*(v + v1)*dt; v = v1
        if t >= (periods - 1)*T: lo, hi = min(lo, x), max(hi, x)
    return hi - lo
def run(binary, kind, fid, law, eta, mu=0.5, f=1.0, periods=4, settle=0.3, out=os.path.join(os.environ.get('FFEM_HARMONIC_OUT', '/tmp/ffem_harmonic'), 'h')):
    A = eta*mu*g; w = 2*math.pi*f
    pts = [[0.0, 0.0], [settle, 0.0]] + [[settle + k*0.002, A*math.sin(w*k*0.002)] for k in range(1, int(periods/f/0.002) + 2)]
    scene = {"name": "harmonic", "items": [{"kind": kind, "name": "it", "fidelity": fid,
             "params": {"mu_floor_long": mu, "mu_floor_short": mu}}],
             "ground_motion": {"source": "points", "x": pts}, "duration": settle + periods/f, "dt": 0.001,
             "contact": {"law": law}, "outputs": {"figures": False, "markers": [{"name": "p", "item": "it", "point": [0, 0, 0.0]}]}}
    sf = f"{out}_{kind}_{fid}_{law}_{eta}.json"; od = sf[:-5]
    json.dump(scene, open(sf, 'w'))
    subprocess.run([binary, sf, '--out', od, '--overwrite', '--quiet', '--no-figures'], check=True, capture_output=True)
    rows = list(csv.DictReader(open(od + '/markers.csv')))
    T0 = settle + (periods - 1)/f
    xs = [float(r['p_x']) for r in rows if float(r['t']) >= T0 - 1e-9]
    summ = json.load(open(od + '/summary.json'))
    return max(xs) - min(xs), coulomb_p2p(A, w, mu, periods), summ['wall_seconds'], summ['factorizations']
if __name__ == '__main__':
    binary = sys.argv[1]
    os.makedirs(os.environ.get('FFEM_HARMONIC_OUT', '/tmp/ffem_harmonic'), exist_ok=True)
    for kind, fid, law, eta in [tuple(a.split(':')) for a in sys.argv[2:]]:
        p2p, exact, wall, fac = run(binary, kind, fid, law, float(eta))
        print(f"{kind} {fid} {law} eta {eta}: peak-to-peak {p2p:.4f} m, exact 1-DOF {exact:.4f} m ({100*(p2p/exact-1):+.2f} %), {wall:.1f} s, {fac} factorisations", flush=True)
