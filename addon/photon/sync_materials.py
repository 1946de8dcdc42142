"""Blender materials and world to native parameters.

Foundation scope: Principled BSDF base colour (plus its glass, mirror-metal and emission
extremes), Diffuse, Glossy (as a mirror), Glass and Emission. Everything else is reported once by
material and node name and falls back to its nearest meaning, never to black.
"""

DEFAULT_COLOR = (0.8, 0.8, 0.8)


def _input(node, *names):
    """First input socket with one of `names` (Blender renames sockets between versions)."""
    for name in names:
        socket = node.inputs.get(name)
        if socket is not None:
            return socket
    return None


def _color(node, material_name, reporter, *names, default=DEFAULT_COLOR):
    socket = _input(node, *names)
    if socket is None:
        return list(default)
    if socket.is_linked:
        reporter.warning(f"Material '{material_name}': the '{socket.name}' input of node "
                         f"'{node.name}' is connected to a texture or node, which is not "
                         f"supported yet; using its colour value")
    value = socket.default_value
    return [float(value[0]), float(value[1]), float(value[2])]


def _value(node, default, *names):
    socket = _input(node, *names)
    if socket is None:
        return default
    return float(socket.default_value)


def _output_node(node_tree, output_type):
    outputs = [n for n in node_tree.nodes if n.type == output_type]
    for node in outputs:
        if getattr(node, "is_active_output", False) and getattr(node, "target", "ALL") in {
                'ALL', 'CYCLES'}:
            return node
    return outputs[0] if outputs else None


def _linked_node(socket):
    if socket is None or not socket.is_linked:
        return None
    node = socket.links[0].from_node
    # Follow reroutes to the real node.
    while node is not None and node.type == 'REROUTE':
        if not node.inputs[0].is_linked:
            return None
        node = node.inputs[0].links[0].from_node
    return node


def _from_shader_node(node, material_name, reporter):
    """Native material parameters for the shader node feeding the Material Output."""
    params = {"type": "DIFFUSE", "color": list(DEFAULT_COLOR), "ior": 1.45,
              "emission": [0.0, 0.0, 0.0]}
    kind = node.type
    if kind == 'BSDF_PRINCIPLED':
        base = _color(node, material_name, reporter, "Base Color")
        params["color"] = base
        metallic = _value(node, 0.0, "Metallic")
        roughness = _value(node, 0.5, "Roughness")
        transmission = _value(node, 0.0, "Transmission", "Transmission Weight")
        if transmission >= 0.5:
            params["type"] = "GLASS"
            params["ior"] = _value(node, 1.45, "IOR")
        elif metallic >= 0.5:
            params["type"] = "MIRROR"
            if roughness > 0.05:
                reporter.warning(f"Material '{material_name}': rough metal (roughness "
                                 f"{roughness:.2f}) renders as a perfect mirror for now")
        strength = _value(node, 1.0, "Emission Strength")
        emission = _color(node, material_name, reporter, "Emission", "Emission Color",
                          default=(0.0, 0.0, 0.0))
        params["emission"] = [c * strength for c in emission]
    elif kind == 'BSDF_DIFFUSE':
        params["color"] = _color(node, material_name, reporter, "Color")
    elif kind == 'BSDF_GLOSSY':
        params["type"] = "MIRROR"
        params["color"] = _color(node, material_name, reporter, "Color")
        roughness = _value(node, 0.0, "Roughness")
        if roughness > 0.0:
            reporter.warning(f"Material '{material_name}': Glossy BSDF with roughness "
                             f"{roughness:.2f} renders as a perfect mirror for now")
    elif kind == 'BSDF_GLASS':
        params["type"] = "GLASS"
        params["color"] = _color(node, material_name, reporter, "Color")
        params["ior"] = _value(node, 1.45, "IOR")
    elif kind == 'EMISSION':
        color = _color(node, material_name, reporter, "Color", default=(1.0, 1.0, 1.0))
        strength = _value(node, 1.0, "Strength")
        params["color"] = [0.0, 0.0, 0.0]
        params["emission"] = [c * strength for c in color]
    else:
        # Nearest meaning: a diffuse surface of the node's own colour, if it has one.
        reporter.warning(f"Material '{material_name}': node '{node.name}' ({node.bl_idname}) "
                         f"is not supported yet; rendering it as diffuse")
        params["color"] = _color(node, material_name, reporter, "Color", "Base Color")
    return params


def convert_material(material, reporter):
    """Returns (name, params) for Scene.add_material."""
    if material is None:
        return "default", {"type": "DIFFUSE", "color": list(DEFAULT_COLOR)}
    name = material.name
    if not material.use_nodes or material.node_tree is None:
        color = material.diffuse_color
        return name, {"type": "DIFFUSE", "color": [color[0], color[1], color[2]]}
    output = _output_node(material.node_tree, 'OUTPUT_MATERIAL')
    shader = _linked_node(output.inputs.get("Surface")) if output else None
    if shader is None:
        # Cycles renders an unconnected output black; keep the artist's viewport colour instead
        # of a silent black object, and say so.
        reporter.warning(f"Material '{name}' has no shader connected to its output; "
                         f"rendering its viewport colour")
        color = material.diffuse_color
        return name, {"type": "DIFFUSE", "color": [color[0], color[1], color[2]]}
    return name, _from_shader_node(shader, name, reporter)


class MaterialTable:
    """Converts each Blender material once per render and hands out native indices."""

    def __init__(self, native_scene, reporter):
        self._scene = native_scene
        self._reporter = reporter
        self._index = {}

    def index(self, material):
        key = material.name_full if material is not None else None
        found = self._index.get(key)
        if found is None:
            name, params = convert_material(material, self._reporter)
            found = self._scene.add_material(name, **params)
            self._index[key] = found
        return found

    def slot_indices(self, obj):
        slots = [self.index(slot.material) for slot in obj.material_slots]
        return slots or [self.index(None)]


def world_color(world, reporter):
    """Background radiance (colour x strength) of the world."""
    if world is None:
        return [0.0, 0.0, 0.0]
    if not world.use_nodes or world.node_tree is None:
        return [float(c) for c in world.color]
    output = _output_node(world.node_tree, 'OUTPUT_WORLD')
    node = _linked_node(output.inputs.get("Surface")) if output else None
    if node is None:
        return [0.0, 0.0, 0.0]
    if node.type != 'BACKGROUND':
        reporter.warning(f"World '{world.name}': node '{node.name}' is not supported; "
                         f"using a black background")
        return [0.0, 0.0, 0.0]
    color = _color(node, world.name, reporter, "Color", default=(0.05, 0.05, 0.05))
    strength = _value(node, 1.0, "Strength")
    return [c * strength for c in color]
