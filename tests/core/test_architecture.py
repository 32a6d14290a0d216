"""The plugin's imports go one way: plugin -> provider -> algorithms -> (dependencies) -> core,
with no cycle, and core never imports qgis. Read from the sources with ast, imports inside
functions included."""
import ast
import os

import pytest

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PACKAGE = "roadsigns"
#: the shipped Python code, by layer: a module may import its own layer or lower ones only
LAYERS = {"": 0, "plugin": 0, "provider": 1, "gui": 1, "algorithms": 2, "dependencies": 3, "core": 4}


def module_name(root, path):
    """``core/ground/csf.py`` -> ``core.ground.csf``; ``__init__.py`` -> ``''`` (the package)."""
    parts = os.path.relpath(path, root)[:-3].split(os.sep)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def shipped_modules(root):
    """{module name: path} of the plugin's own code (not tests, scripts, devtools, bench)."""
    found = {}
    for top in LAYERS:
        path = os.path.join(root, top + ".py") if top else os.path.join(root, "__init__.py")
        if os.path.isfile(path):
            found[module_name(root, path)] = path
        folder = os.path.join(root, top)
        if top and os.path.isdir(folder):
            for dirpath, _, files in os.walk(folder):
                for name in files:
                    if name.endswith(".py"):
                        found[module_name(root, os.path.join(dirpath, name))] = os.path.join(dirpath, name)
    return found


def _resolve(importer, is_package, node):
    """Absolute module names (inside the plugin, '' = the package) an import node refers to."""
    if isinstance(node, ast.Import):
        names = [a.name for a in node.names]
        return [n[len(PACKAGE) + 1:] if n.startswith(PACKAGE + ".") else "" for n in names
                if n == PACKAGE or n.startswith(PACKAGE + ".")]
    if node.level == 0:
        if node.module and (node.module == PACKAGE or node.module.startswith(PACKAGE + ".")):
            base = node.module[len(PACKAGE) + 1:]
            return [base + "." + a.name if base else a.name for a in node.names] + [base]
        return []
    parts = importer.split(".") if importer else []
    if not is_package:
        parts = parts[:-1]
    parts = parts[:len(parts) - (node.level - 1)] if node.level > 1 else parts
    base = ".".join(parts + ([node.module] if node.module else []))
    return [base] + [(base + "." if base else "") + a.name for a in node.names]


def import_graph(root):
    """{module: set of plugin modules it imports} and {module: imports qgis}."""
    modules = shipped_modules(root)
    graph, uses_qgis = {}, {}
    for name, path in modules.items():
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        targets, qgis = set(), False
        is_package = path.endswith("__init__.py")
        for node in ast.walk(tree):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                top = node.names[0].name if isinstance(node, ast.Import) else (node.module or "")
                if getattr(node, "level", 0) == 0 and top.split(".")[0] in ("qgis", "processing"):
                    qgis = True
                targets.update(t for t in _resolve(name, is_package, node) if t in modules and t != name)
        graph[name], uses_qgis[name] = targets, qgis
    return graph, uses_qgis


def cycles(graph):
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def layer(module):
    return LAYERS[module.split(".")[0]]


def upward_imports(graph):
    """(importer, imported) pairs that import a higher layer."""
    return sorted((a, b) for a, targets in graph.items() for b in targets if layer(b) < layer(a))


def test_plugin_imports_have_no_cycle_and_go_one_way():
    graph, _ = import_graph(REPO_ROOT)
    assert {"plugin", "provider.provider", "algorithms.base", "core.geometry"} <= set(graph)
    assert cycles(graph) == []
    assert upward_imports(graph) == []


def test_core_never_imports_qgis():
    _, uses_qgis = import_graph(REPO_ROOT)
    core = [m for m in uses_qgis if m.startswith("core")]
    assert len(core) > 10
    assert [m for m in core if uses_qgis[m]] == []


@pytest.fixture
def tangled(tmp_path):
    """A tiny plugin tree with a cycle in core and an algorithm importing the provider."""
    files = {
        "__init__.py": "",
        "plugin.py": "from .provider import provider\n",
        "provider/__init__.py": "",
        "provider/provider.py": "from ..algorithms import base\n",
        "algorithms/__init__.py": "",
        "algorithms/base.py": "def f():\n    from ..provider.provider import X\n",
        "core/__init__.py": "",
        "core/a.py": "from . import b\n",
        "core/b.py": "from .a import thing\nimport qgis.core\n",
    }
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    return str(tmp_path)


def test_the_check_finds_a_cycle_an_upward_import_and_qgis_in_core(tangled):
    graph, uses_qgis = import_graph(tangled)
    found = cycles(graph)
    assert ["core.a", "core.b"] in found
    assert ["algorithms.base", "provider.provider"] in found
    assert ("algorithms.base", "provider.provider") in upward_imports(graph)
    assert uses_qgis["core.b"] and not uses_qgis["core.a"]
