"""The package's layers, read from the source (the AST of every module in sdfgl/): who may
import whom, how long a module may grow, and that private names stay in their module."""
import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "sdfgl"
SOURCE_LEAF = "sdfgl.compiler.source"  # the one module of the compiler that sdfgl.gl imports
COMPILER_MAX_LINES = 350
MODULE_MAX_LINES = 600


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out


MODULES = _modules()


def _type_checking_only(tree: ast.AST) -> set[int]:
    """ids of the import nodes inside ``if TYPE_CHECKING:`` blocks (type hints only)."""
    hidden: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            hidden.update(id(n) for stmt in node.body for n in ast.walk(stmt))
    return hidden


def _imports(name: str) -> list[tuple[int, str, str, bool]]:
    """(line, imported module, imported name or "", at run time) for every import in module ``name``."""
    path = MODULES[name]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    hidden = _type_checking_only(tree)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name, "", id(node) not in hidden) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - (node.level - 1)]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            for a in node.names:
                sub = f"{module}.{a.name}"
                target = sub if sub in MODULES else module  # `from . import x` names a module
                out.append((node.lineno, target, "" if target == sub else a.name, id(node) not in hidden))
    return out


def _inside(module: str, package: str) -> bool:
    return module == package or module.startswith(package + ".")


def test_every_module_is_seen():
    assert {"sdfgl.gl.programs", "sdfgl.nodes.base", "sdfgl.compiler.generate", SOURCE_LEAF} <= set(MODULES)


def test_gl_imports_nothing_of_the_compiler_but_the_source_leaf():
    bad = [f"{name}:{line} imports {target}" for name in MODULES if _inside(name, "sdfgl.gl")
           for line, target, _, _ in _imports(name) if _inside(target, "sdfgl.compiler") and target != SOURCE_LEAF]
    assert not bad, "sdfgl.gl may import only sdfgl.compiler.source of the compiler:\n" + "\n".join(bad)


def test_the_source_leaf_imports_nothing_else_of_the_compiler():
    bad = [f"line {line}: {target}" for line, target, _, _ in _imports(SOURCE_LEAF) if _inside(target, "sdfgl.compiler")]
    assert not bad, f"{SOURCE_LEAF} must stay a leaf of the compiler:\n" + "\n".join(bad)


def test_the_compiler_package_init_imports_nothing():
    # importing the leaf runs sdfgl/compiler/__init__.py first: it must load nothing else
    assert not _imports("sdfgl.compiler")


def test_nodes_never_import_the_compiler_at_run_time():
    bad = [f"{name}:{line} imports {target}" for name in MODULES if _inside(name, "sdfgl.nodes")
           for line, target, _, runtime in _imports(name) if runtime and _inside(target, "sdfgl.compiler")]
    assert not bad, ("sdfgl.nodes may import the compiler only under `if TYPE_CHECKING:` (for type hints):\n"
                     + "\n".join(bad))


def _lines(path: Path) -> int:
    return len(path.read_text(encoding="utf-8").splitlines())


def test_compiler_modules_are_small():
    big = [f"{name}: {_lines(path)} lines" for name, path in MODULES.items()
           if _inside(name, "sdfgl.compiler") and _lines(path) > COMPILER_MAX_LINES]
    assert not big, f"compiler modules over {COMPILER_MAX_LINES} lines (split them by job):\n" + "\n".join(big)


def test_no_module_is_over_the_size_limit():
    big = [f"{name}: {_lines(path)} lines" for name, path in MODULES.items() if _lines(path) > MODULE_MAX_LINES]
    assert not big, f"modules over {MODULE_MAX_LINES} lines (split them by job):\n" + "\n".join(big)


def test_no_private_name_is_imported_across_modules():
    bad = [f"{name}:{line} imports {imported} from {target}" for name in MODULES
           for line, target, imported, _ in _imports(name)
           if _inside(target, "sdfgl") and imported.startswith("_") and not imported.startswith("__")]
    assert not bad, ("private names imported from another module (make each public with a real name and a "
                     "docstring, or keep it local):\n" + "\n".join(bad))


@pytest.mark.parametrize("name", ["sdfgl.gl.programs", "sdfgl.nodes.booleans"])
def test_the_reader_resolves_relative_imports(name):
    # the checks above only hold if relative imports resolve to the modules they name
    targets = {t for _, t, _, _ in _imports(name)}
    assert "sdfgl.errors" in targets or "sdfgl.compiler.source" in targets
