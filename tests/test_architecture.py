"""The package's architecture, checked: one-way imports between layers, no import cycles, and a
stated purpose for every sub-package (docs/architecture.md describes the same rules)."""
import ast
import pathlib

import pytest

SRC = pathlib.Path(__file__).resolve().parents[1] / "src" / "stitchswitch"

#: Layers, bottom to top: a module may import its own layer and the layers below it, never above.
LAYERS = [
    ("stitchswitch.errors", "stitchswitch.files", "stitchswitch.blas", "stitchswitch.executor",
     "stitchswitch.native_output"),
    ("stitchswitch.reduced.model",),
    ("stitchswitch.reduced.solvers",),
    ("stitchswitch.reduced.calibration", "stitchswitch.reduced.design_space"),
    ("stitchswitch.fem_reference", "stitchswitch.validation"),
    ("stitchswitch.layout.embroidery",),
    ("stitchswitch.layout.garment",),
    ("stitchswitch.layout.check",),
    ("stitchswitch.layout.fabrication",),
    ("stitchswitch.preview3d",),
    ("stitchswitch.demos",),
    ("stitchswitch.studio",),
    ("stitchswitch.cli",),
]
#: Modules placed by name: the package root re-exports the model's entry points (stitchswitch.solve,
#: lazily from the solvers) and ``__version__``; ``__main__`` runs the CLI; ``reduced`` and ``layout``
#: are folders whose ``__init__`` only describes them.
PLACED = {"stitchswitch": 2, "stitchswitch.__main__": len(LAYERS) - 1,
          "stitchswitch.reduced": 1, "stitchswitch.layout": 5}
MAX_MODULES_PER_FOLDER = 12


def module_name(path: pathlib.Path) -> str:
    parts = ("stitchswitch",) + path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports(path: pathlib.Path, *, top_level_only: bool):
    """(imported module, line) for every ``stitchswitch`` import of the file; with
    ``top_level_only`` only those run at import time (not inside functions)."""
    tree = ast.parse(path.read_text())
    nodes = tree.body if top_level_only else list(ast.walk(tree))
    this = module_name(path)
    package = this if path.name == "__init__.py" else this.rpartition(".")[0]
    for node in nodes:
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            base = node.module
        elif isinstance(node, ast.ImportFrom) and node.level:
            base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1] + [node.module or ""])
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("stitchswitch"):
                    yield alias.name, node.lineno
            continue
        else:
            continue
        if not base.startswith("stitchswitch"):
            continue
        for alias in node.names:         # "from pkg import module" imports pkg.module
            sub = f"{base.rstrip('.')}.{alias.name}"
            yield (sub if (SRC.parent / (sub.replace(".", "/") + ".py")).exists()
                   or (SRC.parent / sub.replace(".", "/")).is_dir() else base.rstrip(".")), node.lineno


def layer(name: str) -> int | None:
    if name in PLACED:
        return PLACED[name]
    best = None
    for k, prefixes in enumerate(LAYERS):
        for p in prefixes:
            if (name == p or name.startswith(p + ".")) and (best is None or len(p) > best[1]):
                best = (k, len(p))
    return None if best is None else best[0]


MODULES = sorted(p for p in SRC.rglob("*.py") if "__pycache__" not in p.parts)


def test_every_module_belongs_to_a_layer():
    assert [module_name(p) for p in MODULES if layer(module_name(p)) is None] == []


def test_imports_run_one_way():
    upward = []
    for path in MODULES:
        me = module_name(path)
        for target, line in imports(path, top_level_only=False):
            if layer(target) is not None and layer(target) > layer(me):
                upward.append(f"{me}:{line} imports {target} (a higher layer)")
    assert upward == []


def _cycles(top_level_only: bool):
    graph = {module_name(p): {t for t, _ in imports(p, top_level_only=top_level_only)} for p in MODULES}
    seen, stack, found = set(), [], []

    def visit(node, on_path):
        seen.add(node)
        stack.append(node)
        on_path.add(node)
        for nxt in sorted(graph.get(node, ())):
            if nxt in on_path:
                found.append(stack[stack.index(nxt):] + [nxt])
            elif nxt not in seen and nxt in graph:
                visit(nxt, on_path)
        on_path.discard(node)
        stack.pop()

    for node in sorted(graph):
        if node not in seen:
            visit(node, set())
    # a package's __init__ importing its own submodules is not a cycle of concern
    return [c for c in found if not all(m.startswith(c[0] + ".") or m == c[0] for m in c[1:])]


@pytest.mark.parametrize("top_level_only", [True, False], ids=["import-time", "with-function-imports"])
def test_no_import_cycles(top_level_only):
    assert _cycles(top_level_only) == []


def test_every_package_states_its_purpose():
    for init in SRC.rglob("__init__.py"):
        if "__pycache__" in init.parts:
            continue
        doc = ast.get_docstring(ast.parse(init.read_text()))
        assert doc and len(doc.split()) >= 8, f"{init.relative_to(SRC)} has no docstring stating its purpose"


def test_folders_stay_small():
    for folder in [SRC, *(p for p in SRC.rglob("*") if p.is_dir() and (p / "__init__.py").exists())]:
        modules = [p for p in folder.glob("*.py") if p.name not in ("__init__.py", "__main__.py")]
        assert len(modules) <= MAX_MODULES_PER_FOLDER, f"{folder.relative_to(SRC.parent)}: {len(modules)} modules"


def test_no_issue_numbers_in_code():
    import re

    pattern = re.compile(r"\bissue\s+#?\d+", re.IGNORECASE)
    hits = [f"{p.relative_to(SRC)}:{n}" for p in MODULES
            for n, line in enumerate(p.read_text().splitlines(), 1) if pattern.search(line)]
    assert hits == []
