"""Every writer on a disk that fills: the old file stays whole, no half-written file is left
under the target's name, no temporary file is left beside it, and the error says what
happened. The disk is a small tmpfs mounted for the test (needs root, as CI runs)."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import Callable, Iterator

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.errors import SdfglError

pytestmark = pytest.mark.skipif(os.geteuid() != 0, reason="mounting a tmpfs needs root")

SCENE = sg.sphere(1) | sg.box(1.5)


@pytest.fixture
def small_disk(tmp_path: Path) -> Iterator[Path]:
    """A 2 MiB tmpfs mounted at a fresh folder."""
    mnt = tmp_path / "disk"
    mnt.mkdir()
    subprocess.run(["mount", "-t", "tmpfs", "-o", "size=2m", "tmpfs", str(mnt)], check=True)
    try:
        yield mnt
    finally:
        subprocess.run(["umount", "-l", str(mnt)], check=False)


def fill(disk: Path, leave: int) -> None:
    """Fill ``disk`` up to ``leave`` free bytes."""
    with open(disk / "filler", "ab", buffering=0) as fh:
        try:
            while True:
                fh.write(b"\0" * 4096)
        except OSError:
            pass
    st = os.statvfs(disk)
    free = st.f_bavail * st.f_frsize
    size = (disk / "filler").stat().st_size
    os.truncate(disk / "filler", max(0, size - max(0, leave - free)))


def check_refused(disk: Path, target: Path, write: Callable[[], object]) -> None:
    """``write`` (which would write more than the disk holds) fails with a clear error,
    leaves ``target``'s old bytes in place and no temporary file."""
    old = target.read_bytes()
    fill(disk, 8192)
    with pytest.raises(SdfglError) as info:
        write()
    message = str(info.value)
    assert target.name in message and "No space left on device" in message, message
    assert target.read_bytes() == old
    leftovers = sorted(p.name for p in disk.iterdir() if p.name.startswith("."))
    assert leftovers == [], leftovers


@pytest.fixture(scope="module")
def meshes() -> tuple[object, object]:
    """A small mesh (the old file) and a large one (the write that does not fit)."""
    return sg.mesh(SCENE, step=0.4), sg.mesh(SCENE, step=0.03)


@pytest.mark.parametrize("suffix", [".stl", ".obj", ".ply", ".glb", ".3mf"])
def test_mesh_writers_leave_the_old_file_whole(small_disk: Path, meshes: tuple, suffix: str) -> None:
    small, large = meshes
    target = small_disk / f"part{suffix}"
    small.save(target)
    check_refused(small_disk, target, lambda: large.save(target))


def test_npz_outputs_leave_the_old_file_whole(small_disk: Path) -> None:
    from sdfgl.outputs import save_outputs
    target = small_disk / "out.npz"
    save_outputs(sg.render(SCENE, size=(8, 6), outputs=("color", "depth")), target, ("color", "depth"))
    res = sg.render(SCENE, size=(320, 240), outputs=("color", "depth", "normal", "steps"))
    res.normal[:] = np.random.default_rng(0).random(res.normal.shape)  # incompressible
    check_refused(small_disk, target, lambda: save_outputs(res, target, ("color", "depth", "normal", "steps")))


def test_png_leaves_the_old_file_whole(small_disk: Path) -> None:
    target = small_disk / "a.png"
    sg.render(SCENE, size=(8, 6)).save(target)
    noise = np.random.default_rng(1).integers(0, 255, (1000, 1000, 3), dtype=np.uint8)
    from sdfgl.outputs import write_image
    check_refused(small_disk, target, lambda: write_image(noise, target))


@pytest.mark.slow
def test_html_and_scene_documents_leave_the_old_file_whole(small_disk: Path) -> None:
    page = small_disk / "view.html"
    sg.save_html(sg.sphere(1), page, size=(64, 48))
    big = sg.union(*[sg.sphere(0.1).translate((i * 0.01, 0, 0)) for i in range(3000)])
    doc = small_disk / "scene.json"
    sg.save_scene(sg.sphere(1), doc)
    check_refused(small_disk, doc, lambda: sg.save_scene(big, doc))
    os.unlink(small_disk / "filler")
    check_refused(small_disk, page, lambda: sg.save_html(big, page, size=(64, 48), grid=False))


@pytest.mark.parametrize("name", ["clip.mp4", "clip.webm", "clip.gif"])
@pytest.mark.slow
def test_animate_fails_on_a_full_disk_and_keeps_the_old_clip(small_disk: Path, tmp_path: Path, name: str) -> None:
    scene = tmp_path / "scene.py"
    scene.write_text("import sdfgl as sg\nscene = sg.sphere(1).color(0.9, 0.3, 0.2) | sg.box(1.4)\n")
    target = small_disk / name
    cmd = [sys.executable, "-m", "sdfgl", "animate", str(scene), "-o", str(target), "--turntable",
           "--size", "64x48", "--fps", "4", "--seconds", "1"]
    subprocess.run(cmd, check=True, capture_output=True)
    old = target.read_bytes()
    fill(small_disk, 4096)
    long_cmd = cmd[:-4] + ["--size", "320x240", "--fps", "10", "--seconds", "3"]
    out = subprocess.run(long_cmd, capture_output=True, text=True)
    assert out.returncode != 0, out.stdout + out.stderr
    assert "Traceback" not in out.stderr, out.stderr
    assert name in out.stderr, out.stderr
    assert target.read_bytes() == old
    assert sorted(p.name for p in small_disk.iterdir() if p.name.startswith(".")) == []
