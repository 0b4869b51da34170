"""Every node type in a few configurations, and random compositions, for parity tests."""
import numpy as np
import trimesh

import sdfgl as sg

from .conftest import all_primitives


def all_nodes() -> dict[str, sg.Node]:
    """One or more instances of every node type (primitives, booleans, transforms, ops)."""
    a, b = sg.box((1.0, 0.6, 0.8)), sg.sphere(0.6).translate((0.4, 0.2, 0))
    nodes = dict(all_primitives())
    nodes.update({
        "box_frame": sg.box_frame((1.2, 1.0, 0.8), 0.1),
        "union": a | b,
        "union_smooth": sg.union(a, b, k=0.3),
        "union_nary": sg.union(a, b, sg.torus(0.6, 0.1), k=0.1),
        "intersection": a & b,
        "intersection_smooth": sg.intersection(a, b, k=0.2),
        "difference": a - b,
        "difference_smooth": sg.difference(a, b, k=0.2),
        "translate": sg.torus(0.6, 0.2).translate((0.3, -0.2, 0.5)),
        "rotate": sg.box((1.2, 0.4, 0.3)).rotate(35, (1, 2, 0.5)),
        "orient": sg.cylinder(0.3, 1.5).orient((1, 1, 0)),
        "scale": sg.octahedron(0.5).scale(1.7),
        "scale_axes": sg.sphere(0.5).scale((1.5, 0.6, 1.0)),
        "color": (a.color(1, 0, 0) | b.color(0, 0, 1)),
        "material": sg.union(a.material("gold", metallic=1, roughness=0.4), b.material(emission="#203040"), k=0.2),
        "twist": sg.box((0.6, 1.6, 0.4)).twist(90),
        "bend": sg.box((1.6, 0.3, 0.4)).bend(40),
        "repeat": sg.sphere(0.5).repeat((1.0, 0, 1.0)),
        "repeat_finite": sg.box(0.4).rotate(30, (0, 1, 0)).repeat((1.0, 1.0, 0), count=(2, 1, 0)),
        "repeat_cheap": sg.sphere(0.2).repeat(1.0),
        "repeat_finite_cheap": sg.sphere(0.2).repeat((0, 0, 1.0), count=(0, 0, 2)),
        "union_circular": sg.union(a, b, k=0.3, blend="circular"),
        "union_chamfer": sg.union(a, b, k=0.3, blend="chamfer"),
        "difference_circular": sg.difference(a, b, k=0.2, blend="circular"),
        "mirror": sg.sphere(0.4).translate((0.6, 0.1, 0)).mirror(sg.X),
        "mirror_crossing": sg.box(0.8).translate((0.2, 0, 0)).mirror((1, 1, 0), (0.1, 0, 0)),
        "symmetric": sg.box(0.3).translate((0.5, 0.5, 0.2)).symmetric("xz"),
        "repeat_polar": sg.box(0.3).translate((1.0, 0, 0)).repeat_polar(6),
        "elongate": sg.torus(0.5, 0.1).elongate((0.4, 0, 0.2)),
        "round": sg.box(0.6).round(0.1),
        "shell": sg.sphere(0.6).shell(0.05),
        "sierpinski": sg.sierpinski(4, 1.0),
        "tree": sg.tree(3, 0.8, 0.06, 30, 0.7),
        "extrude": sg.extrude(sg.polygon([(0, 0), (1, 0.2), (0.4, 0.9), (-0.3, 0.5)]), 0.4),
        "revolve": sg.revolve(sg.rectangle((0.3, 0.8), 0.05), 0.4),
        "displace": sg.sphere(0.7).displace(0.08, 3.0, 3),
        "noise_field": sg.noise(1.5, 3, 1.0, 0.2) & sg.box(2.0),
        "displace_expr": sg.displace_expr(sg.box(0.8), "0.04*sin(9*x)*sin(9*y)*sin(9*z)"),
        # 2D modelling: each 2D shape and operator, made solid
        "extrude_text": sg.extrude(sg.text("o", size=1.4, align="center").translate((0, -0.35)), 0.3),
        "extrude_boolean2d": sg.extrude(sg.circle(0.8) - sg.rectangle(0.8), 0.4),
        "extrude_union2d_smooth": sg.extrude(sg.union(sg.circle(0.5).translate((-0.3, 0)), sg.rectangle((0.6, 0.4)),
                                                      k=0.3), 0.5),
        "extrude_intersection2d": sg.extrude(sg.intersection(sg.circle(0.7), sg.rectangle((1.0, 0.5)).rotate(30),
                                                             k=0.1, blend="circular"), 0.3),
        "revolve_transforms2d": sg.revolve(sg.triangle((0, 0), (0.5, 0.1), (0.2, 0.6)).rotate(20).translate((0.1, 0.2))
                                           .scale(1.3), 0.3),
        "extrude_scale2d_axes": sg.extrude(sg.star(6, 0.8, sharpness=3).scale((1.0, 0.5)), 0.4),
        "extrude_round_onion2d": sg.extrude(sg.rectangle((1.0, 0.6)).round(0.1).onion(0.08), 0.3),
        "extrude_ellipse": sg.extrude(sg.ellipse((0.9, 0.4)), 0.3),
        "extrude_arc": sg.extrude(sg.arc(0.7, 250, 0.15), 0.3),
        "extrude_star": sg.extrude(sg.star(5, 0.9, sharpness=3.5), 0.3),
        "extrude_regular_polygon": sg.extrude(sg.regular_polygon(6, 0.8, 0.15), 0.3),
        "extrude_capsule2": sg.extrude(sg.capsule2((-0.5, -0.2), (0.4, 0.3), 0.2), 0.3),
        "extrude_slice": sg.extrude(sg.slice(sg.torus(0.6, 0.2).rotate(90, sg.X)), 0.3),
        "extrude_taper": sg.extrude(sg.rectangle((1.0, 0.6)), 1.0, taper=0.6),
        "extrude_twist": sg.extrude(sg.star(5, 0.8, sharpness=3), 1.0, twist=90),
        "taper": sg.box((0.8, 1.2, 0.6)).taper(0.4, "y"),
        "twist_x": sg.box((1.6, 0.6, 0.4)).twist(60, "x"),
        "bend_x": sg.box((0.3, 1.6, 0.4)).bend(40, "x"),
        "bend_y": sg.box((0.4, 0.3, 1.6)).bend(40, "y"),
        # more solids and operators
        "tetrahedron": sg.tetrahedron(0.5),
        "dodecahedron": sg.dodecahedron(0.7),
        "icosahedron": sg.icosahedron(0.7),
        "pyramid": sg.pyramid(1.2, 1.0),
        "slab": sg.slab(x0=-0.5, x1=0.8, y0=-0.3) & sg.sphere(1.0),
        "tube": sg.tube([(-0.8, 0, 0), (0, 0.6, 0.2), (0.5, -0.2, 0.4), (0.9, 0.3, -0.3)], 0.12),
        "bezier_tube": sg.bezier_tube((-0.8, -0.3, 0), (0.1, 0.9, 0.3), (0.8, -0.2, -0.2), 0.15),
        "capped_torus": sg.capped_torus(0.7, 0.15, 240),
        "gyroid": sg.gyroid(6.0, 0.08) & sg.sphere(1.0),
        "dilate": sg.box(0.8).dilate(0.1),
        "erode": sg.box(1.0).erode(0.1),
        "morph": sg.morph(sg.box(0.9), sg.sphere(0.6).translate((0.2, 0, 0)), 0.35),
        "shear": sg.box((0.6, 1.0, 0.5)).shear(0.7, "x", "y"),
        "glsl": sg.glsl("float r = length(p.xz) - 0.6;\nreturn length(vec2(r, p.y)) - 0.2;",
                        twin=lambda p: np.hypot(np.hypot(p[:, 0], p[:, 2]) - 0.6, p[:, 1]) - 0.2,
                        bounds=((-0.8, -0.2, -0.8), (0.8, 0.2, 0.8)), exact=True),
        "glsl_steep": sg.glsl("2.0 * (length(p) - 0.5)", twin=lambda p: 2.0 * (np.linalg.norm(p, axis=-1) - 0.5),
                              lipschitz=2.0, bounds=((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))),
        "product": sg.product(sg.sphere(0.6), sg.box(0.8).translate((0.5, 0, 0))),
        "implicit": sg.implicit("x**2 + y**2/0.5 + z**2 - 1", bounds=((-1.2, -1, -1.2), (1.2, 1, 1.2))),
        "mesh": sg.from_mesh(trimesh.creation.torus(0.6, 0.2, major_sections=48, minor_sections=24), name="torus"),
    })
    return nodes


PRIMS = list(all_primitives().values())


def random_scene(rng: np.random.Generator, depth: int = 3) -> sg.Node:
    """A random tree of primitives, booleans (hard and smooth) and transforms."""
    if depth == 0 or rng.random() < 0.2:
        node = PRIMS[rng.integers(len(PRIMS))]
        if node.bounds[0][0] == -np.inf:  # keep planes out of compositions: bounded scenes
            node = sg.sphere(0.5)
        return node
    pick = rng.integers(6)
    if pick < 3:
        op = (sg.union, sg.intersection, sg.difference)[pick]
        k = float(rng.choice([0.0, 0.05, 0.3]))
        return op(random_scene(rng, depth - 1), random_scene(rng, depth - 1), k=k)
    child = random_scene(rng, depth - 1)
    if pick == 3:
        return child.translate(rng.uniform(-0.5, 0.5, 3))
    if pick == 4:
        return child.rotate(float(rng.uniform(-180, 180)), rng.normal(size=3) + 1e-3)
    return child.scale(float(rng.uniform(0.5, 1.5)))


def probe_points(node: sg.Node, rng: np.random.Generator, n: int = 4000) -> dict[str, np.ndarray]:
    """Points near the surface, inside, far away, and at awkward places (centres, edges)."""
    lo, hi = node.bounds
    lo = np.where(np.isfinite(lo), lo, -3.0)
    hi = np.where(np.isfinite(hi), hi, 3.0)
    box = rng.uniform(lo - 0.5, hi + 0.5, size=(n, 3))
    d = node.distance(box)
    # walk towards the surface by the field value along a numerical gradient
    h = 1e-5
    g = np.stack([node.distance(box + h * e) - node.distance(box - h * e) for e in np.eye(3)], -1) / (2 * h)
    gn = np.linalg.norm(g, axis=-1, keepdims=True)
    near = box - d[:, None] * g / np.where(gn > 0, gn, 1) ** 2 * np.where(gn > 0, gn, 0)
    near += rng.normal(scale=1e-3, size=near.shape)
    inside = box[d < 0]
    far = rng.normal(size=(500, 3)) * 200.0
    corners = np.array(np.meshgrid(*[[a, (a + b) / 2, b] for a, b in zip(lo, hi)])).reshape(3, -1).T
    awkward = np.concatenate([corners, np.zeros((1, 3)), np.eye(3) * 0.5, -np.eye(3) * 0.5])
    return {"near": near, "inside": inside, "far": far, "awkward": awkward}
