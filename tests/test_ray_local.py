"""``sdfgl batch --ray local`` starts its own cluster whatever a killed one left behind."""
import json
import os
import subprocess
import sys

import pytest

SCENE = "import sdfgl as sg\nscene = sg.sphere(1) | sg.box(1.5)\n"


@pytest.mark.slow
def test_local_ray_ignores_a_stale_cluster_address(tmp_path):
    (tmp_path / "scene.py").write_text(SCENE)
    (tmp_path / "jobs.json").write_text(json.dumps(
        {"defaults": {"scene": "scene.py", "size": [24, 18]},
         "jobs": [{"count": 2, "camera": {"yaw": {"uniform": [0, 360]}}, "output": "out/{index}.png"}]}))
    # what a killed cluster leaves: an address nobody answers at (RAY_ADDRESS, like the
    # address file in /tmp/ray, is what a plain ray.init() would join)
    env = {**os.environ, "RAY_ADDRESS": "127.0.0.1:9"}
    out = subprocess.run([sys.executable, "-m", "sdfgl", "batch", "jobs.json", "--ray", "local", "--workers", "1"],
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["0.png", "1.png"]
