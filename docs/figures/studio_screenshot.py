"""docs/studio.png and docs/studio.gif: the studio on fogleman's CSG part, in headless Chromium.

    python docs/figures/studio_screenshot.py

The part is opened as a scene document with a live sphere radius; the GIF records that
radius's slider moving (uniforms only: the page does not recompile).
"""
import json
import math
import tempfile
from pathlib import Path

from PIL import Image

import sdfgl as sg
from sdfgl.scene_io import save_scene
from sdfgl.studio import Workspace, Studio
from sdfgl.web.chromium import Chromium

ROOT = Path(__file__).resolve().parents[2]
W, H = 1600, 800
VIEW = (360, 260)
FRAMES = 14


def part() -> sg.Node:
    r = sg.param(1.0, "radius", range=(0.8, 1.25))
    c = sg.cylinder(0.5, 4)
    return (sg.sphere(r) & sg.box(1.5)) - (c.orient(sg.X) | c | c.orient(sg.Z))


def main() -> None:
    path = Path(tempfile.mkdtemp()) / "part.json"
    save_scene(part(), path, sg.OrbitCamera(target=(0, 0, 0), distance=4.5, yaw=30, pitch=25))
    still = "document.getElementById('studio-view').dataset.still === '1'"
    with Studio(Workspace(path, size=VIEW)) as st, Chromium(size=(W, H)) as b:
        b.goto(st.url)
        b.wait_for(f"document.body.dataset.ready === '1' && window.studio.state.shownGen >= 1 && {still}", timeout=120)
        b.evaluate("window.studio.python()")  # fills the code box
        count = b.evaluate("""(() => { const s = window.studio, data = s.editor.export().drawflow.Home.data;
          const ids = Object.values(data).filter((n) => n.name !== "output").map((n) => n.id);
          s.editor.zoom_out(); s.editor.zoom_out(); s.editor.zoom_out(); s.editor.zoom_out();
          return ids.length; })()""")
        b.wait_for(f"window.studio.previewsIdle() && "
                   f"document.querySelectorAll('.drawflow-node[data-previews]').length === {count}", timeout=120)
        b.wait_for(still)
        Image.fromarray(b.screenshot()).save(ROOT / "docs" / "studio.png", optimize=True)
        rect = b.evaluate("(() => { const r = document.getElementById('studio-side').getBoundingClientRect();"
                          " return [r.x, r.y, r.width, 330]; })()")
        frames = []
        for i in range(FRAMES):
            x = 0.8 + 0.45 * (0.5 - 0.5 * math.cos(2 * math.pi * i / FRAMES))
            n = int(b.evaluate("+document.getElementById('studio-view').dataset.frames"))
            b.evaluate(f"window.studio.setParam('radius', {x})")
            b.wait_for(f"{still} && +document.getElementById('studio-view').dataset.frames > {n}", timeout=60)
            frames.append(Image.fromarray(b.screenshot(tuple(rect))).convert("P", palette=Image.ADAPTIVE, colors=64))
        frames[0].save(ROOT / "docs" / "studio.gif", save_all=True, append_images=frames[1:], duration=120, loop=0,
                       optimize=True)
        print(json.dumps({"compiles": st.workspace.compiles, "frames": len(frames)}))


if __name__ == "__main__":
    main()
