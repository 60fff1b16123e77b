# pen-conv3: limit of P_max(dx) for the converging form from the four levels
# (q11-q13): least-squares fit P = L - C dx^p over all four, two-level
# extrapolations of the finest pair at fixed p, and the fit's spread when
# every P_max is moved by up to +-0.3 um (the spread of equivalent runs:
# the step's phase at first contact, docs/validation.md)
import math, random
h = [0.75, 0.5, 0.375, 0.3]
f = [62.845, 66.896, 69.270, 70.988]   # q13 sc_L_10, q12 sc_L_15, sc_L_20, q11 sc_L_25

def fit(f, h=h):
    best = None
    for i in range(5, 400):
        p = i * 0.01
        x = [a ** p for a in h]; n = len(h)
        sx, sy = sum(x), sum(f); sxx = sum(a * a for a in x); sxy = sum(a * b for a, b in zip(x, f))
        C = (n * sxy - sx * sy) / (n * sxx - sx * sx); L = (sy - C * sx) / n
        res = sum((L + C * a - b) ** 2 for a, b in zip(x, f))
        if best is None or res < best[0]:
            best = (res, p, L)
    return best

res, p, L = fit(f)
print('least squares over d/10-d/25: order %.2f, limit %.2f um, rms %.3f um' % (p, L, math.sqrt(res / 4)))
for q in (0.5, 1.0, 2.0):
    r = h[2] / h[3]
    print('two-level d/20-d/25 at order %.1f: limit %.2f um' % (q, f[3] + (f[3] - f[2]) / (r ** q - 1)))
random.seed(1)
Ls = sorted(fit([a + random.uniform(-0.3, 0.3) for a in f])[2] for _ in range(400))
print('fit limit with +-0.3 um noise: 10/50/90 %% = %.1f / %.1f / %.1f um' % (Ls[40], Ls[200], Ls[360]))

# early P(t) with the fifth level, d/30 run to 120 ns only (q13 sc_L_30_t120)
h5 = h + [0.25]
for name, g in (('P(25 ns)', [20.437, 21.043, 21.378, 21.534, 21.643]),
                ('P(50 ns)', [33.099, 34.203, 34.865, 35.185, 35.407]),
                ('P(100 ns)', [49.013, 50.999, 52.108, 52.678, 53.102])):
    res, p, L = fit(g, h5)
    print('%s over d/10-d/30: order %.2f, limit %.2f um, rms %.3f um; d/30 %.1f %% short' %
          (name, p, L, math.sqrt(res / 5), 100 * (1 - g[4] / L)))
