"""The benchmark's hand-written baseline shaders live in benchmarks/baselines/ of a source
checkout; without them (an installed package) their rows are skipped, not a crash."""
import sdfgl.bench_model as bench_model


def hand_labels() -> list[str]:
    groups = dict(bench_model.variants([]))
    return [v.label for v in groups["generated vs hand-written (same template and settings)"]]


def test_baselines_are_read_from_the_benchmarks_folder():
    assert bench_model.BASELINES.parts[-2:] == ("benchmarks", "baselines")
    assert {p.stem for p in bench_model.BASELINES.glob("*.glsl")} == set(bench_model.HANDWRITTEN)
    assert hand_labels().count("hand-written") == len(bench_model.HANDWRITTEN)
    assert "float map(vec3 p)" in (bench_model.BASELINES / "csg.glsl").read_text()


def test_missing_baselines_skip_their_rows_with_a_message(tmp_path, monkeypatch):
    monkeypatch.setattr(bench_model, "BASELINES", tmp_path / "absent")
    assert hand_labels() == ["generated"] * len(bench_model.HANDWRITTEN)
    assert "source checkout" in bench_model.MISSING_BASELINES


def test_whole_hand_written_shader_draws_the_same_image():
    """The whole shader written by hand for the CSG scene shows what the generated one shows
    (same lights and look), so the bench's frame-time ratio compares like with like."""
    table = bench_model.run_whole((96, 54), frames=1, warmup=0)
    rows = [r for r in table.splitlines() if r.startswith("| csg |")]
    assert [r.split(" | ")[1] for r in rows] == ["generated", "generated, no coarse pass", "whole shader written by hand"]
    assert float(rows[1].split(" | ")[-1].rstrip(" %|")) < 0.5   # the coarse pass does not change the image
    assert float(rows[2].split(" | ")[-1].rstrip(" %|")) < 3.0   # nor does writing the shader by hand
