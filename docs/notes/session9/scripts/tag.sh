#!/bin/bash
# tag.sh SRC DST: copy a tree and make its steps output tag the kind of each map() call
rm -rf $2 && cp -r $1 $2 && cd $2 && python3 - <<'PY'
p='shaders/march_relaxed.glsl'; s=open(p).read()
old="""        steps++;
        float s = 0.0;"""
assert old in s
s=s.replace(old,"""        steps += settling == 0 ? 1 : (S.scan > 0 ? 1000 : (S.fb >= UNSAMPLED ? (settling == 3 ? 1000000 : 100000) : 100));
        float s = 0.0;""")
open(p,'w').write(s)
PY
