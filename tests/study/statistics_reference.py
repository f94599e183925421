#!/usr/bin/env python3
"""Independent reference values for tests/study/test_statistics.cpp (Python standard library only).

Written from the papers' formulas, not from statistics.hpp:
  - Wilson score interval without continuity correction (Newcombe 1998a, method 3);
  - Newcombe's (1998b) method 10 for paired proportions, with its phi adjustment;
  - type-7 quantiles through statistics.quantiles(method="inclusive") (numpy's default);
  - a lognormal-fragility maximum-likelihood fit by Nelder-Mead over (ln theta, ln beta).
Run: python3 tests/study/statistics_reference.py
"""
import math
import statistics

N = statistics.NormalDist()
Z95 = N.inv_cdf(0.975)  # 1.959963984540054


def wilson(x, n, z=Z95):
    p = x / n
    centre = (2 * n * p + z * z) / (2 * (n + z * z))
    half = z * math.sqrt(z * z + 4 * n * p * (1 - p)) / (2 * (n + z * z))
    return p, centre - half, centre + half


def newcombe10(e, f, g, h, z=Z95):
    """e = both, f = A only, g = B only, h = neither (Newcombe 1998b's notation)."""
    n = e + f + g + h
    a, l2, u2 = wilson(e + f, n, z)
    b, l3, u3 = wilson(e + g, n, z)
    denom = (e + f) * (g + h) * (e + g) * (f + h)
    num = e * h - f * g
    if num > n / 2:
        num -= n / 2
    elif num >= 0:
        num = 0
    phi = num / math.sqrt(denom) if denom > 0 else 0.0
    d = a - b
    dl2, du2, dl3, du3 = a - l2, u2 - a, b - l3, u3 - b
    lo = d - math.sqrt(dl2**2 - 2 * phi * dl2 * du3 + du3**2)
    hi = d + math.sqrt(du2**2 - 2 * phi * du2 * dl3 + dl3**2)
    return a, b, d, lo, hi


def type7(values):
    if len(values) == 1:  # statistics.quantiles needs two points; every type-7 quantile of one is that value
        return values * 5 + [values[0]]
    q = statistics.quantiles(values, n=100, method="inclusive")
    return min(values), q[15], q[49], q[83], max(values), statistics.fmean(values)


def neg_loglik(params, levels):
    ln_theta, ln_beta = params
    beta = math.exp(ln_beta)
    total = 0.0
    for im, n, f in levels:
        p = N.cdf((math.log(im) - ln_theta) / beta)
        p = min(max(p, 1e-300), 1 - 1e-16)
        total += math.lgamma(n + 1) - math.lgamma(f + 1) - math.lgamma(n - f + 1)
        total += f * math.log(p) + (n - f) * math.log(1 - p)
    return -total


def nelder_mead(fun, x0, step=0.3, tol=1e-14, iters=5000):
    pts = [list(x0), [x0[0] + step, x0[1]], [x0[0], x0[1] + step]]
    vals = [fun(p) for p in pts]
    for _ in range(iters):
        order = sorted(range(3), key=lambda i: vals[i])
        pts = [pts[i] for i in order]
        vals = [vals[i] for i in order]
        if abs(vals[2] - vals[0]) < tol and max(abs(pts[2][k] - pts[0][k]) for k in range(2)) < 1e-10:
            break
        c = [(pts[0][k] + pts[1][k]) / 2 for k in range(2)]
        r = [c[k] + (c[k] - pts[2][k]) for k in range(2)]
        fr = fun(r)
        if fr < vals[0]:
            e = [c[k] + 2 * (c[k] - pts[2][k]) for k in range(2)]
            fe = fun(e)
            pts[2], vals[2] = (e, fe) if fe < fr else (r, fr)
        elif fr < vals[1]:
            pts[2], vals[2] = r, fr
        else:
            k_ = [c[k] + 0.5 * (pts[2][k] - c[k]) for k in range(2)]
            fk = fun(k_)
            if fk < vals[2]:
                pts[2], vals[2] = k_, fk
            else:
                for i in (1, 2):
                    pts[i] = [pts[0][k] + 0.5 * (pts[i][k] - pts[0][k]) for k in range(2)]
                    vals[i] = fun(pts[i])
    i = min(range(3), key=lambda i: vals[i])
    return pts[i], vals[i]


if __name__ == "__main__":
    print("z95 =", repr(Z95))
    for x, n in [(81, 263), (15, 148), (0, 20), (1, 29)]:
        p, lo, hi = wilson(x, n)
        print(f"wilson {x}/{n}: lo {lo:.10f} hi {hi:.10f}")
    p, lo, hi = wilson(7, 40, N.inv_cdf(0.995))
    print(f"wilson 7/40 at 99%: lo {lo:.10f} hi {hi:.10f}")
    for t in [(59, 6, 16, 80), (36, 12, 2, 0), (3, 9, 1, 27), (0, 0, 4, 16), (1, 7, 2, 40)]:
        a, b, d, lo, hi = newcombe10(*t)
        print(f"newcombe10 {t}: d {d:.10f} lo {lo:.10f} hi {hi:.10f}")
    for v in [[3.0, 1.0, 2.0], [0.5, 2.5, -1.0, 4.0, 10.0, 7.5, 3.25], [42.0], [1.0, 1.0, 2.0, 9.0]]:
        print("type7", v, "->", ["%.12g" % t for t in type7(v)])
    levels = [(0.1, 20, 0), (0.2, 20, 2), (0.3, 20, 5), (0.4, 20, 9), (0.5, 20, 13), (0.6, 20, 14), (0.8, 20, 19)]
    (lt, lb), nll = nelder_mead(lambda x: neg_loglik(x, levels), [math.log(0.3), math.log(0.5)])
    print(f"fragility MLE: theta {math.exp(lt):.10f} beta {math.exp(lb):.10f} loglik {-nll:.10f}")
