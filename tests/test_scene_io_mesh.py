"""Mesh nodes in scene documents: file references (relative, checked by SHA-256), inline
triangles, and what a bad reference says."""
import json
import pickle
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh
from PIL import Image

import sdfgl as sg
from sdfgl.scene_io import dumps, loads, mesh_nodes

ROOT = Path(__file__).resolve().parents[1]


def part_file(folder: Path, name: str = "ball.stl") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    trimesh.creation.icosphere(2, radius=0.5).export(str(path))
    return path


def scene_with(node: sg.Node) -> sg.Node:
    return (node | sg.box(0.3).translate((0.5, 0, 0))).color((0.8, 0.3, 0.2))


def test_a_file_beside_the_document_is_saved_relative_and_loads_to_the_same_glsl(tmp_path):
    node = sg.load_mesh(part_file(tmp_path / "parts"), units="cm", scale=2)
    scene = scene_with(node)
    doc_path = sg.save_scene(scene, tmp_path / "s.json")
    entry = json.loads(doc_path.read_text())["scene"]["child"]["children"][0]
    assert entry["file"] == "parts/ball.stl"
    assert entry["sha256"] == __import__("hashlib").sha256((tmp_path / "parts" / "ball.stl").read_bytes()).hexdigest()
    assert (entry["scale"], entry["units"], entry["scene_units"]) == (2.0, "cm", "mm")
    doc = sg.load_scene(doc_path)
    assert sg.compile(doc.scene) == sg.compile(scene)
    assert dumps(doc.scene, base=tmp_path) == dumps(scene, base=tmp_path)
    # the folder moves as a whole: the relative reference still finds the file
    moved = tmp_path.parent / (tmp_path.name + "-moved")
    shutil.copytree(tmp_path, moved)
    again = sg.load_scene(moved / "s.json").scene
    assert np.allclose(again.distance(np.zeros((1, 3))), scene.distance(np.zeros((1, 3))))


def test_a_file_elsewhere_is_saved_by_absolute_path(tmp_path):
    path = part_file(tmp_path / "elsewhere")
    (tmp_path / "docs").mkdir()
    doc_path = sg.save_scene(sg.load_mesh(path), tmp_path / "docs" / "s.json")
    assert json.loads(doc_path.read_text())["scene"]["file"] == str(path)
    assert sg.compile(sg.load_scene(doc_path).scene) == sg.compile(sg.load_mesh(path))
    assert sg.load_mesh(path).to_dict()["scene"]["file"] == str(path)  # no document folder: absolute


def test_a_changed_or_missing_file_names_the_file_and_the_json_path(tmp_path):
    path = part_file(tmp_path)
    doc_path = sg.save_scene(scene_with(sg.load_mesh(path)), tmp_path / "s.json")
    trimesh.creation.icosphere(1, radius=0.5).export(str(path))
    with pytest.raises(sg.SceneDocumentError, match=r"s.json': scene.child.children\[0\].file: mesh file '.*ball.stl' "
                                                     r"has changed since the document was saved"):
        sg.load_scene(doc_path)
    path.unlink()
    with pytest.raises(sg.SceneDocumentError, match=r"scene.child.children\[0\].file: mesh file '.*ball.stl': "
                                                     r"no such file"):
        sg.load_scene(doc_path)


def test_only_mesh_files_are_read(tmp_path):
    script = tmp_path / "evil.py"
    script.write_text("raise SystemExit('ran')\n")
    for file in (str(script), "/etc/passwd", "scene.json"):
        doc = {"format": "sdfgl-scene", "version": 1, "scene": {"kind": "mesh", "file": file}}
        with pytest.raises(sg.SceneDocumentError, match=r"scene.file: mesh file .*unknown format"):
            loads(json.dumps(doc), base=tmp_path)
    doc = {"format": "sdfgl-scene", "version": 1, "scene": {"kind": "mesh", "file": "ball.stl", "colour": 1}}
    with pytest.raises(sg.SceneDocumentError, match=r"scene.colour: unknown key of a mesh node"):
        loads(json.dumps(doc), base=tmp_path)


def test_an_in_memory_mesh_is_saved_inline_exactly_up_to_a_limit(tmp_path, monkeypatch):
    node = sg.from_mesh(trimesh.creation.torus(0.6, 0.2, major_sections=24, minor_sections=12), name="ring")
    text = dumps(scene_with(node))
    entry = json.loads(text)["scene"]["child"]["children"][0]
    assert set(entry) == {"kind", "name", "vertices", "faces"}
    back = loads(text).scene
    assert sg.compile(back) == sg.compile(scene_with(node))
    assert dumps(back) == text
    bad = json.loads(text)
    bad["scene"]["child"]["children"][0]["faces"] = "not base64!"
    with pytest.raises(sg.SceneDocumentError, match=r"scene.child.children\[0\].faces: expected base64"):
        loads(json.dumps(bad))
    monkeypatch.setattr(mesh_nodes, "MAX_INLINE_TRIANGLES", 100)
    with pytest.raises(sg.ParameterError, match=r"mesh\(ring, 576 triangles\): a mesh without a file .* up to 100"):
        dumps(node)


def test_pickle_keeps_the_file_reference(tmp_path):
    node = sg.load_mesh(part_file(tmp_path))
    assert pickle.loads(pickle.dumps(node)).source == node.source


def test_cli_renders_a_document_with_a_mesh_node(tmp_path):
    node = sg.load_mesh(part_file(tmp_path / "parts"))
    doc_path = sg.save_scene(scene_with(node), tmp_path / "s.json")
    out = tmp_path / "s.png"
    r = subprocess.run([sys.executable, "-m", "sdfgl.cli", "render", str(doc_path), "-o", str(out), "--size", "64x48"],
                       capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert r.returncode == 0, r.stderr
    img = np.asarray(Image.open(out).convert("RGB"))
    assert len(np.unique(img.reshape(-1, 3), axis=0)) > 20
    (tmp_path / "parts" / "ball.stl").unlink()
    r = subprocess.run([sys.executable, "-m", "sdfgl.cli", "render", str(doc_path), "-o", str(out)],
                       capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert r.returncode == 2 and "scene.child.children[0].file: mesh file" in r.stderr, r.stderr
