"""Shader AOVs (View Layer > Shader AOV): the AOV Output nodes of a material's or the world's
node tree as the native AOV list, [{"name", "type": "COLOR" | "VALUE", "value": input}].

As in Cycles (OutputAOVNode::simplify_settings), a node writes the view layer's AOV of its name
and kind (its Color input into a colour AOV, its Value input into a value AOV), inside node
groups too; a node whose name the view layer does not list compiles to nothing, so an unused
AOV Output costs no shading time. The native film writes the values at the camera's first hits,
the world's where camera rays leave the scene (native/src/photon/integrators/data_passes.h)."""

from . import nodes
from .inputs import Param, read_input

# The deepest node group nesting searched for AOV Output nodes (Blender forbids recursion; this
# bounds pathological files).
_MAX_GROUP_DEPTH = 32
_BIG = 3.0e38  # AOV values are written as computed: only non-finite constants are replaced
_PARAMS = {'COLOR': Param("aov", 'color', -_BIG, _BIG, [0.0, 0.0, 0.0]),
           'VALUE': Param("aov", 'scalar', -_BIG, _BIG, 0.0)}


def aov_name(node):
    """The AOV name of an AOV Output node: `aov_name` since Blender 4.0, `name` before (where
    the node's own name is hidden behind it)."""
    name = getattr(node, "aov_name", None)
    return node.name if name is None else name


def output_nodes(tree, stack=(), depth=0):
    """(node, group stack) of every unmuted AOV Output node in `tree` and the groups it uses."""
    if tree is None or depth > _MAX_GROUP_DEPTH:
        return
    for node in tree.nodes:
        if getattr(node, "mute", False):
            continue
        if node.type == 'OUTPUT_AOV':
            yield node, stack
        elif node.type == 'GROUP' and getattr(node, "node_tree", None) is not None:
            yield from output_nodes(node.node_tree, stack + (node,), depth + 1)


def _socket(node, kind):
    return node.inputs.get("Color" if kind == 'COLOR' else "Value")


def wanted_outputs(tree, wanted):
    """(node, group stack, kind) of the AOV Output nodes in `tree` that write one of the view
    layer's AOVs `wanted` ({name: 'COLOR' | 'VALUE'})."""
    if not wanted:
        return []
    found = []
    for node, stack in output_nodes(tree):
        kind = wanted.get(aov_name(node))
        if kind is not None and _socket(node, kind) is not None:
            found.append((node, stack, kind))
    return found


def is_linked(node, stack, kind):
    """Whether the input an AOV Output node writes is fed by a node."""
    return nodes.source(_socket(node, kind), stack).node is not None


def read_outputs(outputs, ctx):
    """The native AOV list of wanted_outputs(); inputs fed by nodes are compiled into ctx's
    program."""
    return [{"name": aov_name(node), "type": kind,
             "value": read_input(_socket(node, kind), stack, _PARAMS[kind], ctx)}
            for node, stack, kind in outputs]


def material_aovs(tree, wanted, ctx):
    """The native AOV list of a material's node tree for the view layer's AOVs `wanted`."""
    return read_outputs(wanted_outputs(tree, wanted), ctx)


def plain_value(value, kind):
    """An AOV input without its program register (when the program cannot be compiled)."""
    if isinstance(value, dict) and "register" in value:
        fallback = value.get("value")
        if fallback is None:
            return [0.0, 0.0, 0.0] if kind == 'COLOR' else 0.0
        return fallback
    return value
