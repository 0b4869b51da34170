"""Expression strings never run code and are refused quickly when they are hostile or too big."""
import time
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg
from sdfgl import expr

MARK = Path("/tmp/sdfgl_expr_pwned")

HOSTILE = [
    ("import", "__import__('os').system('touch /tmp/sdfgl_expr_pwned')", r"unexpected character"),
    ("import no quotes", "__import__(os)", r"unknown function '__import__'"),
    ("attribute", "x.__class__.__bases__", r"attribute access is not allowed"),
    ("lambda", "lambda: 1", r"unexpected character ':'"),
    ("subscript", "x[0]", r"unexpected character '\['"),
    ("keyword arg", "sin(x=1)", r"unexpected character '='"),
    ("tower", "10**10**10", r"exponent 10000000000 is larger than 64"),
    ("huge constant", "(10**60)**60", r"beyond 10\*\*300"),
    ("factorial", "factorial(10**8)", r"unknown function 'factorial'"),
    ("deep parens", "(" * 200 + "x" + ")" * 200, r"nesting deeper than 40"),
    ("deep unary", "-" * 1500 + "x", r"nesting deeper than 40"),
    ("deep calls", "sin(" * 60 + "x" + ")" * 60, r"nesting deeper than 40"),
    ("long", "x+" * 1500 + "x", r"characters long \(limit 2000\)"),
    ("long number", "1" * 60, r"more than 40 digits"),
    ("floor", "floor(x)+y", r"unknown function 'floor'; allowed: abs, acos"),
    ("integral", "Integral(x, x)", r"unknown function 'Integral'"),
    ("empty", "   ", r"empty"),
    ("dangling", "x +", r"unexpected end"),
    ("two args", "sin(x, y)", r"sin\(\) takes one argument"),
    ("unknown symbol", "x + w", r"unknown symbol\(s\) w"),
]


def refused_within(seconds, call, pattern):
    """Assert ``call`` raises ParameterError matching ``pattern``; the fastest of three tries
    must be under ``seconds`` (the issue's bound; the minimum keeps a loaded machine's
    scheduling noise out). Returns the message."""
    best, msg = float("inf"), ""
    for _ in range(3):
        t0 = time.perf_counter()
        with pytest.raises(sg.ParameterError, match=pattern) as info:
            call()
        best, msg = min(best, time.perf_counter() - t0), str(info.value)
    assert best < seconds, f"refused after {best:.3f} s"
    return msg


@pytest.fixture(scope="module", autouse=True)
def _sympy_loaded():
    # time the refusals, not sympy's one-time import and set-up
    sg.displace_expr(sg.sphere(1), "0.01*sin(x)*(x + y + 1)**2", lipschitz=1)
    sg.parametric("s", "t", "s*t")
    yield


@pytest.mark.parametrize("name, text, pattern", HOSTILE, ids=[h[0] for h in HOSTILE])
@pytest.mark.parametrize("api", ["implicit", "displace_expr", "parametric"])
def test_hostile_expressions_are_refused_fast_with_a_message(api, name, text, pattern):
    if api == "parametric":
        text = text.replace("x", "s").replace("y", "t").replace("w", "q")
        pattern = pattern.replace(" w", " q")
    call = {"implicit": lambda: sg.implicit(text),
            "displace_expr": lambda: sg.displace_expr(sg.sphere(1), text),
            "parametric": lambda: sg.parametric(text, "t", "s")}[api]
    msg = refused_within(0.1, call, pattern)
    assert api.split("_")[0] in msg
    assert not MARK.exists()


def test_live_expressions_share_the_parser():
    r = sg.param(1.0, name="r")
    e = expr.parse_live("2*r - 0.5", {"r": r})
    assert float(e) == 1.5
    r.value = 2.0
    assert float(e) == 3.5
    for bad, pattern in [("r.value", "attribute"), ("__import__('os')", "unexpected character"),
                         ("q + 1", "unknown parameter 'q'"), ("r**100", "small whole powers"),
                         ("r / 0", "division by zero"), ("tanh(r)", "not available for live parameters")]:
        refused_within(0.1, lambda: expr.parse_live(bad, {"r": r}), pattern)
    assert abs(float(expr.parse_live("exp(r)", {"r": r})) - np.exp(2.0)) < 1e-12  # sg.exp over live values


def test_expansion_work_is_bounded_before_sympy_starts():
    refused_within(0.1, lambda: sg.displace_expr(sg.sphere(1), "0.001*(x + y + z + 1)**40"),
                   r"about 1.15e\+04 terms \(limit 2000\)")
    # a 40th power that needs no expansion is fine as an implicit surface (written as pow())
    node = sg.implicit("(x**2 + y**2 + z**2)**20 - 1", bounds=((-2, -2, -2), (2, 2, 2)))
    assert "pow(" in sg.compile(node, method="newton", ao=False)


def test_sympy_objects_outside_the_whitelist_name_the_function():
    import sympy as sp
    x, y = sp.symbols("x y")
    with pytest.raises(sg.ParameterError, match="function 'floor' is not supported"):
        sg.implicit(sp.floor(x) + y)
    with pytest.raises(sg.ParameterError, match="function 'Integral' is not supported"):
        sg.implicit(sp.Integral(x, x) + y)
    with pytest.raises(sg.ParameterError, match="exponent 100 is larger than 64"):
        sg.implicit(x ** 100 - y)


def test_valid_expressions_parse_like_python_precedence():
    import sympy as sp
    x, y, z = sp.symbols("x y z", real=True)
    vars_ = {"x": x, "y": y, "z": z}
    assert expr.parse_sympy("-x**2", vars_) == -(x ** 2)
    assert expr.parse_sympy("2**3**2", vars_) == 512
    assert expr.parse_sympy("x^2 + 1e-3*y", vars_) == x ** 2 + sp.Float("1e-3") * y
    assert expr.parse_sympy("sqrt(abs(x)) / (1 + pi)", vars_) == sp.sqrt(sp.Abs(x)) / (1 + sp.pi)
    assert expr.parse_sympy("x - y - z", vars_) == x - y - z
    assert expr.parse_sympy("x / y / z", vars_) == x / y / z


def test_glsl_printing_failures_name_the_function():
    import sympy as sp
    from sdfgl.nodes.implicit import glsl
    x = sp.Symbol("x", real=True)
    with pytest.raises(sg.ParameterError, match=r"implicit: cannot write the derivative of floor\(x\) in GLSL"):
        glsl(sp.Derivative(sp.floor(x), x), "implicit")
    with pytest.raises(sg.ParameterError, match=r"cannot write Integral in GLSL"):
        glsl(sp.Integral(sp.exp(x ** 2), x), "implicit")
