"""No text from a document or a user string reaches generated GLSL except as an escaped
comment: every string field of a scene document and every name given to the API is fuzzed
with line breaks, continuations, directives and HTML openers, and the shaders (desktop and
WebGL2) and the page are searched for what got through."""
from __future__ import annotations

import copy
import json
import re
from typing import Any, Iterator

import pytest

import sdfgl as sg
from sdfgl.errors import SdfglError
from sdfgl.scene_io import dumps, loads
from sdfgl.web.html import to_html
from sdfgl.web.spec import build_spec

MARK = "INJECTED"
NASTY = [f"a\n#error {MARK}", f"a\r#error {MARK}", f"a\\\n#error {MARK}", f"a */ #error {MARK} /*",
         f"a\u2028#error {MARK}", f"a\x00{MARK}", f"<!-- {MARK}", f"</script><b>{MARK}</b>", f"é{MARK}"]
DIRECTIVES = re.compile(r"#(version|define|undef|if|ifdef|ifndef|elif|else|endif|extension)\b")


def check_glsl(text: str) -> None:
    """Every line is ASCII; a line holding the mark has it inside a // comment; every '#'
    starts a known directive (the only way a '#' can reach the source from us)."""
    for n, line in enumerate(text.split("\n"), start=1):
        assert line.isascii(), f"line {n} is not ASCII: {line!r}"
        assert "\r" not in line and not line.rstrip().endswith("\\"), f"line {n}: {line!r}"
        if MARK in line:
            assert "//" in line and line.index("//") < line.index(MARK), f"line {n} carries the mark as code: {line!r}"
        code = line.split("//", 1)[0]
        for m in re.finditer("#", code):
            assert DIRECTIVES.match(code, m.start()), f"line {n}: {line!r}"


def check_everywhere(scene: sg.Node) -> None:
    """The desktop shader, the WebGL2 blocks and the page of ``scene``; it also renders."""
    check_glsl(sg.compile(scene, shadows="soft", ao=True))
    spec = build_spec(scene, None, (32, 24))
    for block in spec["blocks"]:
        check_glsl(block)
    page = to_html(scene, size=(32, 24))
    data = page.split('<script type="application/json" id="sdfgl-spec">', 1)[1].split("</script>", 1)[0]
    assert "<" not in data and ">" not in data and "&" not in data
    assert page.count("</script>") == 2 and page.count("<!--") == 0
    assert json.loads(data)["params"] == spec["params"]
    assert sg.render(scene, size=(16, 12)).color.std() > 0


@pytest.mark.parametrize("name", NASTY)
def test_parameter_names_reach_the_shader_only_as_escaped_comments(name: str) -> None:
    r = sg.param(0.8, name, (0.5, 1.0))
    scene = sg.union(sg.sphere(r), sg.box(1).translate((1, 0, 0)), k=0.1)
    check_everywhere(scene)


def string_slots(doc: Any, path: tuple = ()) -> Iterator[tuple]:
    """Paths to every string value and every key of a parameter table in ``doc``."""
    if isinstance(doc, dict):
        for key, value in doc.items():
            if path == ("params",):
                yield path + (("key", key),)
            yield from string_slots(value, path + (key,))
    elif isinstance(doc, list):
        for i, value in enumerate(doc):
            yield from string_slots(value, path + (i,))
    elif isinstance(doc, str):
        yield path


def with_text(doc: dict, slot: tuple, text: str) -> dict:
    out = copy.deepcopy(doc)
    node = out
    for step in slot[:-1]:
        node = node[step]
    last = slot[-1]
    if isinstance(last, tuple):  # rename a parameter, and every reference to it
        old = last[1]
        node[text] = node.pop(old)
        return json.loads(json.dumps(out).replace(json.dumps({"param": old}), json.dumps({"param": text})))
    node[last] = text
    return out


def zoo_document() -> dict:
    r = sg.param(0.5, "r", (0.1, 1.0))
    shape = sg.implicit("x*x + y*y + z*z - 1").translate((2, 0, 0))
    scene = sg.union(sg.sphere(r).color("tomato"), sg.box(1).material("#336699", metallic=0.5),
                     shape, sg.star(5, 1, 0.4).extrude(0.2).translate((0, 2, 0)), k=0.1, blend="circular")
    return json.loads(dumps(scene, sg.OrbitCamera(), {"aa": 2, "shadows": "soft"}))


def test_every_string_of_a_document_is_refused_or_reaches_the_shader_escaped() -> None:
    doc = zoo_document()
    slots = list(string_slots(doc))
    assert len(slots) >= 8, slots
    loaded = 0
    for slot in slots:
        for text in NASTY[:5] + NASTY[6:8]:
            try:
                got = loads(json.dumps(with_text(doc, slot, text)))
            except SdfglError:
                continue
            loaded += 1
            check_everywhere(got.scene)
    assert loaded > 0  # the parameter names, at least, are free text

