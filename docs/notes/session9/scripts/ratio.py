"""Step cost: per case mean calls new/old, median over the cases both have. Usage: ratio.py old.npz new.npz [new2.npz]"""
import sys, numpy as np
o = np.load(sys.argv[1]); ns = [np.load(a) for a in sys.argv[2:]]
names = [k[:-6] for k in o.files if k.endswith(".steps") and all(k in n.files for n in ns)]
rs = [[] for _ in ns]
names = [c for c in names if o[c + ".steps"].mean() > 0]
for c in names:
    om = o[c + ".steps"].mean(); line = f"{c:22s} old {om:7.3f}"
    for i, n in enumerate(ns):
        m = n[c + ".steps"].mean(); rs[i].append(m / om); line += f"  {m:7.3f} ({m/om:5.3f})"
    print(line)
for i, r in enumerate(rs):
    print(sys.argv[2 + i], "median ratio", round(float(np.median(r)), 4), "over", len(r), "cases")
