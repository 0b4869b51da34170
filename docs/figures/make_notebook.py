"""Write examples/notebook.ipynb (the notebook workflow); run it with
`jupyter nbconvert --to notebook --execute --inplace examples/notebook.ipynb`."""
from pathlib import Path

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

CELLS = [
    new_markdown_cell("# sdfgl in a notebook\n\nRenders show inline, a node shows a small preview, and "
                      "`sg.widget` is an interactive view synced with Python (orbit, pan, zoom, the A/S/O/D "
                      "toggles, a slider per `sg.param`)."),
    new_code_cell('import sdfgl as sg\n\n'
                  'r = sg.param(0.6, "r", range=(0.3, 1.0))\n'
                  'scene = sg.union(sg.sphere(r).color(0.9, 0.4, 0.2),\n'
                  '                 sg.box((0.8, 0.5, 0.8)).translate((0.9, 0, 0)), k=0.1)'),
    new_markdown_cell("A render shows its image (and a one-line repr in a terminal):"),
    new_code_cell("res = sg.render(scene, size=(480, 320), aa=2)\nres"),
    new_code_cell("print(repr(res))"),
    new_markdown_cell("A node shows a small preview (`sg.set_preview(False)` turns it off):"),
    new_code_cell("scene"),
    new_markdown_cell("The interactive view. Drag to orbit, right drag to pan, wheel to zoom; the slider "
                      "sets `r.value`, and setting `r.value` here moves the view:"),
    new_code_cell("w = sg.widget(scene, size=(640, 400))\nw"),
    new_code_cell("r.value = 0.9      # the view follows\nw.values"),
    new_code_cell("w.camera           # the camera the view is at, back in Python"),
    new_code_cell("w.render(size=(320, 200))  # the same view rendered headless (EGL)"),
    new_markdown_cell("`sg.show` would open a window; in a notebook it returns the widget instead, so the "
                      "kernel never blocks:"),
    new_code_cell("sg.show(scene)"),
    new_markdown_cell("A one-file HTML page of the same view, for people without Python:"),
    new_code_cell("import os, tempfile\n\n"
                  "path = sg.save_html(scene, os.path.join(tempfile.mkdtemp(), 'part.html'))\n"
                  "print(path.name, path.stat().st_size // 1024, 'KiB')"),
]


def main() -> None:
    nb = new_notebook(cells=CELLS, metadata={"kernelspec": {"name": "python3", "display_name": "Python 3",
                                                            "language": "python"}})
    out = Path(__file__).resolve().parents[2] / "examples" / "notebook.ipynb"
    nbformat.write(nb, out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
