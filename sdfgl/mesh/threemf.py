"""3MF files written with the standard library: one object per part, base materials, units.

Each part is a 3MF ``<object>`` named after it, with its own ``<m:basematerials>`` group
(one base material per scene colour, sRGB display colours, named ``part`` or ``part.k``)
and a material index on every triangle; every part is a build item at its place (no
transform: the parts keep their relative positions). The model's ``unit`` says what a
scene unit is. ``Metadata/Slic3r_PE_model.config`` gives part k extruder k + 1, which is
how PrusaSlicer (and slicers that read its files) map parts to extruders; other readers
ignore it.
"""
from __future__ import annotations

import io
import zipfile
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from ..values.colors import linear_to_srgb
from ..version import __version__
from .parts import Part

CORE = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
MATERIAL = "http://schemas.microsoft.com/3dmanufacturing/material/2015/02"
MODEL_PATH = "3D/3dmodel.model"
CONFIG_PATH = "Metadata/Slic3r_PE_model.config"

CONTENT_TYPES = """<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
 <Default Extension="config" ContentType="text/xml"/>
</Types>
"""
RELS = """<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"""


def display_color(rgb: np.ndarray) -> str:
    """``#RRGGBBFF`` of a linear RGB colour (3MF display colours are sRGB)."""
    q = np.clip(np.round(linear_to_srgb(rgb) * 255), 0, 255).astype(int)
    return "#{:02X}{:02X}{:02X}FF".format(*q)


def write_3mf(parts: list[Part], path: Path, unit: str = "millimeter") -> None:
    """Write ``parts`` to ``path`` (a finished zip; the caller makes it atomic)."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.writestr("[Content_Types].xml", CONTENT_TYPES)
        zf.writestr("_rels/.rels", RELS)
        with zf.open(MODEL_PATH, "w", force_zip64=True) as raw, io.TextIOWrapper(raw, "utf-8") as fh:
            _model(parts, fh, unit)
        zf.writestr(CONFIG_PATH, slicer_config(parts))


def _model(parts: list[Part], fh: io.TextIOWrapper, unit: str) -> None:
    fh.write(f'<?xml version="1.0" encoding="UTF-8"?>\n<model unit="{unit}" xml:lang="en-US" '
             f'xmlns="{CORE}" xmlns:m="{MATERIAL}">\n'
             f' <metadata name="Application">sdfgl {__version__}</metadata>\n <resources>\n')
    for i, part in enumerate(parts):
        mat_id, obj_id = 2 * i + 1, 2 * i + 2
        fh.write(f'  <m:basematerials id="{mat_id}">\n')
        for k, rgb in enumerate(part.palette):
            name = part.name if len(part.palette) == 1 else f"{part.name}.{k}"
            fh.write(f'   <m:base name={quoteattr(name)} displaycolor="{display_color(rgb)}"/>\n')
        fh.write(f'  </m:basematerials>\n  <object id="{obj_id}" type="model" name={quoteattr(part.name)} '
                 f'pid="{mat_id}" pindex="{int(part.material[0])}">\n   <mesh>\n    <vertices>\n')
        np.savetxt(fh, part.vertices, fmt='     <vertex x="%.9g" y="%.9g" z="%.9g"/>')
        fh.write("    </vertices>\n    <triangles>\n")
        rows = np.column_stack([part.faces, part.material])
        np.savetxt(fh, rows, fmt='     <triangle v1="%d" v2="%d" v3="%d" p1="%d"/>')
        fh.write("    </triangles>\n   </mesh>\n  </object>\n")
    fh.write(" </resources>\n <build>\n")
    for i in range(len(parts)):
        fh.write(f'  <item objectid="{2 * i + 2}"/>\n')
    fh.write(" </build>\n</model>\n")


def slicer_config(parts: list[Part]) -> str:
    """PrusaSlicer's per-object settings: the part's name and extruder (part k: extruder k + 1)."""
    lines = ['<?xml version="1.0" encoding="UTF-8"?>', "<config>"]
    for i, part in enumerate(parts):
        name = quoteattr(part.name)
        lines += [f' <object id="{2 * i + 2}" instances_count="1">',
                  f'  <metadata type="object" key="name" value={name}/>',
                  f'  <metadata type="object" key="extruder" value="{i + 1}"/>',
                  f'  <volume firstid="0" lastid="{len(part.faces) - 1}">',
                  f'   <metadata type="volume" key="name" value={name}/>',
                  f'   <metadata type="volume" key="extruder" value="{i + 1}"/>',
                  "  </volume>", " </object>"]
    return "\n".join(lines + ["</config>", ""])


def read_3mf(path: str | Path) -> dict:
    """What a 3MF file holds, read with the standard library: ``{"unit": ..., "objects":
    {name: {"vertices", "faces", "colors" (sRGB hex per face), "materials" (names)}}}``.
    Used to check written files (trimesh reads 3MF geometry but not its materials)."""
    import xml.etree.ElementTree as ET
    with zipfile.ZipFile(path) as zf:
        root = ET.fromstring(zf.read(MODEL_PATH))
    ns = {"c": CORE, "m": MATERIAL}
    groups = {g.get("id"): [(b.get("name"), b.get("displaycolor")) for b in g.findall("m:base", ns)]
              for g in root.iter(f"{{{MATERIAL}}}basematerials")}
    objects = {}
    for obj in root.iter(f"{{{CORE}}}object"):
        mesh = obj.find("c:mesh", ns)
        v = np.array([[float(e.get(a)) for a in "xyz"] for e in mesh.iter(f"{{{CORE}}}vertex")])
        tris = list(mesh.iter(f"{{{CORE}}}triangle"))
        f = np.array([[int(t.get(a)) for a in ("v1", "v2", "v3")] for t in tris])
        group = groups.get(obj.get("pid"), [])
        index = [int(t.get("p1", obj.get("pindex", 0))) for t in tris]
        objects[obj.get("name")] = {"vertices": v, "faces": f, "colors": [group[k][1] for k in index],
                                    "materials": [g[0] for g in group]}
    return {"unit": root.get("unit", "millimeter"), "objects": objects}
