import sys, math, bisect
rec = sys.argv[1]; lat = float(sys.argv[2]) * 1e6 if len(sys.argv) > 2 else 11.111111e6
P = []; F = []; D = []
for line in open(rec):
    f = line.split()
    if not f: continue
    if f[0] == 'P':
        t = int(f[1]); valid = int(f[3]) & 1
        j = 10; base = 4 + j * 8
        P.append((t, valid, (float(f[base]), float(f[base+1]), float(f[base+2]))))
    elif f[0] == 'F':
        F.append((int(f[2]), int(f[3]), int(f[4])))
    elif f[0] == 'D':
        cnt = int(f[3]); tips = [tuple(map(float, f[4+3*k:7+3*k])) for k in range(cnt)]
        D.append((int(f[1]), int(f[2]), tips))
PT = [p[0] for p in P]
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def norm(a): return math.sqrt(sum(x * x for x in a))
def lerp(a, b, s): return tuple(x + (y - x) * s for x, y in zip(a, b))
def felt(h, newest):
    n = bisect.bisect_right(PT, newest) - 1
    if n < 1: return None, 'none'
    if h <= PT[n]:
        i = bisect.bisect_right(PT, h) - 1
        if i < 0: return P[0][2], 'old'
        if i >= n: return P[n][2], 'at'
        s = (h - PT[i]) / (PT[i+1] - PT[i]); return lerp(P[i][2], P[i+1][2], s), 'interp'
    span = PT[n] - PT[n-1]
    interval = (PT[n] - PT[max(0, n-8)]) / min(8, n)
    horizon = min(100e6, 2 * interval + 20e6)
    ahead = min(h - PT[n], horizon)
    return lerp(P[n-1][2], P[n][2], 1 + ahead / span), 'extrap %.1fms%s' % ((h - PT[n]) / 1e6, ' CAPPED' if h - PT[n] > horizon else '')
# stops by the meter's anchor rule on the input
anchor = None; moving = False; stops = []
for k, (t, v, p) in enumerate(P):
    if not v: continue
    for s in stops:
        if not s['left']:
            if norm(sub(p, s['rest'])) > 20e-6: s['left'] = True
            else: s['restEnd'] = t
    if anchor is None or norm(sub(p, anchor[1])) > 20e-6: anchor = (t, p)
    if moving and t - anchor[0] >= 100e6:
        moving = False; stops.append({'hand': anchor[0], 'rest': anchor[1], 'restEnd': t, 'left': False, 'known_at': t})
    else:
        # moving: along-surface (x,z) motion > 100 um over 10 ms
        i = bisect.bisect_right(PT, t - 10e6) - 1
        if i >= 0:
            d = sub(p, P[i][2]); 
            if math.hypot(d[0], d[2]) > 100e-6: moving = True
for s in stops:
    disp = next((d for d in D if d[1] >= s['hand']), None)
    if not disp: continue
    s['display'] = disp[0]
    worst = None
    for (t, newest, h) in F:
        fn = t + lat
        if fn < disp[0]: continue
        if fn - disp[0] > 300e6 or h > s['restEnd']: break
        tip, how = felt(h, newest)
        if tip is None: continue
        away = math.hypot(tip[0] - s['rest'][0], tip[2] - s['rest'][2])
        if away > 50e-6:
            print('  stop@%.3fs tick felt +%.1fms hand +%.1fms away %.1fum (%s) newest age %.1fms' % ((s['hand'] - P[0][0]) / 1e9, (fn - disp[0]) / 1e6, (h - s['hand']) / 1e6, away * 1e6, how, (t - newest) / 1e6))
    print('stop at %.3f s rest x=%.6f restEnd +%.1f ms left=%s display +%.1f ms' % ((s['hand'] - P[0][0]) / 1e9, s['rest'][0], (s['restEnd'] - s['hand']) / 1e6, s['left'], (disp[0] - s['hand']) / 1e6))
# detail for ticks away: the two newest poses
for s in stops:
    if 'display' not in s: continue
    for (t, newest, h) in F:
        fn = t + lat
        if fn < s['display']: continue
        if fn - s['display'] > 300e6 or h > s['restEnd']: break
        tip, how = felt(h, newest)
        if tip is None: continue
        away = math.hypot(tip[0] - s['rest'][0], tip[2] - s['rest'][2])
        if away > 50e-6:
            n = bisect.bisect_right(PT, newest) - 1
            for k in range(n - 3, n + 2):
                print('   P[%d] t=%+.3fms x=%.7f y=%.7f %s' % (k, (PT[k] - h) / 1e6, P[k][2][0], P[k][2][1], '<- newest' if k == n else ''))
