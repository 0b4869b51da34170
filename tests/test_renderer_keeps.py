"""What a renderer keeps of the last scene it drew, and what it lets go (at exit too)."""
import gc
import subprocess
import sys
import textwrap
import weakref

import sdfgl as sg


def test_forget_scene_lets_the_scene_go_and_the_next_render_matches():
    r = sg.Renderer()
    scene = sg.sphere(1) | sg.box(0.8).translate((0.9, 0, 0))
    first = r.render(scene, size=(32, 24)).color
    r.forget_scene()
    assert (r.render(scene, size=(32, 24)).color == first).all()  # its source generated again
    ref = weakref.ref(scene)
    del scene
    gc.collect()
    assert ref() is not None  # kept: its next frame skips code generation
    r.forget_scene()
    gc.collect()
    assert ref() is None


def test_at_exit_the_default_renderer_lets_its_last_scene_go():
    """At the last exit handler (registered before sdfgl is imported, so it runs after
    sdfgl's), the scene drawn by sg.render is held by nothing but the script's own names."""
    script = textwrap.dedent("""
        import atexit, gc, weakref

        def check():
            global scene, res
            del scene, res
            gc.collect()
            print("freed" if ref() is None else "kept")

        atexit.register(check)
        import sdfgl as sg
        scene = sg.sphere(1) | sg.box(0.8).translate((0.9, 0, 0))
        res = sg.render(scene, size=(16, 12))
        ref = weakref.ref(scene)
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().splitlines()[-1] == "freed"
