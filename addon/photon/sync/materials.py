"""Blender materials to native closure lists, and the world colour.

A material becomes a flat list of closures (see native/src/photon/scene/material.h): Mix Shader and
Add Shader nodes are flattened into each closure's weight, a product of mix factors (`fac`, or
`1 - fac` for a Mix Shader's first input), by graph.py. Each closure is a dict
    {"type": "PRINCIPLED", "sharp": False, "params": {"color": [r, g, b] | {"texture": i,
     "channel": "COLOR"}, "roughness": 0.5, ...}, "normal_map": {"texture": i, "strength": 1.0},
     "weight": [{"fac": 0.3 | {"texture": i, "channel": "ALPHA"}, "complement": True}, ...]}
which Scene.add_material parses. Unsupported nodes are reported once per material and node and
fall back to their nearest meaning (a shader: diffuse of its colour), never to silent black.
"""

import math

import bpy

from .. import native
from . import aovs as sync_aovs, graph, nodes
from .inputs import (DEFAULT_COLOR, MaterialContext, clamp_constant, closure_param,
                     closure_table, closures_by_name, read_input, read_normal_map)
from .shader_program import RENDER_COLOR, program_attributes
from .textures import TextureTable

MAX_BSDF_LOBES = 8  # Bsdf::kMaxLobes (native/src/photon/render/bsdf.h): lobes kept per point

# Which nodes become which closures, and each input's socket names, range and default, come
# from the core's one table (inputs.closure_table(), _photon.material_parameters()).

# Microfacet distributions rendered as GGX without comment (Multiscatter GGX before Blender 4
# warns where it is read); Sharp and Beckmann render as themselves, others (Ashikhmin-Shirley)
# warn.
GGX_LIKE = {'GGX', 'MULTI_GGX'}
# Principled inputs Photon does not render: (input names, Blender default, whether the input
# itself is ignored, inputs that only matter when this one is active: (name, default or None
# for "only a link counts")). Linked counts as active.
PRINCIPLED_IGNORED = [
    (("Subsurface", "Subsurface Weight"), 0.0, False,
     [("Subsurface Radius", (1.0, 0.2, 0.1)), ("Subsurface IOR", 1.4),
      ("Subsurface Anisotropy", 0.0)]),
    (("Anisotropic",), 0.0, False, [("Tangent", None)]),
]
# Blender 4.0+'s Principled BSDF (v2, read with Cycles 4's meaning as PRINCIPLED_V2): inputs
# Photon does not render, in PRINCIPLED_IGNORED's form.
PRINCIPLED_V2_IGNORED = [
    (("Sheen Weight",), 0.0, True, [("Sheen Roughness", None), ("Sheen Tint", None)]),
    (("Thin Film Thickness",), 0.0, True, [("Thin Film IOR", None)]),
    (("Subsurface Weight",), 0.0, False,
     [("Subsurface Radius", None), ("Subsurface Scale", None), ("Subsurface IOR", None),
      ("Subsurface Anisotropy", None)]),
    (("Anisotropic",), 0.0, False, [("Tangent", None)]),
]
# Nodes whose Tangent input, when linked, is ignored (the UV map's tangent is used).
TANGENT_NODES = {'BSDF_PRINCIPLED', 'BSDF_ANISOTROPIC', 'BSDF_GLOSSY'}


def is_principled_v2(node):
    """A Principled BSDF node of Blender 4.0+ (its sockets say so, whatever the version)."""
    return node.type == 'BSDF_PRINCIPLED' and node.inputs.get("Specular IOR Level") is not None


def is_glossy_v2(node):
    """Blender 4.0+'s Glossy BSDF, which absorbed the Anisotropic BSDF (its Python type stays
    ShaderNodeBsdfAnisotropic, its type reads BSDF_GLOSSY)."""
    return node.type == 'BSDF_GLOSSY' and node.inputs.get("Anisotropy") is not None


def is_ashikhmin_sheen(node):
    """Blender 4.0+'s Sheen BSDF with the Ashikhmin distribution: Cycles' velvet, which a 3.x
    Velvet BSDF becomes on loading (its Sigma read as Roughness). Microfiber is another model."""
    return node.type == 'BSDF_SHEEN' and getattr(node, "distribution", None) == 'ASHIKHMIN'


def _differs(socket, default):
    """Whether an input is active: linked, or its value is not Blender's default (default None:
    only a link counts)."""
    if socket is None:
        return False
    if socket.is_linked:
        return True
    if default is None:
        return False
    value = socket.default_value
    if isinstance(default, tuple):
        return any(abs(float(value[i]) - d) > 1e-6 for i, d in enumerate(default))
    return abs(float(value) - default) > 1e-6


def _note_ignored_principled(node, stack, ctx):
    v2 = is_principled_v2(node)
    subsurface = nodes.find_input(node, "Subsurface Weight" if v2 else "Subsurface")
    if _differs(subsurface, 0.0):
        if v2:
            ctx.warn_once(("subsurface", ctx.name),
                          f"Material '{ctx.name}': subsurface scattering is not supported; "
                          f"Subsurface Weight is rendered as diffuse of the Base Color")
        else:
            ctx.warn_once(("subsurface", ctx.name),
                          f"Material '{ctx.name}': subsurface scattering is not supported; "
                          f"Subsurface is rendered as diffuse mixed towards Subsurface Color (as "
                          f"Cycles renders it without subsurface scattering)")
    if v2:
        thin_wall = node.inputs.get("Thin Wall")
        if thin_wall is not None and (thin_wall.is_linked or bool(thin_wall.default_value)):
            ctx.ignored_principled.append("Thin Wall")
    for names, default, ignored, dependents in (PRINCIPLED_V2_IGNORED if v2 else
                                                PRINCIPLED_IGNORED):
        main = nodes.find_input(node, *names)
        if not _differs(main, default):
            continue
        if ignored:
            ctx.ignored_principled.append(main.name)
        for name, dep_default in dependents:
            if _differs(node.inputs.get(name), dep_default):
                ctx.ignored_principled.append(name)


def _read_params(node, stack, table, ctx):
    params = {}
    for names, param in table:
        socket = nodes.find_input(node, *names)
        if socket is not None:
            params[param.name] = read_input(socket, stack, param, ctx)
    return params


def _bsdf_closure(node, stack, ctx):
    """The closure of a supported BSDF / emission node, or None if the node is unsupported."""
    kind = node.type
    # Blender 4's Glass and Refraction BSDFs: Cycles 4's microfacet model (the glass one
    # interface with the Fresnel per microfacet).
    v2 = is_principled_v2(node) or is_glossy_v2(node) or (
        kind in ('BSDF_GLASS', 'BSDF_REFRACTION') and bpy.app.version >= (4, 0, 0))
    if is_principled_v2(node):
        closure_type, table, _ = closures_by_name()["PRINCIPLED_V2"]
    elif is_glossy_v2(node):
        # One closure for the merged node: anisotropic GGX (isotropic at Anisotropy 0).
        closure_type, table, _ = closures_by_name()["ANISOTROPIC"]
    elif is_ashikhmin_sheen(node):
        closure_type, table, _ = closures_by_name()["VELVET"]
    else:
        found = closure_table().get(kind)
        if found is None:
            return None
        closure_type, table = found
    closure = {"type": closure_type, "sharp": False,
               "params": _read_params(node, stack, table, ctx)}
    if v2:
        # Cycles 4's microfacet model, and its Multiscatter GGX (albedo scaling) when chosen.
        closure["cycles4"] = True
        closure["multiscatter"] = getattr(node, "distribution", None) == 'MULTI_GGX'
    elif getattr(node, "distribution", None) == 'MULTI_GGX':
        # Cycles 3.x's Multiscatter GGX follows light between the microfacets by a random walk
        # (Heitz et al. 2016), which Photon does not trace.
        where = ctx.where(node, stack)
        ctx.warn_once(("multiscatter", where),
                      f"{where}: the Multiscatter GGX distribution is rendered as "
                      "single-scattering GGX (darker where rough)")
    if kind == 'BSDF_DIFFUSE' and bpy.app.version >= (4, 3, 0):
        # Cycles 4.3's Oren-Nayar puts back the light its microfacets scatter among themselves.
        closure["diffuse_multiscatter"] = True
    if kind == 'BSDF_PRINCIPLED':
        _note_ignored_principled(node, stack, ctx)
    elif kind != 'BSDF_SHEEN':  # its distribution chose the closure
        distribution = getattr(node, "distribution", None)
        if distribution == 'SHARP':
            closure["sharp"] = True
        elif distribution == 'BECKMANN':
            closure["beckmann"] = True
        elif distribution is not None and distribution not in GGX_LIKE:
            where = ctx.where(node, stack)
            ctx.warn_once(("distribution", where),
                          f"{where}: the {distribution.replace('_', ' ').title()} "
                          f"distribution is rendered as GGX")
    normal = node.inputs.get("Normal")
    if normal is not None:
        normal_map = read_normal_map(normal, stack, ctx)
        if normal_map is not None:
            closure["normal" if "register" in normal_map else "normal_map"] = normal_map
    if kind == 'BSDF_PRINCIPLED':
        coat_normal = nodes.find_input(node, "Clearcoat Normal", "Coat Normal")
        if coat_normal is not None and coat_normal.is_linked:
            found = read_normal_map(coat_normal, stack, ctx, program_only=True)
            if found is not None:
                closure["clearcoat_normal"] = found
    tangent = node.inputs.get("Tangent") if kind in TANGENT_NODES else None
    if kind != 'BSDF_PRINCIPLED' and tangent is not None and tangent.is_linked:
        where = ctx.where(node, stack)
        ctx.warn_once(("tangent", where), f"{where}: a linked Tangent is not supported; "
                                          f"using the UV map's tangent")
    return closure


def _fallback_closure(node, stack, ctx):
    """Nearest meaning of an unsupported shader node: diffuse of its own colour."""
    path = nodes.node_path(node, stack)
    ctx.warn_once(("node", path), f"Material '{ctx.name}': node '{path}' ({node.bl_idname}) "
                                  f"is not supported yet; rendering it as diffuse")
    socket = nodes.find_input(node, "Color", "Base Color")
    color = (read_input(socket, stack, closure_param('BSDF_DIFFUSE', "color"), ctx)
             if socket is not None and socket.type == 'RGBA' else list(DEFAULT_COLOR))
    return {"type": "DIFFUSE", "sharp": False, "params": {"color": color}}


def _converted_emission(vertex, ctx):
    """A colour or value output linked into a shader input, as Cycles converts it (ShaderGraph's
    automatic conversion): an Emission of that colour at strength 1, or of white at that
    strength. Artists plug a texture straight into the Material Output to see it unlit."""
    fed, stack = vertex.fed
    params = {"color": [1.0, 1.0, 1.0], "strength": 1.0}
    if vertex.output.type in ('VALUE', 'INT', 'BOOLEAN'):
        params["strength"] = read_input(fed, stack, closure_param('EMISSION', "strength"), ctx)
    else:
        params["color"] = read_input(fed, stack, closure_param('EMISSION', "color"), ctx)
    return {"type": "EMISSION", "sharp": False, "params": params}


def _leaf_closure(vertex, ctx):
    """The closure of a graph vertex that is not a Mix or Add Shader."""
    node, stack = vertex.node, vertex.stack
    if vertex.output.type != 'SHADER':
        return _converted_emission(vertex, ctx)
    closure = _bsdf_closure(node, stack, ctx)
    return closure if closure is not None else _fallback_closure(node, stack, ctx)


def _diffuse_of(color):
    return [{"type": "DIFFUSE", "sharp": False,
             "params": {"color": [float(color[0]), float(color[1]), float(color[2])]},
             "weight": []}]


def convert_material(material, reporter, textures, aovs=None):
    """(name, closures, program, aov outputs) for Scene.add_material; textures is a
    TextureTable; program is None when every input is a constant or a plain image lookup;
    `aovs` ({name: 'COLOR' | 'VALUE'}) are the view layer's shader AOVs the material's AOV
    Output nodes may write."""
    name, closures, ctx = _convert(material, reporter, textures)
    outputs = []
    if aovs and ctx is not None and material.use_nodes and material.node_tree is not None \
            and closures_from_nodes(material, ctx):
        outputs = sync_aovs.material_aovs(material.node_tree, aovs, ctx)
    return name, closures, (ctx.program_dict() if ctx is not None else None), outputs


def closures_from_nodes(material, ctx):
    """Whether the material's Surface output is linked (Cycles compiles a material's AOV
    Output nodes only then)."""
    output = nodes.output_node(material.node_tree, 'OUTPUT_MATERIAL')
    surface = output.inputs.get("Surface") if output else None
    return surface is not None and nodes.source(surface, (), ctx.links).node is not None


def _convert(material, reporter, textures):
    if material is None:
        return "default", _diffuse_of(DEFAULT_COLOR), None
    name = material.name
    ctx = MaterialContext(name, reporter, textures)
    if not material.use_nodes or material.node_tree is None:
        return name, _diffuse_of(read_constant_color(material.diffuse_color, ctx)), ctx
    output = nodes.output_node(material.node_tree, 'OUTPUT_MATERIAL')
    surface = output.inputs.get("Surface") if output else None
    if surface is None or nodes.source(surface, (), ctx.links).node is None:
        # Cycles renders an unconnected output black; keep the artist's viewport colour instead
        # of a silent black object, and say so.
        reporter.warning(f"Material '{name}' has no shader connected to its output; "
                         f"rendering its viewport colour")
        return name, _diffuse_of(read_constant_color(material.diffuse_color, ctx)), ctx
    closures = graph.collect_closures(surface, ctx, lambda vertex: _leaf_closure(vertex, ctx))
    for socket_name in ("Volume", "Displacement"):
        socket = output.inputs.get(socket_name)
        if socket is not None and nodes.source(socket, (), ctx.links).node is not None:
            reporter.warning(f"Material '{name}': {socket_name.lower()} is not supported yet "
                             f"and is ignored")
    if ctx.ignored_principled:
        unique = list(dict.fromkeys(ctx.ignored_principled))
        reporter.warning(f"Material '{name}': Principled BSDF inputs not supported yet are "
                         f"rendered at their defaults: {', '.join(unique)}")
    _add_dispersion(material, name, closures, reporter)
    scattering = sum(1 for c in closures if c["type"] not in ("EMISSION", "HOLDOUT"))
    if scattering > MAX_BSDF_LOBES:
        reporter.warning(f"Material '{name}': {scattering} BSDF closures; Photon shades the "
                         f"{MAX_BSDF_LOBES} strongest lobes at each point and drops the rest")
    return name, closures, ctx


# Closures whose IOR material.photon.abbe_number makes vary with the wavelength.
DISPERSIVE_CLOSURES = ("GLASS", "REFRACTION", "PRINCIPLED", "PRINCIPLED_V2")


# Abbe numbers of real materials (the native module's; unbounded when it did not load).
ABBE_RANGE = tuple(getattr(native.MODULE, "ABBE_RANGE", (0.0, math.inf)))


def _add_dispersion(material, name, closures, reporter):
    """The material's Abbe number on its glass closures (spectral mode disperses them), clamped
    into real materials' range with a warning: near 0 Cauchy's law gives indices of hundreds."""
    settings = getattr(material, "photon", None)
    abbe = float(getattr(settings, "abbe_number", 0.0)) if settings is not None else 0.0
    if not math.isfinite(abbe) or abbe <= 0.0:
        return
    low, high = ABBE_RANGE
    if not low <= abbe <= high:
        clamped = min(max(abbe, low), high)
        reporter.warning(f"Material '{name}': Abbe number {abbe:g} is outside real materials' "
                         f"range ({low:g} for rutile, the most dispersive, to {high:g}); "
                         f"rendering {clamped:g}")
        abbe = clamped
    for c in closures:
        if c["type"] in DISPERSIVE_CLOSURES:
            c["abbe"] = abbe


def _without_registers(closures):
    """Closures with every program input replaced by its constant."""
    def plain(value):
        return value.get("value", 0.0) if isinstance(value, dict) and "register" in value \
            else value
    result = []
    for c in closures:
        c = dict(c)
        c["params"] = {k: plain(v) for k, v in c.get("params", {}).items()}
        c["weight"] = [dict(w, fac=plain(w["fac"])) for w in c.get("weight", [])]
        c.pop("normal", None)
        c.pop("clearcoat_normal", None)
        result.append(c)
    return result


def read_constant_color(value, ctx):
    color = closure_param('BSDF_DIFFUSE', "color")
    return clamp_constant([value[0], value[1], value[2]], color.kind, color.lo, color.hi,
                          list(DEFAULT_COLOR), ctx, "the viewport colour")


class MaterialTable:
    """Converts each Blender material once per render and hands out native indices."""

    def __init__(self, native_scene, reporter, pixels_type=None, aovs=None):
        self._scene = native_scene
        self._reporter = reporter
        self._aovs = aovs  # {name: 'COLOR' | 'VALUE'}: the view layer's shader AOVs
        self._index = {}
        self.names = {}  # native index -> the Blender material's name (None: no material)
        self._attributes = {}  # native index -> program_attributes() of its program
        self._missing_reported = set()
        self.textures = TextureTable(native_scene, reporter, pixels_type)

    def index(self, material):
        key = material.name_full if material is not None else None
        found = self._index.get(key)
        if found is None:
            name, closures, program, aovs = convert_material(material, self._reporter,
                                                             self.textures, self._aovs)
            pass_index = float(getattr(material, "pass_index", 0)) if material else 0.0
            try:
                found = self._scene.add_material(name, closures, program, pass_index,
                                                 aovs=aovs or None)
            except ValueError as error:
                if program is None:
                    raise
                self._reporter.warning(f"Material '{name}': its nodes could not be compiled "
                                       f"({error}); rendering its inputs' constant values")
                plain_aovs = [dict(a, value=sync_aovs.plain_value(a["value"], a["type"]))
                              for a in aovs]
                found = self._scene.add_material(name, _without_registers(closures), None,
                                                 pass_index, aovs=plain_aovs or None)
                program = None
            self._attributes[found] = program_attributes(program)
            self._index[key] = found
            self.names[found] = material.name if material is not None else None
        return found

    def reconvert(self, material):
        """(index, name, closures, program, pass_index) of an edited material that this table
        converted before, converted again with the same images; None when it was not in the
        table or the edit needs what only a full sync adds (an image the scene does not hold,
        a named attribute its meshes were not exported with)."""
        index = self._index.get(material.name_full)
        if index is None:
            return None
        textures_before = self._scene.texture_count
        name, closures, program, _aovs = convert_material(material, self._reporter,
                                                          self.textures)
        if self._scene.texture_count != textures_before:
            return None
        if not set(program_attributes(program)) <= set(self._attributes.get(index, {})):
            return None
        return index, name, closures, program, float(getattr(material, "pass_index", 0))

    def slot_indices(self, obj):
        slots = [self.index(slot.material) for slot in obj.material_slots]
        return slots or [self.index(None)]

    def attribute_requests(self, slots):
        """{attribute name: [node descriptions]} the materials of native indices `slots` read."""
        requests = {}
        for index in slots:
            for name, where in self._attributes.get(index, {}).items():
                requests.setdefault(name, []).extend(where)
        return requests

    def report_missing_attributes(self, object_name, missing, requests):
        """Warns once per node and attribute name a mesh does not have (it renders as 0, as in
        Cycles)."""
        for name in missing:
            shown = "the active colour attribute" if name == RENDER_COLOR else \
                f"attribute '{name}'"
            for where in requests.get(name, ()):
                if (where, name) in self._missing_reported:
                    continue
                self._missing_reported.add((where, name))
                self._reporter.warning(f"{where} reads {shown}, which object '{object_name}' "
                                       f"does not have; it reads as 0, as in Cycles")

    def release(self):
        """Deletes the textures written for this render (call after the render ends)."""
        self.textures.release()


def _checked_world(name, color, strength, reporter, max_emission):
    """colour x strength with NaN read as 0, negatives clamped to 0 and the product to
    `max_emission` (hue kept), each reported once."""
    if math.isnan(strength):
        reporter.warning(f"World '{name}': the Background strength is NaN; using 0 (a black "
                         f"world)")
        strength = 0.0
    elif strength < 0.0:
        reporter.warning(f"World '{name}': the Background strength {strength:g} is negative; "
                         f"clamped to 0 (a black world)")
        strength = 0.0
    if not all(c >= 0.0 for c in color):  # NaN fails the test too
        reporter.warning(f"World '{name}': the background colour has NaN or negative "
                         f"components; they are read as 0")
        color = [c if c >= 0.0 else 0.0 for c in color]
    radiance = [c * strength if c > 0.0 else 0.0 for c in color]  # 0 x inf is not NaN here
    brightest = max(radiance)
    if max_emission is not None and brightest > max_emission:
        scale = max_emission / brightest if math.isfinite(brightest) else 0.0
        radiance = ([min(r * scale, max_emission) for r in radiance] if scale > 0.0 else
                    [max_emission if math.isinf(r) else 0.0 for r in radiance])
        reporter.warning(f"World '{name}': background colour x strength {brightest:.3g} is "
                         f"more than Photon can render; clamped to {max_emission:.3g}")
    return radiance


def world_color(world, reporter, max_emission=None):
    """Background radiance (colour x strength) of the world; at most `max_emission`."""
    if world is None:
        return [0.0, 0.0, 0.0]
    if not world.use_nodes or world.node_tree is None:
        return _checked_world(world.name, [float(c) for c in world.color], 1.0, reporter,
                              max_emission)
    output = nodes.output_node(world.node_tree, 'OUTPUT_WORLD')
    src = nodes.source(output.inputs.get("Surface")) if output else None
    node = src.node if src is not None else None
    if node is None:
        return [0.0, 0.0, 0.0]
    if node.type != 'BACKGROUND':
        reporter.warning(f"World '{world.name}': node '{node.name}' is not supported; "
                         f"using a black background")
        return [0.0, 0.0, 0.0]
    color_socket = node.inputs.get("Color")
    if color_socket.is_linked:
        reporter.warning(f"World '{world.name}': the 'Color' input of node '{node.name}' is "
                         f"connected to a texture or node, which is not supported yet; using "
                         f"its colour value")
    color = [float(color_socket.default_value[i]) for i in range(3)]
    strength = float(node.inputs.get("Strength").default_value)
    return _checked_world(world.name, color, strength, reporter, max_emission)
