"""Lights whose Cycles controls Photon reads or says it does not: a portal, a narrow spread, and
light node trees (constant Emission Color and Strength, an IES Texture, Light Falloff, an
unconnected output). Reports light_arguments' colour and power for each, and the warnings."""

import bpy

import harness


class Reporter:
    def __init__(self):
        self.warnings = []

    def warning(self, message):
        self.warnings.append(message)


def light(name, kind="AREA", energy=100.0):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    data.color = (1.0, 0.5, 0.25)
    return data


def emission_of(data):
    data.use_nodes = True
    return next(n for n in data.node_tree.nodes if n.type == 'EMISSION')


def feed(data, node_type, output, socket):
    """`data` with a node of `node_type` feeding its Emission node's `socket`."""
    emission = emission_of(data)
    node = data.node_tree.nodes.new(node_type)
    data.node_tree.links.new(node.outputs[output], emission.inputs[socket])
    return data


def main():
    from photon import _photon
    from photon.sync import lights as sync_lights

    lights = {}
    lights["plain"] = light("plain")
    lights["default_nodes"] = light("default_nodes")
    emission_of(lights["default_nodes"])
    portal = lights["portal"] = light("portal", energy=5000.0)
    portal.cycles.is_portal = True
    narrow = lights["narrow"] = light("narrow")
    narrow.spread = 0.5236  # 30 degrees
    # Blender 4.0+ allows a spread of 0 (3.x stops at 1 degree).
    lights["beam"] = light("beam")
    lights["beam"].spread = 0.0
    constants = lights["constants"] = light("constants", "POINT")
    emission = emission_of(constants)
    emission.inputs["Strength"].default_value = 5.0
    emission.inputs["Color"].default_value = (0.5, 0.5, 1.0, 1.0)
    lights["ies"] = feed(light("ies", "SPOT"), "ShaderNodeTexIES", 0, "Strength")
    quadratic = lights["quadratic"] = feed(light("quadratic", "POINT"), "ShaderNodeLightFalloff",
                                           "Quadratic", "Strength")
    next(n for n in quadratic.node_tree.nodes if n.type == 'LIGHT_FALLOFF').inputs[
        "Strength"].default_value = 3.0
    lights["falloff"] = feed(light("falloff", "POINT"), "ShaderNodeLightFalloff", "Linear",
                             "Strength")
    lights["blackbody"] = feed(light("blackbody", "POINT"), "ShaderNodeBlackbody", 0, "Color")
    unconnected = lights["unconnected"] = light("unconnected", "POINT")
    emission_of(unconnected)
    unconnected.node_tree.links.remove(unconnected.node_tree.links[0])

    # Native power of an area light per watt of Blender's (4/pi from Blender 4.0, whose area
    # lights emit their whole power); reported powers are in Blender's watts.
    probe = bpy.data.objects.new("probe", light("probe", "AREA", 1.0))
    area_factor = sync_lights.light_arguments(_photon, probe, probe.matrix_world,
                                              Reporter())["power"]
    result = {"arguments": {}, "warnings": {}, "area_factor": area_factor,
              "version": list(bpy.app.version)}
    for name, data in lights.items():
        obj = bpy.data.objects.new(name, data)
        reporter = Reporter()
        args = sync_lights.light_arguments(_photon, obj, obj.matrix_world, reporter)
        factor = area_factor if data.type == 'AREA' else 1.0
        if args is not None and args.get("portal"):
            result["arguments"][name] = {k: v for k, v in args.items() if k != "matrix"}
            result["warnings"][name] = reporter.warnings
            continue
        result["arguments"][name] = None if args is None else {
            "color": [round(c, 6) for c in args["color"]],
            "power": round(args["power"] / factor, 6), "spectrum": args["spectrum"]}
        if args is not None and "spread" in args:
            result["arguments"][name]["spread"] = round(args["spread"], 6)
        for key in ("ies", "ies_strength", "ies_source", "ies_edges", "ies_area_by_direction"):
            if args is not None and key in args:
                result["arguments"][name][key] = args[key]
        result["warnings"][name] = reporter.warnings
    return result


if __name__ == "__main__":
    harness.run(main)
