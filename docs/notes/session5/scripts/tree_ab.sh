#!/bin/sh
# A/B frame medians across two trees, alternated: tree_ab.sh TREE_A TREE_B [scene] [WxH] [frames] [pairs]
# e.g. tree_ab.sh /tmp/old /work/wt/v10 demo 400x300 15 4   (PY: a python with sdfgl's deps)
A=$1; B=$2; S=${3:-demo}; Z=${4:-400x300}; F=${5:-15}; N=${6:-4}
PY=${PY:-/work/wt/v10/.venv/bin/python}; D=$(dirname "$(readlink -f "$0")")
cd /tmp
for i in $(seq "$N"); do
  echo "A $(PYTHONPATH=$A $PY $D/tree.py $S $Z $F)   B $(PYTHONPATH=$B $PY $D/tree.py $S $Z $F)"
done
