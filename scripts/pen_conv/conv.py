# pen-conv3: convergence table of the converging form (fixed AV length
# 0.65 um + contact_offset dx1/2) from pc_run's CSV histories (t after
# contact [ns], tip depth P [um]; with sc=1 no shift is needed).
# usage: python3 conv.py [tag:dx_um ...]   (default: the q11-q13 runs)
import csv, math, sys

def load(tag):
    rows = [r for r in csv.reader(open('h_' + tag + '.csv')) if len(r) == 5][1:]
    return [float(r[0]) for r in rows], [float(r[1]) for r in rows]

def at(h, t):
    ts, ps = h
    for k in range(1, len(ts)):
        if ts[k - 1] <= t <= ts[k]:
            w = (t - ts[k - 1]) / (ts[k] - ts[k - 1])
            return ps[k - 1] + w * (ps[k] - ps[k - 1])
    return float('nan')

def gap(a, b):
    """max |P_a(t) - P_b(t)| over the common span / P_max(b): the case's history_gap"""
    worst = 0.0
    for t, p in zip(*a):
        q = at(b, t)
        if q == q:
            worst = max(worst, abs(p - q))
    return worst / max(b[1])

def richardson(h, f):
    """f = f_inf + C h^p through three points (pen_richardson's formula)"""
    d01, d12 = f[0] - f[1], f[1] - f[2]
    if d01 * d12 <= 0:
        return None
    ratio = lambda p: (h[0]**p - h[1]**p) / (h[1]**p - h[2]**p)
    lo, hi = 0.05, 20.0
    tgt = d01 / d12
    if not (ratio(lo) < tgt < ratio(hi)):
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ratio(mid) < tgt else (lo, mid)
    p = 0.5 * (lo + hi)
    C = d12 / (h[1]**p - h[2]**p)
    return p, f[2] - C * h[2]**p

levels = [a.split(':') for a in sys.argv[1:]] or \
    [('sc_L_10', '0.75'), ('sc_L_15', '0.5'), ('sc_L_20', '0.375'), ('sc_L_25', '0.3')]
H = []
for tag, dx in levels:
    try:
        H.append((tag, float(dx), load(tag)))
    except OSError:
        pass
print('| dx1 | P(25) | P(50) | P(100) | P(200) | P_max | t(P_max) | change of P_max | P(t) gap to next |')
print('|---|---|---|---|---|---|---|---|---|')
for k, (tag, dx, h) in enumerate(H):
    i = max(range(len(h[1])), key=lambda j: h[1][j])
    ch = '' if k == 0 else '%+.2f um (%+.2f %%)' % (h[1][i] - max(H[k-1][2][1]), 100 * (h[1][i] / max(H[k-1][2][1]) - 1))
    g = '%.4f' % gap(h, H[k+1][2]) if k + 1 < len(H) else ''
    print('| %s (%.4g um, d/%.1f) | %s | %.2f | %.0f ns | %s | %s |' % (tag, dx, 7.38 / dx,
          ' | '.join('%.2f' % at(h, t) for t in (25, 50, 100, 200)), h[1][i], h[0][i], ch, g))
for q, name in ((None, 'P_max'), (25, 'P(25 ns)'), (50, 'P(50 ns)'), (100, 'P(100 ns)'), (200, 'P(200 ns)')):
    for k in range(len(H) - 2):
        trip = H[k:k+3]
        f = [max(x[2][1]) if q is None else at(x[2], q) for x in trip]
        r = richardson([x[1] for x in trip], f)
        lab = '/'.join('d/%.0f' % (7.38 / x[1]) for x in trip)
        if r:
            print('%s %s: order %.2f, limit %.2f um (finest %.1f %% short)' % (name, lab, r[0], r[1], 100 * (1 - f[2] / r[1])))
        else:
            print('%s %s: no Richardson estimate (%s)' % (name, lab, ' '.join('%.3f' % x for x in f)))
