"""Optional extras on the command line: each missing one is named, with its pip line, before long work."""
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

# Runs argv[2:] as `python -m sdfgl ...` (or a script, when argv[2] ends in .py) with the comma list of
# top-level packages in argv[1] made unimportable, as if the extra were not installed.
BLOCKED_RUN = """
import runpy, sys
blocked = set(sys.argv[1].split(","))
class Blocker:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in blocked:
            raise ImportError(f"No module named {name!r} (blocked by the test)")
        return None
sys.meta_path.insert(0, Blocker())
args = sys.argv[2:]
if args[0].endswith(".py"):
    sys.argv = args
    runpy.run_path(args[0], run_name="__main__")
else:
    sys.argv = ["sdfgl", *args]
    runpy.run_module("sdfgl", run_name="__main__")
"""


def run_without(blocked: str, *args: str, timeout: float = 60) -> tuple[subprocess.CompletedProcess, float]:
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-c", BLOCKED_RUN, blocked, *args], capture_output=True, text=True,
                       cwd=ROOT, timeout=timeout)
    return r, time.perf_counter() - t0


def refused(r: subprocess.CompletedProcess, pip_line: str) -> bool:
    return r.returncode == 2 and pip_line in r.stderr and "Traceback" not in r.stderr


def test_the_blocker_blocks():
    r, _ = run_without("numpy", "--version")
    assert r.returncode != 0 and "blocked by the test" in r.stderr


def test_bench_without_matplotlib_refuses_at_once(tmp_path):
    r, seconds = run_without("matplotlib", "bench", "--quick", "--out", str(tmp_path / "b"), "--no-progress")
    assert refused(r, "pip install 'sdfgl[plots]'"), r.stderr
    assert "matplotlib" in r.stderr and seconds < 30
    assert not (tmp_path / "b").exists()


@pytest.mark.slow
def test_mesh_without_scipy_writes_its_file_and_report_is_opt_in(tmp_path):
    out = tmp_path / "s.stl"
    r, _ = run_without("scipy", "mesh", "--demo", "-o", str(out), "--resolution", "16", "--quiet")
    assert r.returncode == 0, r.stderr
    assert out.stat().st_size > 84 and "report:" not in r.stdout and r.stderr == ""
    r, _ = run_without("scipy", "mesh", "--demo", "-o", str(tmp_path / "r.stl"), "--resolution", "16", "--report")
    assert refused(r, "pip install 'sdfgl[mesh]'") and "scipy" in r.stderr, r.stderr
    assert not (tmp_path / "r.stl").exists()  # refused before meshing, not after writing
    r, _ = run_without("scipy", "mesh", "--demo", "-o", str(out), "--resolution", "16", "--quiet", "--no-report")
    assert r.returncode == 0 and "the report is off unless --report is given" in r.stderr, r.stderr


@pytest.mark.parametrize("suffix, blocked", [(".glb", "trimesh")])
def test_mesh_formats_written_through_trimesh_are_checked_first(tmp_path, suffix, blocked):
    out = tmp_path / f"m{suffix}"
    r, _ = run_without(blocked, "mesh", "--demo", "-o", str(out), "--resolution", "16", "--quiet")
    assert refused(r, "pip install 'sdfgl[mesh]'") and blocked in r.stderr, r.stderr
    assert not out.exists()


def test_3mf_is_written_without_trimesh_or_lxml(tmp_path):
    out = tmp_path / "m.3mf"
    r, _ = run_without("trimesh,lxml", "mesh", "--demo", "-o", str(out), "--resolution", "16", "--quiet")
    assert r.returncode == 0 and out.stat().st_size > 1000, r.stderr


def test_video_pbr_and_ray_name_their_extra(tmp_path):
    r, _ = run_without("imageio_ffmpeg", "animate", "--demo", "-o", str(tmp_path / "a.mp4"), "--frames", "2",
                       "--size", "32x24", "--no-progress")
    assert refused(r, "pip install 'sdfgl[video]'"), r.stderr
    r, _ = run_without("mitsuba", "pbr", "--demo", "-o", str(tmp_path / "p.png"), "--size", "32x24")
    assert refused(r, "pip install 'sdfgl[pbr]'"), r.stderr
    jobs = tmp_path / "jobs.json"
    jobs.write_text('{"jobs": [{"scene": "%s", "size": [32, 24], "output": "o.png"}]}'
                    % (ROOT / "examples" / "csg.py").as_posix())
    r, _ = run_without("ray", "batch", str(jobs), "--ray", "local", "--no-progress")
    assert refused(r, "pip install 'sdfgl[ray]'"), r.stderr
    assert list(tmp_path.iterdir()) == [jobs]


def test_require_extra_knows_every_extra_of_the_package():
    from sdfgl.extras import EXTRAS, MissingExtraError, require_extra
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    assert set(EXTRAS) == set(declared) - {"test", "all"}
    (everything,) = declared["all"]  # [all] is every feature extra, all but the docs tools
    assert set(everything.removeprefix("sdfgl[").removesuffix("]").split(",")) == set(EXTRAS) - {"docs"}
    require_extra("mesh", "scipy")  # installed here: no error
    with pytest.raises(MissingExtraError, match=r"the plot needs no_such_module_x, which is not installed: "
                                                r"pip install 'sdfgl\[plots\]'"):
        require_extra("plots", "no_such_module_x", purpose="the plot")
    with pytest.raises(ValueError, match="unknown extra 'plot'"):
        require_extra("plot")
