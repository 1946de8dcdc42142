"""Blender lights to native lights, in Blender's units (watts; the sun in W/m^2)."""

import math

import numpy as np

from . import nodes


def visibility_bits(native, obj):
    """Object > Visibility > Ray Visibility toggles as the native visibility mask."""
    bits = 0
    if getattr(obj, "visible_camera", True):
        bits |= native.VISIBLE_CAMERA
    if getattr(obj, "visible_diffuse", True):
        bits |= native.VISIBLE_DIFFUSE
    if getattr(obj, "visible_glossy", True):
        bits |= native.VISIBLE_GLOSSY
    if getattr(obj, "visible_transmission", True):
        bits |= native.VISIBLE_TRANSMISSION
    if getattr(obj, "visible_shadow", True):
        bits |= native.VISIBLE_SHADOW
    return bits


def blackbody_temperature(light):
    """The temperature of a Blackbody node feeding the Color of the Emission node at the light's
    output (Use Nodes), when its Temperature is a plain value; else None."""
    tree = light.node_tree if getattr(light, "use_nodes", False) else None
    if tree is None:
        return None
    output = nodes.output_node(tree, 'OUTPUT_LIGHT')
    surface = output.inputs.get("Surface") if output else None
    emission = nodes.source(surface).node if surface is not None else None
    if emission is None or emission.type != 'EMISSION':
        return None
    color = nodes.find_input(emission, "Color")
    found = nodes.source(color).node if color is not None else None
    if found is None or found.type != 'BLACKBODY':
        return None
    temperature = nodes.find_input(found, "Temperature")
    if temperature is None or temperature.is_linked:
        return None
    value = float(temperature.default_value)
    return value if math.isfinite(value) and value > 0.0 else None


def light_spectrum(light):
    """The spectrum, temperature and illuminant add_light takes: light.photon's, or Blackbody
    at a Blackbody node's temperature (see blackbody_temperature) while that is RGB."""
    settings = getattr(light, "photon", None)
    spectrum = settings.spectrum if settings is not None else "RGB"
    temperature = float(settings.temperature) if settings is not None else 6500.0
    illuminant = settings.illuminant if settings is not None else "D65"
    if spectrum == "RGB":
        node_temperature = blackbody_temperature(light)
        if node_temperature is not None:
            spectrum, temperature = "BLACKBODY", node_temperature
    return spectrum, temperature, illuminant


def light_arguments(native, obj, matrix, reporter):
    """Scene.add_light keyword arguments of one light, or None when it adds no light. The
    "matrix" is the world matrix in double precision: sync rebases it (sync_origin) before
    making it float32."""
    light = obj.data
    power = float(light.energy)
    color = [float(c) for c in light.color]
    if not all(math.isfinite(v) for v in color + [power]):
        reporter.warning(f"Light '{obj.name}': non-finite colour or power; skipped")
        return None
    if power <= 0.0 or max(color) <= 0.0:
        reporter.warning(f"Light '{obj.name}' has zero power; it adds no light")
        return None
    kwargs = {
        "name": obj.name,
        "type": light.type,
        "matrix": np.array(matrix, dtype=np.float64),
        "color": color,
        "power": power,
        "visibility": visibility_bits(native, obj),
    }
    kwargs["spectrum"], kwargs["temperature"], kwargs["illuminant"] = light_spectrum(light)
    if light.type in {'POINT', 'SPOT'}:
        kwargs["radius"] = float(light.shadow_soft_size)
    if light.type == 'SPOT':
        kwargs["spot_size"] = float(light.spot_size)
        kwargs["spot_blend"] = float(light.spot_blend)
    elif light.type == 'SUN':
        kwargs["sun_angle"] = float(light.angle)
    elif light.type == 'AREA':
        kwargs["shape"] = light.shape
        kwargs["size_x"] = float(light.size)
        kwargs["size_y"] = float(light.size_y)
        if light.shape in {'SQUARE', 'DISK'}:
            degenerate = light.size <= 0.0
        else:
            degenerate = light.size <= 0.0 or light.size_y <= 0.0
        if degenerate:
            reporter.warning(f"Area light '{obj.name}' has zero size; skipped")
            return None
    return kwargs
