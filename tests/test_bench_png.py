"""The benchmark's PNG rows (sdfgl.bench_png): fresh processes, cold and warm shader caches."""
import json
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from sdfgl.bench_png import CACHES, run_png


def test_the_timed_call_writes_the_png_it_times(tmp_path):
    out = tmp_path / "demo.png"
    r = subprocess.run([sys.executable, "-m", "sdfgl.bench_png", str(out), "96", "54"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout.strip().splitlines()[-1])["seconds"] > 0
    with Image.open(out) as im:
        assert im.size == (96, 54)
        assert len(np.unique(np.asarray(im.convert("RGB")).reshape(-1, 3), axis=0)) > 50  # a shaded scene, not a cleared frame


@pytest.mark.slow
def test_rows_for_both_caches_and_each_tool_or_a_note():
    md, data = run_png(quick=True)
    for cache in CACHES:
        call, whole = data["median_s"][f"sdfgl call {cache}"], data["median_s"][f"sdfgl process {cache}"]
        assert 0 < call < whole  # the call runs inside its process
        assert f"| save call in its process | {cache} |" in md and f"| whole process | {cache} |" in md
    peer = [k for k in data["median_s"] if k.startswith("DistForge")]
    assert len(peer) == 4 or any(n.startswith("DistForge skipped") for n in data["notes"])
    assert not [n for n in data["notes"] if "failed" in n]
