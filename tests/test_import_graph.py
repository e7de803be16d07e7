"""The package's own import graph has no circle: module A importing B importing ... A.

The graph is read from the source (the AST of every module): imports at module level and
inside functions, absolute and relative, ``from . import x`` resolved to the submodule x.
"""
import ast
from pathlib import Path

import shell_adhesion

PACKAGE = "shell_adhesion"
ROOT = Path(shell_adhesion.__file__).parent


def module_names(root=ROOT, package=PACKAGE) -> dict:
    """Dotted module name -> its source file, for every module of the package."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        parts = list(path.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join([package, *parts])] = path
    return out


def _resolve(importer: str, is_package: bool, level: int, module) -> str:
    """The absolute name of `from <level dots><module> import ...` in `importer`."""
    if level == 0:
        return module
    base = importer.split(".")
    base = base[: len(base) - level + (1 if is_package else 0)]
    return ".".join(base + ([module] if module else []))


def imports_of(name: str, source: str, is_package: bool, modules) -> set:
    """The package's modules that module `name` imports, anywhere in its source."""
    found = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(name, is_package, node.level, node.module)
            # `from pkg import sub` imports the submodule pkg.sub if there is one
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base
                       for a in node.names]
        else:
            continue
        for t in targets:
            while t and t not in modules:      # a name inside a module: that module
                t = t.rpartition(".")[0]
            if t and t != name:
                found.add(t)
    return found


def import_graph(root=ROOT, package=PACKAGE) -> dict:
    """Module -> the set of the package's modules it imports."""
    modules = module_names(root, package)
    return {m: imports_of(m, p.read_text(), p.name == "__init__.py", modules)
            for m, p in modules.items()}


def find_cycle(graph: dict):
    """One circle of `graph` as a list [a, b, ..., a], or None (depth-first search)."""
    state, stack = {}, []

    def visit(node):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == "open":
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        stack.pop()
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def test_cycle_finder_finds_a_circle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b", "c"}, "b": {"c"}, "c": set()}) is None
    assert find_cycle({"a": {"a"}}) == ["a", "a"]


def test_resolves_relative_and_function_level_imports(tmp_path):
    pkg = tmp_path / "toy"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("from . import b\n")
    (pkg / "sub" / "a.py").write_text("def f():\n    from .b import g\n")
    (pkg / "sub" / "b.py").write_text("from toy.sub.a import f\ng = 1\n")
    graph = import_graph(pkg, "toy")
    assert graph["toy.sub"] == {"toy.sub.b"}
    assert graph["toy.sub.a"] == {"toy.sub.b"}
    assert graph["toy.sub.b"] == {"toy.sub.a"}
    cycle = find_cycle(graph)
    assert cycle[0] == cycle[-1] and set(cycle) == {"toy.sub.a", "toy.sub.b"}


def test_the_package_has_no_import_circle():
    cycle = find_cycle(import_graph())
    assert cycle is None, "import circle: " + " -> ".join(cycle)
