"""Shader node inputs to native Input values: a constant (float or [r, g, b]) or an image
texture lookup {"texture": index, "channel": "COLOR" | "ALPHA"}.

Whatever cannot be read (unsupported nodes, missing images, NaN values) is reported once and
falls back to its nearest meaning, never to silent black or magenta."""

import functools
import math

from ..native import native_module
from . import nodes

DEFAULT_COLOR = (0.8, 0.8, 0.8)
FALLBACK_TEXTURE_COLOR = [0.8, 0.8, 0.8]  # a missing image: neutral grey, not magenta

# Nodes that only carry texture coordinates in front of an Image Texture.
COORDINATE_NODES = {'UVMAP', 'TEX_COORD', 'MAPPING'}


class MaterialContext:
    """State of one material's conversion: its name for warnings, the texture table, and what
    has already been reported."""

    def __init__(self, material_name, reporter, textures, kind="Material"):
        self.name = material_name
        self.kind = kind  # what warnings call the owner: "Material" or "World"
        self.reporter = reporter
        self.textures = textures
        self.reported = set()
        self.ignored_principled = []  # "Input (node)" entries for the one Principled warning
        self.links = nodes.LinkIndex()
        self._program = None

    @property
    def program(self):
        """The material's ProgramBuilder (shader_program.py), made on first use."""
        if self._program is None:
            from .shader_program import ProgramBuilder
            self._program = ProgramBuilder(self)
        return self._program

    def use_program(self, builder):
        """Compiles inputs into `builder` (the world's ProgramBuilder) instead of a new one."""
        self._program = builder

    def program_dict(self):
        return self._program.program() if self._program is not None else None

    def where(self, node, stack):
        return f"{self.kind} '{self.name}': node '{nodes.node_path(node, stack)}'"

    def warn_once(self, key, message):
        if key not in self.reported:
            self.reported.add(key)
            self.reporter.warning(message)


def _finite_clamp(value, lo, hi, fallback, ctx, what):
    if not math.isfinite(value):
        ctx.warn_once(("value", what), f"Material '{ctx.name}': {what} is not a finite number; "
                                       f"using {fallback:g}")
        return fallback
    if value < lo or value > hi:
        clamped = min(max(value, lo), hi)
        ctx.warn_once(("value", what), f"Material '{ctx.name}': {what} is {value:g}, outside "
                                       f"[{lo:g}, {hi:g}]; using {clamped:g}")
        return clamped
    return value


def clamp_constant(value, kind, lo, hi, fallback, ctx, what):
    """A finite constant within [lo, hi] for a scalar or per channel for a colour."""
    if kind == 'scalar':
        return float(_finite_clamp(float(value), lo, hi, fallback, ctx, what))
    fallback = fallback if isinstance(fallback, (list, tuple)) else [fallback] * 3
    return [float(_finite_clamp(float(value[i]), lo, hi, fallback[i], ctx, what))
            for i in range(3)]


def _luminance(rgb):
    # Blender's implicit colour -> float conversion (Rec.709 luma of the scene-linear colour).
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]


def socket_constant(socket, kind):
    """A socket's default_value as a scalar or [r, g, b], converting like Blender does."""
    value = getattr(socket, "default_value", None)
    if value is None:  # e.g. a shader socket
        return None
    try:
        channels = [float(value[i]) for i in range(min(3, len(value)))]
    except TypeError:
        channels = [float(value)]
    if kind == 'scalar':
        return channels[0] if len(channels) == 1 else _luminance(channels)
    return channels * 3 if len(channels) == 1 else (channels + [0.0, 0.0])[:3]


class Param:
    """How one native param is read: its native name, scalar or colour, valid range and
    Blender's default (used when nothing better is known)."""

    def __init__(self, name, kind, lo, hi, default):
        self.name, self.kind, self.lo, self.hi, self.default = name, kind, lo, hi, default


def _scalar_param(name, spec):
    return Param(name, 'scalar', spec["min"], spec["max"], spec["default"])


@functools.lru_cache(maxsize=None)
def closures_by_name():
    """{closure type: (closure type, [(socket names, Param), ...], bpy node type)}: the core's one
    table of material inputs (native/src/photon/scene/material_params.cpp), read once."""
    table = {}
    for closure in native_module().material_parameters():
        params = []
        for p in closure["params"]:
            default = list(p["default"]) if p["kind"] == 'color' else p["default"]
            params.append((tuple(p["sockets"]),
                           Param(p["key"], p["kind"], p["min"], p["max"], default)))
        table[closure["closure"]] = (closure["closure"], params, closure["node"])
    return table


@functools.lru_cache(maxsize=None)
def closure_table():
    """{bpy node type: (closure type, [(socket names, Param), ...])}; where two closures convert
    the same node type (Principled v1 and v2) the first, and materials.py picks by the node's
    sockets."""
    table = {}
    for name, params, node in closures_by_name().values():
        table.setdefault(node, (name, params))
    return table


def closure_param(node_type, key):
    """The Param `key` of the closure converted from nodes of `node_type`."""
    return next(param for _, param in closure_table()[node_type][1] if param.name == key)


@functools.lru_cache(maxsize=None)
def mix_factor_param():
    return _scalar_param("fac", native_module().MIX_FACTOR)


@functools.lru_cache(maxsize=None)
def normal_map_strength_param():
    return _scalar_param("strength", native_module().NORMAL_MAP_STRENGTH)


def read_input(socket, stack, param, ctx):
    """The native value of input `socket` (of a node reached through `stack`) for `param`."""
    node = socket.node
    what = f"input '{socket.name}' of node '{nodes.node_path(node, stack)}'"
    src = nodes.source(socket, stack, ctx.links)
    if src.node is None:
        value = socket_constant(src.socket, param.kind)
        if value is None:
            value = param.default
        return clamp_constant(value, param.kind, param.lo, param.hi, param.default, ctx, what)
    return _from_node(src, socket, param, ctx, what, depth=0)


def _plain_image(node, stack, ctx):
    """An Image Texture read at the active UV map with a flat projection: the texture lookup
    Inputs express without a program."""
    if node.type != 'TEX_IMAGE' or node.projection != 'FLAT':
        return False
    socket = node.inputs.get("Vector")
    for _ in range(16):
        src = nodes.source(socket, stack, ctx.links) if socket is not None else None
        if src is None or src.node is None:
            return True
        if src.node.type == 'UVMAP' and not src.node.uv_map:
            return True
        if src.node.type == 'TEX_COORD' and src.output_name == "UV":
            return True
        if src.node.type == 'MAPPING' and _identity_mapping(src.node):
            socket, stack = src.node.inputs.get("Vector"), src.stack
            continue
        return False
    return False


def _from_program(src, fed, param, ctx, fallback):
    """An input computed by the material's shader program."""
    kind = 'float' if param.kind == 'scalar' else 'color'
    outputs = ctx.program.compile(src.node, src.stack)
    found = outputs.get(src.socket.identifier)
    if found is None:
        return fallback
    reg = ctx.program.convert(found[0], found[1], kind)
    return {"register": reg, "value": fallback}


def _from_node(src, fed, param, ctx, what, depth):
    node, kind = src.node, param.kind
    fallback = socket_constant(fed, kind)
    if fallback is None:
        fallback = param.default
    fallback = clamp_constant(fallback, kind, param.lo, param.hi, param.default, ctx, what)
    if (node.type not in {'TEX_IMAGE', 'RGB', 'VALUE'} and
            ctx.program.verdict(node, src.stack) is None) or (
            node.type == 'TEX_IMAGE' and not _plain_image(node, src.stack, ctx)):
        return _from_program(src, fed, param, ctx, fallback)
    if node.type == 'TEX_IMAGE':
        channel = "ALPHA" if src.output_name == "Alpha" else "COLOR"
        check_coordinates(node, src.stack, ctx)
        index = ctx.textures.texture(node, ctx.where(node, src.stack))
        if index is not None:
            image = node.image
            if channel == "ALPHA" and image is not None and image.alpha_mode == 'NONE':
                return 1.0 if kind == 'scalar' else [1.0, 1.0, 1.0]
            return {"texture": index, "channel": channel}
        # Missing image: neutral grey for colours, the fed socket's own value for scalars.
        return list(FALLBACK_TEXTURE_COLOR) if kind == 'color' else fallback
    if node.type in {'RGB', 'VALUE'}:
        value = socket_constant(node.outputs[0], kind)
        return clamp_constant(value, kind, param.lo, param.hi, param.default, ctx,
                              f"the value of node '{nodes.node_path(node, src.stack)}'")
    # Unsupported: its own Color input is the nearest meaning when it has one (a colour
    # correction node), else the value the fed socket shows when unlinked.
    through = node.inputs.get("Color") if kind == 'color' else None
    if through is not None and through.type == 'RGBA' and depth < 16:
        ctx.warn_once(("node", nodes.node_path(node, src.stack)),
                      f"{ctx.where(node, src.stack)} ({node.bl_idname}) is not supported yet; "
                      f"using its Color input")
        inner = nodes.source(through, src.stack, ctx.links)
        if inner.node is None:
            value = socket_constant(inner.socket, kind)
            return clamp_constant(value, kind, param.lo, param.hi, param.default, ctx, what)
        return _from_node(inner, through, param, ctx, what, depth + 1)
    ctx.warn_once(("node", nodes.node_path(node, src.stack)),
                  f"{ctx.where(node, src.stack)} ({node.bl_idname}) is not supported yet; "
                  f"using the value of the '{fed.name}' input it feeds")
    return fallback


def check_coordinates(image_node, stack, ctx):
    """Photon reads images at the mesh's active UV map: say so when the tree asks otherwise."""
    socket = image_node.inputs.get("Vector")
    for _ in range(16):
        src = nodes.source(socket, stack, ctx.links) if socket is not None else None
        if src is None or src.node is None:
            return
        node = src.node
        where = ctx.where(node, src.stack)
        if node.type == 'UVMAP' or (node.type == 'TEX_COORD' and src.output_name == "UV"):
            return
        if node.type == 'MAPPING':
            if not _identity_mapping(node):
                ctx.warn_once(("mapping", where), f"{where}: Mapping transforms are not "
                                                  f"supported yet; using plain UVs")
            socket, stack = node.inputs.get("Vector"), src.stack
            continue
        if node.type == 'TEX_COORD':
            message = f"{where}: '{src.output_name}' coordinates are not supported; using UVs"
        else:
            message = (f"{where} ({node.bl_idname}) as texture coordinates is not supported; "
                       f"using UVs")
        ctx.warn_once(("coords", where), message)
        return


def _identity_mapping(node):
    defaults = {"Location": (0.0, 0.0, 0.0), "Rotation": (0.0, 0.0, 0.0),
                "Scale": (1.0, 1.0, 1.0)}
    for name, default in defaults.items():
        socket = node.inputs.get(name)
        if socket is None or not socket.enabled:
            continue
        if socket.is_linked or any(abs(float(a) - b) > 1e-6
                                   for a, b in zip(socket.default_value, default)):
            return False
    return True


def read_normal_map(socket, stack, ctx, program_only=False):
    """{"texture", "strength"} for a Normal input fed by a tangent-space Normal Map node with an
    image, {"register"} for any other normal the shader program computes (always, with
    `program_only`), or None (the interpolated normal)."""
    src = nodes.source(socket, stack, ctx.links)
    if src.node is None:
        return None
    node = src.node
    where = ctx.where(node, src.stack)
    color = (nodes.source(node.inputs["Color"], src.stack, ctx.links)
             if node.type == 'NORMAL_MAP' else None)
    strength_src = (nodes.source(node.inputs["Strength"], src.stack, ctx.links)
                    if node.type == 'NORMAL_MAP' else None)
    if (program_only or node.type != 'NORMAL_MAP' or node.space != 'TANGENT' or node.uv_map or
            color.node is None or color.node.type != 'TEX_IMAGE' or
            color.output_name != "Color" or strength_src.node is not None or
            not _plain_image(color.node, color.stack, ctx)):
        # Anything but a tangent-space map of a plain image: the shader program computes it.
        outputs = ctx.program.compile(node, src.stack)
        found = outputs.get(src.socket.identifier)
        if found is None:
            return None
        return {"register": ctx.program.convert(found[0], found[1], 'vector')}
    check_coordinates(color.node, color.stack, ctx)
    index = ctx.textures.texture(color.node, ctx.where(color.node, color.stack))
    if index is None:
        return None
    strength = read_input(node.inputs["Strength"], src.stack, normal_map_strength_param(), ctx)
    if not isinstance(strength, float):
        ctx.warn_once(("nstrength", where), f"{where}: a texture driving Strength is not "
                                            f"supported; using 1")
        strength = 1.0
    return {"texture": index, "strength": strength}
