"""Most common (diff, old, march, secant, scan, probe, shallow) per pixel class. Usage: modes.py old.npz new.npz tagged.npz case [class]"""
import sys, numpy as np, collections
o=np.load(sys.argv[1]); m=np.load(sys.argv[2]); n=np.load(sys.argv[3]); c=sys.argv[4]; cl=sys.argv[5] if len(sys.argv)>5 else 'hit'
k=c+'.steps'; t=n[k].astype(np.int64); ho=np.isfinite(o[c+'.depth']); hn=np.isfinite(m[c+'.depth'])
mask={'hit':ho&hn,'oldonly':ho&~hn,'miss':~ho&~hn}[cl]
d=m[k].astype(int)-o[k]; cnt=collections.Counter(); ex=collections.Counter()
for y,x in zip(*np.nonzero(mask)):
    v=t[y,x]; key=(int(d[y,x]), int(o[k][y,x]), v%100, v//100%10, v//1000%100, v//100000%10, v//1000000); cnt[key]+=1; ex[key]+=int(d[y,x])
print(c, cl, 'pixels', int(mask.sum()), 'extra', int(d[mask].sum()))
for kk,vv in sorted(cnt.items(), key=lambda kv:-abs(ex[kv[0]]))[:10]: print('  diff,old,march,sec,scan,probe,shallow',kk,vv,'extra',ex[kk])
