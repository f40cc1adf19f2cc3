"""What any choice of polynomial order in T could reach on the CATS folds, beside thermonav's rule.

Reads the work folder and the results JSON that bench/thermal_peers.sh printed (its banks hold
each fold's training blocks) and, per (fold, channel), refits b(T) of every fixed order 0..3 in
numpy on the same blocks (one offset per power-on), predicts the held-out leg's 30 s block means
(clamped to the training range) and scores the shape RMS as the bench does. Prints per pair the
fixed orders, a stacked average of them (non-negative weights summing to 1, on a 0.05 grid,
minimising the folds' held-out error: Breiman 1996, "Stacked regressions"), and counts: pairs
within 1.05x the better peer, and pairs no worse than 1.1x uncompensated. "oracle" picks, per
pair, the fixed order that does best on the held-out leg itself: a bound no rule can pass.
Usage: python3 bench/thermal_peers/order_bound.py WORK_FOLDER RESULTS.json
"""
import json, os, sys
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cats
W = sys.argv[1]
res = json.load(open(sys.argv[2]))
data = cats.load()
SCALE = {'g': 180/np.pi*3600, 'a': 1000/9.80665}
def design(T, po, order, ref, pos):
    cols = [(po == p).astype(float) for p in pos]
    for k in range(1, order+1): cols.append((T-ref)**k)
    return np.column_stack(cols)
def fit(T, po, y, order, ref, pos):
    X = design(T, po, order, ref, pos)
    beta, *_ = np.linalg.lstsq(X, y, rcond=None)
    return beta
def curve(beta, T, order, ref, npo):
    return sum(beta[npo+k-1]*(T-ref)**k for k in range(1, order+1)) if order else 0*T
out = []
for row in res['rows']:
    fid, ch = row['fold_id'], row['channel']
    bank = json.load(open(f'{W}/{fid}/thermonav/bank.json'))
    bl = [b for b in bank['thermal']['sweep_blocks'] if ch in b['values']]
    T = np.array([b['temperature_c'] for b in bl]); y = np.array([b['values'][ch] for b in bl])
    po = np.array([b['power_on'] for b in bl]); leg = np.array([b['leg'] for b in bl])
    pos = sorted(set(po)); ref = (T.min()+T.max())/2
    sel = bank['thermal']['channels'][ch]['selection']
    if sel['rule'] == 'leave_one_leg_out':
        folds = leg; about_offset = False
    else:
        order_idx = np.lexsort((np.array([b['t_s'] for b in bl]), po))
        folds = np.empty(len(bl), int); folds[order_idx] = (np.arange(len(bl))*5)//len(bl); about_offset = True
    # held-out predictions per candidate
    P = {o: np.full(len(bl), np.nan) for o in range(4)}
    for f in np.unique(folds):
        tr = folds != f; te = ~tr
        lo, hi = T[tr].min(), T[tr].max(); te &= (T >= lo) & (T <= hi)
        if te.sum() < 2: continue
        for o in range(4):
            if tr.sum() <= o + len(pos): continue
            beta = fit(T[tr], po[tr], y[tr], o, ref, pos)
            off = np.array([beta[pos.index(p)] if p in po[tr] else np.nan for p in po[te]])
            P[o][te] = curve(beta, T[te], o, ref, len(pos)) + off
    ok = np.all([~np.isnan(P[o]) for o in range(4)], axis=0)
    # residual targets: for LOLO, compare shapes (remove fold mean of residual) -> stack on centred per fold
    Z = np.column_stack([P[o][ok] for o in range(4)]); yy = y[ok]; ff = folds[ok]
    if not about_offset:
        for f in np.unique(ff):
            m = ff == f
            Z[m] -= Z[m].mean(0); 
            yy = yy.copy(); yy[m] -= yy[m].mean()
    # non-negative weights summing to 1: simple projected search over simplex grid
    best = None
    for w0 in np.arange(0, 1.01, 0.05):
        for w1 in np.arange(0, 1.01 - w0, 0.05):
            for w2 in np.arange(0, 1.01 - w0 - w1, 0.05):
                w = np.array([w0, w1, w2, 1 - w0 - w1 - w2])
                e = np.mean((yy - Z @ w)**2)
                if best is None or e < best[0]: best = (e, w)
    w = best[1]
    # fit all, predict held-out leg
    betas = [fit(T, po, y, o, ref, pos) for o in range(4)]
    ht = row['held_t_s']
    m = (data['t_s'] >= ht[0]) & (data['t_s'] <= ht[1])
    idx = np.flatnonzero(m); n = len(idx)//30; idx = idx[:n*30]
    Th = data['temp_c'][idx].reshape(n,30).mean(1); yh = data[ch][idx].reshape(n,30).mean(1)
    Th = np.clip(Th, T.min(), T.max())
    preds = [curve(betas[o], Th, o, ref, len(pos)) for o in range(4)]
    stacked = sum(w[o]*preds[o] for o in range(4))
    ch_order = sel['best_in_temperature_alone']['order']
    def shape(p): d = yh - p; d = d - d.mean(); return np.sqrt(np.mean(d**2)) * SCALE[ch[0]]
    best_peer = min(row['px4'], row['ardupilot'])
    out.append((fid, ch, row['uncompensated'], best_peer, row['thermonav'], shape(preds[ch_order]), shape(stacked), w, [shape(p) for p in preds]))
def count(k):
    return sum(r[k] <= 1.05*r[3] for r in out), sum(r[k] <= 1.1*r[2] for r in out)
for r in out:
    print(f"{r[0]:11s} {r[1]} un={r[2]:7.2f} peer={r[3]:7.2f} tn={r[4]:7.2f} py_choice={r[5]:7.2f} stack={r[6]:7.2f} w={np.round(r[7],2)} fixed={np.round(r[8],2)}")
print("pairs (within 1.05x better peer, within 1.1x uncompensated): thermonav %s, numpy refit of its T-only choice %s, stacked %s" % (tuple(map(int, count(4))), tuple(map(int, count(5))), tuple(map(int, count(6)))))
for o in range(4): print("fixed order", o, int(sum(r[8][o] <= 1.05*r[3] for r in out)), int(sum(r[8][o] <= 1.1*r[2] for r in out)))
both = sum(any(r[8][o] <= 1.05*r[3] and r[8][o] <= 1.1*r[2] for o in range(4)) for r in out)
print('oracle order choice (T only) meeting both in', both, 'of', len(out))
print('oracle peer-ok', sum(any(r[8][o] <= 1.05*r[3] for o in range(4)) for r in out))
