"""The layout: no import cycles, a short top level, few positional parameters, docstrings."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "unilateral"
#: Compiled kernels (numba signatures) are exempt from the parameter limit, and so are click
#: commands (one parameter per command-line option), recognised by their decorators.
EXEMPT = {"march/compiled.py", "lcp/pivoting.py"}


def is_click_command(node) -> bool:
    return any(any(word in ast.unparse(d) for word in ("click.", "command", "option", "argument"))
               for d in node.decorator_list)


def module_name(path: Path) -> str:
    parts = ["unilateral", *path.relative_to(PACKAGE).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imports_of(name: str, path: Path) -> set[str]:
    """Modules of the package that ``name`` imports, at module level or inside functions."""
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                root = ".".join(base + ([node.module] if node.module else []))
            else:
                root = node.module or ""
            # "from pkg import sub" imports the submodule pkg.sub if there is one
            targets = [f"{root}.{alias.name}" if f"{root}.{alias.name}" in MODULES else root
                       for alias in node.names]
        else:
            continue
        found.update(t for t in targets if t in MODULES and t != name)
    return found


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    state, stack = {}, []

    def visit(node):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state and (cycle := visit(nxt)):
                return cycle
        state[node] = "done"
        stack.pop()
        return None

    for node in sorted(graph):
        if node not in state and (cycle := visit(node)):
            return cycle
    return None


def test_there_is_no_import_cycle():
    graph = {name: imports_of(name, path) for name, path in MODULES.items()}
    # a package's __init__ importing its own submodules is how packages work; a submodule that
    # imports its own package's __init__ back would close a cycle and is caught below
    for name in graph:
        graph[name] = {t for t in graph[name] if not (MODULES[name].name == "__init__.py" and t.startswith(name + "."))}
    assert find_cycle(graph) is None, f"import cycle: {' -> '.join(find_cycle(graph))}"


def test_the_cycle_finder_finds_a_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_the_top_level_is_short_and_every_package_says_what_it_holds():
    top = [p.name for p in PACKAGE.glob("*.py")]
    assert len(top) <= 12, sorted(top)
    for init in PACKAGE.glob("*/__init__.py"):
        doc = ast.get_docstring(ast.parse(init.read_text()))
        assert doc and len(doc) > 40, f"{init.parent.name}/__init__.py has no docstring saying what it holds"


@pytest.mark.parametrize("path", sorted(p for p in MODULES.values()
                                        if str(p.relative_to(PACKAGE)) not in EXEMPT), ids=str)
def test_no_function_takes_more_than_seven_positional_parameters(path):
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and not is_click_command(node):
            names = [a.arg for a in node.args.posonlyargs + node.args.args if a.arg not in ("self", "cls")]
            assert len(names) <= 7, f"{node.name}({', '.join(names)}) in {path.name}"


# ---------------------------------------------------------------------- the house, as a ratchet
#: Limits of the house: a function's and a module's lines.
FUNCTION_MAX_LINES, MODULE_MAX_LINES = 80, 800
#: Pairs of packages that still import each other (module- or function-level), with the reason.
#: The list may only shrink: a new pair fails, and so does a listed pair that no longer imports.
PACKAGE_CYCLES = {
}
#: Modules over MODULE_MAX_LINES lines and functions over FUNCTION_MAX_LINES lines that are still
#: to be split (by line count when listed). The lists may only shrink: a new one, or a listed one
#: that grew, fails; a listed one that got short enough fails until it is taken off the list.
LONG_MODULES = {
}
LONG_FUNCTIONS = {
    "march/compiled.py:direct_steps": 151,
}


def package_of(module: str) -> str:
    """``unilateral.methods.direct`` -> ``methods``; a top-level module is its own package."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def package_pairs() -> set[tuple[str, str]]:
    """The pairs of packages (sorted names) that import each other."""
    edges = {(package_of(name), package_of(t)) for name, path in MODULES.items() for t in imports_of(name, path)}
    return {tuple(sorted((a, b))) for a, b in edges if a != b and (b, a) in edges}


def lengths():
    """Lines of every module and of every function (``path:name``) over the limits."""
    modules, functions = {}, {}
    for path in MODULES.values():
        rel, text = str(path.relative_to(PACKAGE)), path.read_text()
        if len(text.splitlines()) > MODULE_MAX_LINES:
            modules[rel] = len(text.splitlines())
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lines = node.end_lineno - node.lineno + 1
                if lines > FUNCTION_MAX_LINES:
                    functions[f"{rel}:{node.name}"] = max(lines, functions.get(f"{rel}:{node.name}", 0))
    return modules, functions


def test_no_new_pair_of_packages_imports_each_other():
    found = package_pairs()
    assert found <= set(PACKAGE_CYCLES), f"packages that import each other: {sorted(found - set(PACKAGE_CYCLES))}"
    assert set(PACKAGE_CYCLES) <= found, f"no longer a cycle, take off PACKAGE_CYCLES: {set(PACKAGE_CYCLES) - found}"


def test_the_pair_finder_finds_a_pair():
    edges = {"unilateral.a.x": {"unilateral.b.y"}, "unilateral.b.y": {"unilateral.a.z"}}
    pairs = {tuple(sorted((package_of(a), package_of(b)))) for a, ts in edges.items() for b in ts
             if any(package_of(c) == package_of(a) for c in edges.get(b, ()))}
    assert pairs == {("a", "b")} and package_of("unilateral.solve") == "solve"


@pytest.mark.parametrize("kind", ["modules", "functions"])
def test_no_module_or_function_grows_past_the_limits(kind):
    found = dict(zip(("modules", "functions"), lengths()))[kind]
    listed = LONG_MODULES if kind == "modules" else LONG_FUNCTIONS
    limit = MODULE_MAX_LINES if kind == "modules" else FUNCTION_MAX_LINES
    new = {k: v for k, v in found.items() if v > listed.get(k, limit)}
    assert not new, f"{kind} over {limit} lines (or longer than listed): {new}"
    done = sorted(set(listed) - set(found))
    assert not done, f"{kind} now within {limit} lines: take them off the list: {done}"


#: Imports of another package's underscore names still to be made public (importer, module, name).
#: The root package's ``_MATRIX_METHOD_NAMES``, ``_RULE_NAMES`` and ``_LCP_NAMES`` are shared on
#: purpose: the command line and the model-file schema check a name with them before numpy loads.
PRIVATE_IMPORTS = {
    ("unilateral.analysis.footings_example", "unilateral.figures.plots", "_figure"),
    ("unilateral.analysis.halfspace_example", "unilateral.figures.plots", "_figure"),
    ("unilateral.bench.report", "unilateral.figures.plots", "_figure"),
    ("unilateral.bench.report", "unilateral.figures.plots", "_styled"),
}
SHARED_ROOT_NAMES = {"_MATRIX_METHOD_NAMES", "_RULE_NAMES", "_LCP_NAMES"}


def private_imports() -> set[tuple[str, str, str]]:
    """``(importer, module, name)`` of every import of an underscore name of another package (an
    underscore module itself, ``_validate``, is the root package's and counts as its own)."""
    found = set()
    for name, path in MODULES.items():
        base = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.ImportFrom):
                continue
            parts = base.split(".")
            root = (".".join(parts[: len(parts) - node.level + 1] + ([node.module] if node.module else []))
                    if node.level else node.module or "")
            for alias in node.names:
                private = alias.name.startswith("_") and not alias.name.startswith("__")
                if not private or f"{root}.{alias.name}" in MODULES or alias.name in SHARED_ROOT_NAMES:
                    continue
                if root.startswith("unilateral") and package_of(root) != package_of(name):
                    found.add((name, root, alias.name))
    return found


def test_no_new_import_of_another_packages_underscore_names():
    found = private_imports()
    assert found <= PRIVATE_IMPORTS, f"imports of another package's private names: {sorted(found - PRIVATE_IMPORTS)}"
    assert PRIVATE_IMPORTS <= found, f"no longer imported, take off PRIVATE_IMPORTS: {PRIVATE_IMPORTS - found}"
