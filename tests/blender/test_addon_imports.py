"""The add-on's modules import each other without a cycle, only __init__.py imports engine.py (the
RenderEngine class delegates to the modules that do the work; nothing depends on it), and only
native.py imports the native module _photon. The files are parsed with ast: no Blender needed.

Every import counts, module-level or inside a function (a function-level import that dodges a
circle at load time still makes the two modules depend on each other): `from . import x`,
`from .x import y`, `from .. import x`, and absolute `photon.` imports."""

import ast
from pathlib import Path

ADDON = Path(__file__).resolve().parents[2] / "addon" / "photon"
PACKAGE = ADDON.name
# The compiled module inside the package (no .py source): it imports nothing of the add-on.
NATIVE_EXTENSION = f"{PACKAGE}._photon"
NATIVE_HANDLE = f"{PACKAGE}.native"
ENGINE = f"{PACKAGE}.engine"


def _module_names():
    """{dotted module name: path} of every .py file of the add-on (a package is its
    __init__.py)."""
    names = {}
    for path in sorted(ADDON.rglob("*.py")):
        parts = [PACKAGE, *path.relative_to(ADDON).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts.pop()
        names[".".join(parts)] = path
    return names


def _ancestors(name):
    """'photon.sync.cache' -> ['photon.sync', 'photon']."""
    parts = name.split(".")
    return [".".join(parts[:i]) for i in range(len(parts) - 1, 0, -1)]


def _imports(name, path, known):
    """The add-on modules (and the native extension) `name` imports, anywhere in its file."""
    is_package = path.name == "__init__.py"
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found = set()

    def add(target):
        found.add(target)
        # Importing photon.sync.cache first runs photon.sync (its __init__.py); packages the
        # importer sits in are already being imported, so they add no dependency.
        for package in _ancestors(target):
            if package not in _ancestors(name) and package != name:
                found.add(package)

    for node in ast.walk(tree):  # module level, functions, classes and methods alike
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = name if is_package else name.rpartition(".")[0]
                for _ in range(node.level - 1):
                    base = base.rpartition(".")[0]
                target = f"{base}.{node.module}" if node.module else base
            elif node.module and (node.module == PACKAGE
                                  or node.module.startswith(PACKAGE + ".")):
                target = node.module
            else:
                continue
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                if sub in known or sub == NATIVE_EXTENSION:
                    add(sub)  # a submodule
                else:
                    add(target)  # a name defined by the module itself (or its __init__.py)
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == PACKAGE or alias.name.startswith(PACKAGE + "."):
                    add(alias.name)
    found.discard(name)
    return found


def import_graph():
    """{module: set of add-on modules it imports}; the native extension appears only as a
    target."""
    known = _module_names()
    return {name: _imports(name, path, known) for name, path in known.items()}


def _cycles(graph):
    """The strongly connected components of more than one module (or a module importing
    itself), each as a sorted list: every import cycle lies within one."""
    index, low, on_stack, stack, components = {}, {}, set(), [], []

    def visit(node):
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for succ in sorted(graph.get(node, ())):
            if succ not in graph:
                continue
            if succ not in index:
                visit(succ)
                low[node] = min(low[node], low[succ])
            elif succ in on_stack:
                low[node] = min(low[node], index[succ])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1 or node in graph.get(node, ()):
                components.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return components


def _shortest_cycles(graph, component):
    """The shortest import cycle through each module of `component`, each once, as
    'a -> b -> a' (from its alphabetically first module)."""
    members = set(component)
    cycles = []
    for start in component:
        parent, queue = {}, [start]
        while queue and start not in parent:  # breadth first, back to `start`
            node = queue.pop(0)
            for succ in sorted(graph[node]):
                if succ in members and succ not in parent:
                    parent[succ] = node
                    queue.append(succ)
        path = [start]
        while True:
            path.append(parent[path[-1]])
            if path[-1] == start:
                break
        path.reverse()  # start -> ... -> start
        ring = path[:-1]
        first = ring.index(min(ring))
        cycle = " -> ".join(ring[first:] + ring[:first] + [ring[first]])
        if cycle not in cycles:
            cycles.append(cycle)
    return cycles


def test_graph_is_read():
    """The parser finds the imports it is meant to check (a broken parser would pass the
    others vacuously)."""
    graph = import_graph()
    assert ENGINE in graph and PACKAGE in graph
    assert ENGINE in graph[PACKAGE], graph[PACKAGE]
    assert f"{PACKAGE}.sync.scene" in graph[f"{PACKAGE}.sync"]
    assert sum(len(targets) for targets in graph.values()) > len(graph)


def test_no_import_cycle():
    graph = import_graph()
    cycles = [cycle for component in _cycles(graph)
              for cycle in _shortest_cycles(graph, component)]
    assert not cycles, "import cycles in the add-on:\n" + "\n".join(cycles)


def test_only_init_imports_engine():
    graph = import_graph()
    importers = sorted(name for name, targets in graph.items()
                       if ENGINE in targets and name != PACKAGE)
    assert not importers, f"{ENGINE} is imported by {importers}: only {PACKAGE}/__init__.py " \
                          f"registers it; shared code belongs in the modules it delegates to"


def test_only_native_imports_the_native_module():
    graph = import_graph()
    assert NATIVE_HANDLE in graph, f"{NATIVE_HANDLE} holds the native module"
    importers = sorted(name for name, targets in graph.items()
                       if NATIVE_EXTENSION in targets and name != NATIVE_HANDLE)
    assert not importers, f"{NATIVE_EXTENSION} is imported by {importers}: use " \
                          f"{NATIVE_HANDLE}"
