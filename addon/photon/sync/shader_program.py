"""Blender shader node trees to native shader programs (native/src/photon/shading/program.h).

A program is a flat list of node descriptions over a register file of floats, evaluated per
shading point by the C++ library, as Cycles' SVM evaluates its compiled nodes:
    {"registers": [initial values...], "nodes": [
        {"type": bl_idname, "enums": {name: "VALUE"}, "numbers": {name: x},
         "inputs": {socket identifier: first register}, "outputs": {identifier: register},
         "table": [floats]}, ...]}
Unlinked sockets become constant registers; a linked socket reads the register its source
node's output writes (each (node, group stack) is compiled once). Socket kinds convert as Blender
converts them (float -> vector broadcast, colour -> float luminance, vector -> float average).
A node the native library does not know is reported once and replaced by its nearest meaning:
its own input of the output's kind when it has one, else the socket's default value.
"""

from ..native import native_module
from . import nodes

KIND_SIZE = {'float': 1, 'vector': 3, 'color': 3}
SOCKET_KIND = {'VALUE': 'float', 'INT': 'float', 'BOOLEAN': 'float', 'VECTOR': 'vector',
               'RGBA': 'color'}

# Properties every node has (not the node's own settings).
_BASE_PROPERTIES = None

# Vector inputs that, unlinked, read a coordinate instead of their (hidden) value, as Cycles'
# default links do: image textures their UV map, environment textures the position (the
# direction for the world), every other texture but White Noise (which reads its socket's value)
# the Generated coordinates.
_DEFAULT_UV = {'TEX_IMAGE'}
_DEFAULT_POSITION = {'TEX_ENVIRONMENT'}
_DEFAULT_GENERATED = {'TEX_NOISE', 'TEX_VORONOI', 'TEX_MUSGRAVE', 'TEX_WAVE', 'TEX_MAGIC',
                      'TEX_CHECKER', 'TEX_BRICK', 'TEX_GRADIENT', 'TEX_SKY', 'TEX_GABOR'}
# Inputs whose unlinked value means "the shading normal" (the native side reads N).
_NORMAL_INPUTS = {'Normal', 'Clearcoat Normal', 'Tangent'}
# Nodes whose approximation the artist should hear about.
_APPROXIMATE_OUTPUTS = {('NEW_GEOMETRY', 'Pointiness'): "Pointiness is rendered as 0.5",
                        ('NEW_GEOMETRY', 'Random Per Island'): "Random Per Island is rendered as 0",
                        ('NEW_GEOMETRY', 'Parametric'): "Parametric is rendered as 0"}
# Nodes compiled by the add-on itself, without an instruction.
_CONSTANT_NODES = {'RGB', 'VALUE'}
# The name a mesh's active render colour attribute is exported under, read by Color Attribute
# nodes without a layer name (kRenderColorAttribute in native/src/photon/shading/attribute_nodes.h).
RENDER_COLOR = "\x01render_color"


def program_attributes(program):
    """{attribute name: [where, ...]} of the mesh attributes a program dict (ProgramBuilder's
    program()) reads by name, with the nodes that read each (for warnings); the names are those
    of NodeDesc enums "photon_attribute" (Attribute, Color Attribute, named UV Map nodes)."""
    found = {}
    for desc in (program or {}).get("nodes", ()):
        name = desc.get("enums", {}).get("photon_attribute")
        if name:
            found.setdefault(name, []).append(desc.get("where", ""))
    return found


def _base_properties():
    global _BASE_PROPERTIES
    if _BASE_PROPERTIES is None:
        import bpy
        _BASE_PROPERTIES = {p.identifier for p in bpy.types.ShaderNode.bl_rna.properties}
        _BASE_PROPERTIES |= {"rna_type", "name", "label", "location", "width", "height",
                             "dimensions", "color", "select", "show_options", "show_preview",
                             "hide", "mute", "show_texture", "use_custom_color", "parent",
                             "internal_links", "inputs", "outputs", "type", "bl_idname"}
    return _BASE_PROPERTIES


def _settings(node):
    """(enums, numbers) of a node's own settings: enums and booleans as strings, ints and floats
    as numbers."""
    enums, numbers = {}, {}
    base = _base_properties()
    for prop in node.bl_rna.properties:
        name = prop.identifier
        if name in base or prop.is_readonly and prop.type != 'POINTER':
            continue
        try:
            value = getattr(node, name)
        except AttributeError:
            continue
        if prop.type == 'ENUM' and not prop.is_enum_flag:
            enums[name] = str(value)
        elif prop.type == 'BOOLEAN' and getattr(prop, "array_length", 0) == 0:
            enums[name] = "True" if value else "False"
        elif prop.type in {'INT', 'FLOAT'} and getattr(prop, "array_length", 0) == 0:
            numbers[name] = float(value)
        elif prop.type in {'INT', 'FLOAT'}:  # vectors as "name[i]" (the Sky's sun direction)
            for i in range(prop.array_length):
                numbers[f"{name}[{i}]"] = float(value[i])
    return enums, numbers


# Nodes whose settings and sockets did not change while Cycles' arithmetic did: the native side
# is told which Cycles to follow (enum "photon_cycles", the Blender major version). Every other
# node is told apart by what it has (Blender 4.x's Noise by noise_type, Voronoi by normalize).
# 4.x: the Wave's distortion fBm no longer clamps its roughness; the Normal Map applies Strength
# in tangent space; the Vector Transform carries normals by the inverse transpose.
_CYCLES_VERSIONED = {'TEX_WAVE', 'NORMAL_MAP', 'VECT_TRANSFORM'}


def _cycles_version(node, desc):
    if node.type in _CYCLES_VERSIONED:
        import bpy
        desc["enums"]["photon_cycles"] = str(bpy.app.version[0])


def _warn_unmatched(node, where, ctx):
    """Warns about a node Photon renders, but not as this Blender's Cycles does."""
    import bpy
    if node.type == 'TEX_VORONOI' and bpy.app.version[0] >= 5 and \
            getattr(node, "voronoi_dimensions", '3D') != '1D':
        # The node conformance suite: Cycles 5.2's 2D-4D cells differ from 4.x's everywhere.
        ctx.warn_once(("voronoi5", where),
                      f"{where}: Voronoi Texture {node.voronoi_dimensions} follows Cycles 4.x; "
                      f"Cycles {bpy.app.version[0]}.{bpy.app.version[1]} places its cells "
                      f"differently, so the pattern will not match Cycles")


def _constant_of(socket, kind):
    value = getattr(socket, "default_value", None)
    if value is None:
        return [0.0] * KIND_SIZE[kind]
    try:
        channels = [float(value[i]) for i in range(min(3, len(value)))]
    except TypeError:
        channels = [float(value)]
    if kind == 'float':
        if len(channels) == 1:
            return channels
        if socket.type == 'RGBA':
            return [0.2126 * channels[0] + 0.7152 * channels[1] + 0.0722 * channels[2]]
        return [sum(channels) / len(channels)]
    if len(channels) == 1:
        return channels * 3
    return (channels + [0.0, 0.0])[:3]


class ProgramBuilder:
    """Compiles the node sources of sockets into one program. `ctx` is the MaterialContext
    (name, reporter, textures, links, warn_once); `world` makes coordinates those of the
    background."""

    def __init__(self, ctx, world=False):
        self.ctx = ctx
        self.world = world
        self.registers = []
        self.nodes = []
        self._cache = {}
        self._active = set()  # (node, stack) being compiled: a cycle guard
        self._checked = {}    # (bl_idname, enums, inputs) -> native verdict

    # --- registers -----------------------------------------------------------------------
    def constant(self, values):
        reg = len(self.registers)
        self.registers.extend(float(v) for v in values)
        return reg

    def _alloc(self, kind):
        return self.constant([0.0] * KIND_SIZE[kind])

    def program(self):
        if not self.nodes:
            return None
        return {"registers": list(self.registers), "nodes": self.nodes}

    def _emit(self, desc):
        self.nodes.append(desc)

    def convert(self, reg, have, want):
        if have == want or (have in ('vector', 'color') and want in ('vector', 'color')):
            return reg
        out = self._alloc(want)
        if have == 'float':
            self._emit({"type": "PhotonFloatToVector", "inputs": {"In": reg},
                        "outputs": {"Out": out}})
        elif have == 'color':
            self._emit({"type": "PhotonColorToFloat", "inputs": {"In": reg},
                        "outputs": {"Out": out}})
        else:
            self._emit({"type": "PhotonVectorToFloat", "inputs": {"In": reg},
                        "outputs": {"Out": out}})
        return out

    # --- sockets -------------------------------------------------------------------------
    def value_of(self, socket, stack, want):
        """Register holding input `socket` (of a node reached through `stack`) as `want`
        ('float', 'vector', 'color')."""
        src = nodes.source(socket, stack, self.ctx.links)
        if src.node is None:
            return self.constant(_constant_of(src.socket, want))
        outputs = self.compile(src.node, src.stack)
        found = outputs.get(src.socket.identifier)
        if found is None:
            return self.constant(_constant_of(socket, want))
        reg, have = found
        return self.convert(reg, have, want)

    def coordinate(self, output, stack=()):
        """Register of a Texture Coordinate / Geometry output, compiled once per block."""
        key = ("coordinate", output)
        found = self._cache.get(key)
        if found is None:
            reg = self._alloc('vector')
            if output == 'Position':
                self._emit({"type": "ShaderNodeNewGeometry", "outputs": {"Position": reg}})
            else:
                self._emit({"type": "ShaderNodeTexCoord", "outputs": {output: reg}})
            found = {output: (reg, 'vector')}
            self._cache[key] = found
        return found[output][0]

    def _default_link(self, node, socket):
        """A coordinate register for an unlinked hidden Vector input, or None."""
        if socket.name != "Vector" or socket.is_linked:
            return None
        if node.type in _DEFAULT_UV:
            return self.coordinate('UV')
        if node.type in _DEFAULT_POSITION:
            return self.coordinate('Position')
        if node.type in _DEFAULT_GENERATED:
            return self.coordinate('Generated')
        return None

    # --- nodes ---------------------------------------------------------------------------
    def compile(self, node, stack):
        """{output identifier: (register, kind)} of a node's outputs."""
        key = (node, stack)
        found = self._cache.get(key)
        if found is not None:
            return found
        if key in self._active:  # a cycle (Blender draws it red; Cycles ignores the link)
            return {}
        self._active.add(key)
        try:
            outputs = self._compile(node, stack)
        finally:
            self._active.discard(key)
        self._cache[key] = outputs
        return outputs

    def _outputs(self, node):
        outs = {}
        for out in node.outputs:
            kind = SOCKET_KIND.get(out.type)
            if kind is not None and out.enabled:
                outs[out.identifier] = (self._alloc(kind), kind)
        return outs

    def _compile(self, node, stack):
        where = self.ctx.where(node, stack)
        if node.type in _CONSTANT_NODES:
            out = node.outputs[0]
            kind = SOCKET_KIND[out.type]
            return {out.identifier: (self.constant(_constant_of(out, kind)), kind)}
        if node.type == 'BUMP':
            return self._compile_bump(node, stack)
        for (node_type, output), message in _APPROXIMATE_OUTPUTS.items():
            if node.type == node_type and node.outputs.get(output) is not None \
                    and node.outputs[output].is_linked:
                self.ctx.warn_once(("approx", where, output), f"{where}: {message}")
        enums, numbers = _settings(node)
        desc = {"type": node.bl_idname, "enums": enums, "numbers": numbers, "inputs": {},
                "outputs": {}}
        self._special(node, stack, desc)
        _cycles_version(node, desc)
        for socket in node.inputs:
            kind = SOCKET_KIND.get(socket.type)
            if kind is None or not socket.enabled:
                continue
            reg = self._default_link(node, socket)
            if reg is None:
                if socket.name in _NORMAL_INPUTS and socket.type == 'VECTOR' and \
                        nodes.source(socket, stack, self.ctx.links).node is None:
                    continue  # unlinked: the native side reads the shading normal
                reg = self.value_of(socket, stack, kind)
            desc["inputs"][socket.identifier] = reg
        if node.type == 'NORMAL':  # its direction is the output socket's value
            desc["inputs"]["Normal_const"] = self.constant(
                _constant_of(node.outputs["Normal"], 'vector'))
        verdict = self._check(desc)
        if verdict is not None:
            return self._fallback(node, stack, where, verdict)
        _warn_unmatched(node, where, self.ctx)
        outputs = self._outputs(node)
        desc["outputs"] = {ident: reg for ident, (reg, _) in outputs.items()}
        self._emit(desc)
        return outputs

    def verdict(self, node, stack):
        """None when the native library compiles `node` as it is set up, else the reason (the
        node itself, not what feeds it: nothing is emitted)."""
        if node.type in _CONSTANT_NODES or node.type == 'BUMP':
            return None
        enums, numbers = _settings(node)
        desc = {"type": node.bl_idname, "enums": enums, "numbers": numbers, "inputs": {},
                "outputs": {}}
        if node.type not in ('TEX_IMAGE', 'TEX_ENVIRONMENT', 'TEX_COORD'):
            self._special(node, stack, desc)
        _cycles_version(node, desc)
        for socket in node.inputs:
            if SOCKET_KIND.get(socket.type) is not None and socket.enabled:
                desc["inputs"][socket.identifier] = 0
        if node.type == 'NORMAL':
            desc["inputs"]["Normal_const"] = 0
        return self._check(desc)

    def _check(self, desc):
        key = (desc["type"], tuple(sorted(desc["enums"].items())),
               tuple(sorted(desc["inputs"])), len(desc.get("table", ())))
        if key not in self._checked:
            self._checked[key] = native_module().check_shader_node(desc)
        return self._checked[key]

    def _special(self, node, stack, desc):
        """Data a node needs beyond its sockets and settings."""
        if node.type in ('ATTRIBUTE', 'VERTEX_COLOR', 'UVMAP') or (
                node.type == 'NORMAL_MAP' and node.space == 'TANGENT' and node.uv_map):
            self._attribute_name(node, stack, desc)
        elif node.type in ('TEX_IMAGE', 'TEX_ENVIRONMENT'):
            index = None
            if node.image is not None and self.ctx.textures is not None:
                index = self.ctx.textures.texture(node, self.ctx.where(node, stack))
            desc["numbers"]["texture"] = float(index) if index is not None else -1.0
        elif node.type == 'TEX_COORD' and getattr(node, "object", None) is not None:
            inverse = node.object.matrix_world.inverted()
            desc["table"] = [float(inverse[r][c]) for r in range(3) for c in range(4)]
        else:
            try:
                from .node_tables import node_table
            except ImportError:
                return
            table = node_table(node)
            if table is not None:
                desc["table"] = [float(v) for v in table]

    def _attribute_name(self, node, stack, desc):
        """The mesh attribute an Attribute, Color Attribute or UV Map node reads, as
        desc["enums"]["photon_attribute"] (an unnamed UV Map reads the active map natively)."""
        where = self.ctx.where(node, stack)
        if node.type == 'ATTRIBUTE':
            name = node.attribute_name
            if node.attribute_type != 'GEOMETRY':
                self.ctx.warn_once(("attribute_type", where),
                                   f"{where}: {node.attribute_type.replace('_', ' ').title()} "
                                   f"attributes are not supported yet; its outputs are 0")
                name = ""
        elif node.type == 'VERTEX_COLOR':
            name = node.layer_name or RENDER_COLOR
        elif node.type == 'NORMAL_MAP':  # its tangents' UV map
            name = node.uv_map
        else:
            name = node.uv_map
            if getattr(node, "from_instancer", False):
                self.ctx.warn_once(("from_instancer", where),
                                   f"{where}: From Instancer is not supported; reading the "
                                   f"object's own UV map")
        if name:
            desc["enums"]["photon_attribute"] = name
            desc["where"] = where

    def _fallback(self, node, stack, where, verdict):
        """Nearest meaning of a node the native library cannot compile."""
        self.ctx.warn_once(("node", where), f"{where} ({node.bl_idname}) is not supported yet "
                                            f"({verdict}); using its nearest meaning")
        outputs = {}
        for out in node.outputs:
            kind = SOCKET_KIND.get(out.type)
            if kind is None or not out.enabled:
                continue
            through = next((s for s in node.inputs if s.enabled and
                            SOCKET_KIND.get(s.type) == kind and s.name not in _NORMAL_INPUTS),
                           None)
            if through is not None:
                outputs[out.identifier] = (self.value_of(through, stack, kind), kind)
            else:
                outputs[out.identifier] = (self.constant(_constant_of(out, kind)), kind)
        return outputs

    def _compile_bump(self, node, stack):
        desc = {"type": node.bl_idname, "enums": {"invert": "True" if node.invert else "False"},
                "numbers": {}, "inputs": {}, "outputs": {}}
        desc["inputs"]["Strength"] = self.value_of(node.inputs["Strength"], stack, 'float')
        desc["inputs"]["Distance"] = self.value_of(node.inputs["Distance"], stack, 'float')
        normal = node.inputs.get("Normal")
        if normal is not None and nodes.source(normal, stack, self.ctx.links).node is not None:
            desc["inputs"]["Normal"] = self.value_of(normal, stack, 'vector')
        height = node.inputs["Height"]
        if nodes.source(height, stack, self.ctx.links).node is not None:
            # The height's nodes are compiled afresh inside a block the Bump re-runs at points
            # offset along the surface (finite differences), so coordinates there move too.
            self._emit({"type": "PhotonBlockBegin", "inputs": {}, "outputs": {}})
            desc["numbers"]["block"] = 1.0
            outer = self._cache
            self._cache = {}
            try:
                desc["inputs"]["Height"] = self.value_of(height, stack, 'float')
            finally:
                self._cache = outer
        reg = self._alloc('vector')
        desc["outputs"]["Normal"] = reg
        self._emit(desc)
        return {node.outputs["Normal"].identifier: (reg, 'vector')}
