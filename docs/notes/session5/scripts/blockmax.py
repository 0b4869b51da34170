"""Steps against SIMD-block cost: llvmpipe runs a block of pixels until its slowest ray ends.

    python blockmax.py old.npz new.npz [B]   (npz from t10a's hits.py: <case>.steps)
Prints per case: mean steps (old, new, ratio) and the sum over BxB blocks of the block's
max steps (old, new, ratio): the second ratio is what the frame time follows.
"""
import sys, numpy as np
a, b = np.load(sys.argv[1]), np.load(sys.argv[2])
B = int(sys.argv[3]) if len(sys.argv) > 3 else 4
def blocks(s):
    h, w = s.shape
    s = s[:h - h % B, :w - w % B].reshape(h // B, B, w // B, B)
    return s.max(axis=(1, 3)).sum() * B * B
for k in a.files:
    if not k.endswith(".steps") or k not in b.files:
        continue
    so, sn = a[k].astype(float), b[k].astype(float)
    print(f"{k[:-6]:>16}: mean {so.mean():6.2f} -> {sn.mean():6.2f} ({sn.mean() / so.mean():.3f}x)   "
          f"block-max {blocks(so) / so.size:6.2f} -> {blocks(sn) / sn.size:6.2f} ({blocks(sn) / blocks(so):.3f}x)")
