"""Hits gained/lost and depth change between two steps.py outputs. Usage: diffhits.py a.npz b.npz"""
import sys, numpy as np
a = np.load(sys.argv[1]); b = np.load(sys.argv[2])
for k in a.files:
    if not k.endswith(".depth") or k not in b.files: continue
    da, db = a[k], b[k]; ha, hb = np.isfinite(da), np.isfinite(db); both = ha & hb
    rel = np.abs(da[both] - db[both]) / np.maximum(da[both], 1e-30)
    print(f"{k[:-6]:18s} hits {int(ha.sum()):6d} -> {int(hb.sum()):6d} lost {int((ha & ~hb).sum())} gained {int((~ha & hb).sum())} "
          f"rel depth diff max {rel.max() if rel.size else 0:.2e} p99 {np.percentile(rel, 99) if rel.size else 0:.2e}")
