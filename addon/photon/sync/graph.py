"""A material's shader graph (Mix Shader / Add Shader nodes over BSDF and emission nodes) to the
native flat closure list, compiled as a DAG.

Each (node, group stack) is visited once: artists' graphs share sub-trees (one BSDF feeding
several Mix Shaders), and walking every path, as a recursive flattening does, takes time
exponential in the depth of such sharing. The walk is iterative (no recursion limit on a long
Add Shader chain) and takes time linear in the nodes and links reached.

A closure's native weight is a product of factors (native/src/photon/scene/material.h
`Closure::weight`: `fac` or `1 - fac`, each clamped to [0, 1]). Weights are propagated down the
DAG as {texture factors: constant}: the constant factors of a path multiply into one number,
the texture-driven ones stay symbolic. Contributions of paths with the same texture factors add
up (Mix(f, X, X) is X, as Cycles renders it); different texture products stay separate
entries, since the native weight cannot express their sum.
"""

from . import nodes
from .inputs import mix_factor_param, read_input

# Closures per material, as Cycles' MAX_CLOSURE default (kernel/types.h).
MAX_CLOSURES = 64
# Weight entries kept per node while propagating texture-driven weights: bounds the work when
# many different texture products meet (2^depth of them in a diamond of textured mixes).
MAX_ENTRIES_PER_NODE = 4 * MAX_CLOSURES
# A guard against a node group that contains itself (Blender refuses to make one).
MAX_GROUP_NESTING = 64

MAX_COPIES = 1e15
_SNAP = 1e-9  # sums of mix weights within this of a whole number are that number


class _Vertex:
    """One (node, group stack) of the DAG. `edges`: (child, constant, factor key or None) for
    the shader inputs of a Mix or Add Shader; `closure`: the closure of any other node."""

    __slots__ = ("node", "stack", "output", "fed", "edges", "closure", "weights", "done")

    def __init__(self, src, fed):
        self.node, self.stack = src.node, src.stack
        # The output socket that feeds a shader input, and the first (input, stack) it feeds:
        # a colour or value output there is read through that input (Cycles' Emission).
        self.output, self.fed = src.socket, fed
        self.edges = []
        self.closure = None
        self.weights = {}  # sorted tuple of texture factor keys -> summed constant weight
        self.done = False  # False while the depth-first walk is below this vertex


class _Compiler:
    def __init__(self, ctx, make_closure):
        self.ctx = ctx
        self.make_closure = make_closure
        self.vertices = {}
        self.leaves = []        # closure vertices in depth-first order (of their first path)
        self.postorder = []
        self.factors = {}       # texture factor key -> weight factor dict
        self.pruned = 0         # weight entries dropped by MAX_ENTRIES_PER_NODE

    def _shader_inputs(self, vertex):
        """(input socket, constant weight, factor key or None) of a Mix or Add Shader, reading
        its Fac once; None for a closure node."""
        node = vertex.node
        if node.type == 'ADD_SHADER':
            return [(node.inputs[0], 1.0, None), (node.inputs[1], 1.0, None)]
        if node.type != 'MIX_SHADER':
            return None
        # Mix Shader: (1 - fac) * first + fac * second. Constant factors of 0 or 1 prune.
        fac = read_input(node.inputs["Fac"], vertex.stack, mix_factor_param(), self.ctx)
        first, second = node.inputs[1], node.inputs[2]
        if isinstance(fac, float):
            return [(s, w, None) for s, w in ((first, 1.0 - fac), (second, fac)) if w > 0.0]
        out = []
        for shader, complement in ((first, True), (second, False)):
            key = ((fac["texture"], fac.get("channel", "COLOR"), complement) if "texture" in fac
                   else ("register", fac["register"], complement))
            self.factors[key] = {"fac": fac, "complement": complement}
            out.append((shader, 1.0, key))
        return out

    def _vertex(self, socket, stack):
        """The vertex feeding `socket`: (vertex, new) or (None, False) when nothing does."""
        src = nodes.source(socket, stack, self.ctx.links)
        if src.node is None:
            return None, False  # an unlinked shader input adds nothing (Cycles: black)
        # A shader node has one closure; a colour or value output is its own emission.
        key = (src.node, src.stack,
               None if src.socket.type == 'SHADER' else src.socket.identifier)
        vertex = self.vertices.get(key)
        if vertex is not None:
            if not vertex.done:  # a cycle (Blender marks such links invalid; a guard)
                self.ctx.warn_once(("cycle",), f"Material '{self.ctx.name}': shader nodes "
                                               f"form a loop; the looping link is ignored")
                return None, False
            return vertex, False
        if len(src.stack) > MAX_GROUP_NESTING:
            self.ctx.warn_once(("nesting",), f"Material '{self.ctx.name}': node groups nested "
                                             f"deeper than {MAX_GROUP_NESTING} are ignored")
            return None, False
        vertex = _Vertex(src, (socket, stack))
        self.vertices[key] = vertex
        return vertex, True

    def _enter(self, vertex):
        """Reads a newly reached vertex: its shader inputs, or its closure (a leaf)."""
        inputs = self._shader_inputs(vertex)
        if inputs is None:
            vertex.closure = self.make_closure(vertex)
            self.leaves.append(vertex)
            return iter(())
        return iter(inputs)

    def walk(self, socket):
        """Depth-first from `socket`, first inputs first; returns the root vertex or None."""
        root, _ = self._vertex(socket, ())
        if root is None:
            return None
        todo = [(root, self._enter(root))]
        while todo:
            vertex, inputs = todo[-1]
            for shader, constant, factor in inputs:
                child, new = self._vertex(shader, vertex.stack)
                if child is None:
                    continue
                vertex.edges.append((child, constant, factor))
                if new:
                    todo.append((child, self._enter(child)))
                    break
            else:
                vertex.done = True
                self.postorder.append(vertex)
                todo.pop()
        return root

    def propagate(self, root):
        """Pushes {texture factors: constant} from the root down, parents before children
        (reverse postorder is a topological order of a DAG)."""
        root.weights[()] = 1.0
        for vertex in reversed(self.postorder):
            weights = vertex.weights
            if len(weights) > MAX_ENTRIES_PER_NODE:
                keep = sorted(weights.items(), key=lambda kv: -kv[1])[:MAX_ENTRIES_PER_NODE]
                self.pruned += len(weights) - len(keep)
                kept = {k for k, _ in keep}
                vertex.weights = weights = {k: w for k, w in weights.items() if k in kept}
            for child, constant, factor in vertex.edges:
                into = child.weights
                for factors, weight in weights.items():
                    if factor is not None:
                        factors = tuple(sorted(factors + (factor,)))
                    into[factors] = into.get(factors, 0.0) + weight * constant


def _snap(weight):
    whole = round(weight)
    return float(whole) if abs(weight - whole) <= _SNAP * max(1.0, weight) else weight


def _pieces(weight):
    """A summed constant as native factors in [0, 1]: (whole count of weight-1 copies, and the
    fraction left, or 0). Add Shader sums can exceed 1 (Add(X, X) is 2X)."""
    # Nested Add(X, X) doubles per level: bound the count (all but 64 copies are dropped).
    weight = _snap(min(weight, MAX_COPIES))
    whole = int(weight)
    rest = _snap(weight - whole)
    return whole, (rest if rest > 0.0 else 0.0)


def collect_closures(surface, ctx, make_closure):
    """The closures feeding shader input `surface` of a material, each with its weight:
    [closure dict with "weight"]. `make_closure(vertex)` gives the closure dict of a vertex
    that is not a Mix or Add Shader (called once per node and group stack): a shader node, or a
    colour or value output linked straight into a shader input (`vertex.output`, read through
    the input `vertex.fed`)."""
    compiler = _Compiler(ctx, make_closure)
    root = compiler.walk(surface)
    if root is None:
        return []
    compiler.propagate(root)
    # Entries: [constant weight, copies, leaf, texture factors], in depth-first order.
    entries = []
    for leaf in compiler.leaves:
        for factors, weight in leaf.weights.items():
            whole, rest = _pieces(weight)
            if whole:
                entries.append([1.0, whole, leaf, factors])
            if rest:
                entries.append([rest, 1, leaf, factors])
    total = sum(e[1] for e in entries)
    if total > MAX_CLOSURES or compiler.pruned:
        _cap(entries, total, compiler.pruned, ctx)
    closures = []
    for weight, copies, leaf, factors in entries:
        for _ in range(copies):
            constant = [] if weight == 1.0 else [{"fac": weight, "complement": False}]
            closure = dict(leaf.closure)
            closure["weight"] = constant + [dict(compiler.factors[key]) for key in factors]
            closures.append(closure)
    return closures


def _cap(entries, total, pruned, ctx):
    """Keeps MAX_CLOSURES closures, in place. Rule: the largest constant weight first (the
    product of a closure's constant mix factors; its texture factors are at most 1, so this
    bounds its weight anywhere on the surface), ties to the closure reached first depth-first."""
    budget = MAX_CLOSURES
    for entry in sorted(entries, key=lambda e: -e[0]):  # stable: ties keep depth-first order
        entry[1] = min(entry[1], budget)
        budget -= entry[1]
    entries[:] = [e for e in entries if e[1] > 0]
    kept = sum(e[1] for e in entries)
    # Entries pruned on the way (MAX_ENTRIES_PER_NODE) make the count a lower bound.
    at_least = "at least " if pruned else ""
    ctx.reporter.warning(f"Material '{ctx.name}': its shader mixes make {at_least}{total} "
                         f"closures; rendering the {kept} with the largest mix weights and "
                         f"dropping {at_least}{total - kept} (Cycles' limit is {MAX_CLOSURES} "
                         f"too)")
