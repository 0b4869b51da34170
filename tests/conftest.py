import os
import shutil

# llvmpipe's own switch that skips LLVM's optimisation passes: this suite's many small
# shaders compile about twice as fast (and draw somewhat slower). Set before any GL
# context exists; subprocesses inherit it. `sdfgl bench` and users keep the default.
os.environ.setdefault("GALLIVM_PERF", "nopt")

import numpy as np
import pytest

import sdfgl as sg


@pytest.fixture(scope="session")
def renderer() -> sg.Renderer:
    """One real EGL renderer for the whole run (llvmpipe here)."""
    return sg.Renderer()


def all_primitives() -> dict[str, sg.Node]:
    """One instance of every primitive, each small enough to frame the same way."""
    return {
        "sphere": sg.sphere(0.8),
        "box": sg.box((1.2, 0.8, 1.0)),
        "rounded_box": sg.rounded_box(1.2, 0.2),
        "plane": sg.plane((0, 1, 0), (0, -0.5, 0)),
        "torus": sg.torus(0.7, 0.25),
        "capsule": sg.capsule((-0.5, -0.3, 0), (0.5, 0.4, 0.1), 0.3),
        "cylinder": sg.cylinder(0.5, 1.2),
        "cone": sg.cone(1.2, 0.6, 0.2),
        "ellipsoid": sg.ellipsoid((0.9, 0.4, 0.6)),
        "octahedron": sg.octahedron(0.8),
        "hex_prism": sg.hex_prism(0.5, 1.0),
    }


def no_nan(res: sg.RenderResult) -> None:
    for name in ("depth", "normal"):
        arr = getattr(res, name)
        if arr is not None:
            assert not np.isnan(arr).any(), f"NaN in {name}"


glslang = shutil.which("glslangValidator")
