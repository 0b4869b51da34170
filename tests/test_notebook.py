"""examples/notebook.ipynb executed by nbconvert: inline images, a node preview and widget views."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
WIDGET = "application/vnd.jupyter.widget-view+json"


@pytest.mark.slow
def test_demo_notebook_executes_with_images_and_widgets(tmp_path):
    out = tmp_path / "executed.ipynb"
    r = subprocess.run([sys.executable, "-m", "nbconvert", "--to", "notebook", "--execute",
                        "--ExecutePreprocessor.timeout=120", "--output", str(out),
                        str(ROOT / "examples" / "notebook.ipynb")],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    nb = json.loads(out.read_text())
    outputs = {"".join(c["source"]).split("\n")[0]: c["outputs"] for c in nb["cells"] if c["cell_type"] == "code"}
    data = {src: [{k: "".join(v) if isinstance(v, list) else v for k, v in o.get("data", {}).items()} for o in outs]
            for src, outs in outputs.items()}
    assert any("image/png" in d for d in data["res = sg.render(scene, size=(480, 320), aa=2)"])
    assert any("image/png" in d for d in data["scene"])  # the node preview
    widget_views = [d for ds in data.values() for d in ds if WIDGET in d]
    assert len(widget_views) == 2  # sg.widget(...) and sg.show(...) in a kernel
    assert data["r.value = 0.9      # the view follows"][0]["text/plain"] == "[0.9]"
    state = nb["metadata"]["widgets"]["application/vnd.jupyter.widget-state+json"]["state"]
    ours = [m for m in state.values() if "spec" in m["state"]]
    assert ours and ours[0]["state"]["values"] == [0.9]  # the state the view saw last
    short = [d["text/plain"] for ds in data.values() for d in ds if "text/plain" in d]
    assert max(len(t) for t in short) < 300  # no 20 000-character reprs
