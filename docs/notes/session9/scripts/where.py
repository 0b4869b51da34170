"""Extra calls new - old per pixel class (hit both, miss both, hit old only, hit new only). Usage: where.py old.npz new.npz"""
import sys, numpy as np
o = np.load(sys.argv[1]); n = np.load(sys.argv[2])
for k in o.files:
    if not k.endswith(".steps") or o[k].mean() == 0: continue
    c = k[:-6]; so, sn = o[k].astype(float), n[k].astype(float)
    ho, hn = np.isfinite(o[c + ".depth"]), np.isfinite(n[c + ".depth"])
    line = f"{c:18s} tot {sn.sum()-so.sum():7.0f} old {so.sum():7.0f}"
    for nm, m in (("hit", ho & hn), ("miss", ~ho & ~hn), ("oldonly", ho & ~hn), ("newonly", ~ho & hn)):
        line += f" | {nm} {int(m.sum()):5d} {sn[m].sum()-so[m].sum():+7.0f}"
    print(line)
