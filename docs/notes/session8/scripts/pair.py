"""The pair timing the session-8 scripts share: two prepared variants drawn strictly alternating."""
import statistics
from sdfgl.bench import FrameTimer, Variant


def alternate(timer: FrameTimer, pair: list[Variant], rounds: int, warm: int = 2) -> dict[str, float]:
    """Median ms per variant (keyed by scene) over ``rounds`` alternating draws, the first ``warm`` left out."""
    for v in pair:
        timer.prepare(v)
    ts: dict[str, list[float]] = {v.scene: [] for v in pair}
    for rnd in range(rounds):
        for v in pair:
            dt = timer.draw(v)
            if rnd >= warm:
                ts[v.scene].append(dt)
    return {k: 1000 * statistics.median(x) for k, x in ts.items()}
