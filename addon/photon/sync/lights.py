"""Blender lights to native lights, in Blender's units (watts; the sun in W/m^2)."""

import math

import bpy
import numpy as np

from . import light_ies, nodes


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


def _upstream_nodes(tree, socket):
    """The nodes feeding `socket` of a light's node tree, directly or through other nodes, in
    the order met (breadth first)."""
    found, queue, seen = [], [socket], set()
    while queue:
        current = queue.pop(0)
        for link in tree.links:
            if link.to_socket != current or link.is_muted or link.from_node.name in seen:
                continue
            node = link.from_node
            seen.add(node.name)
            found.append(node)
            queue.extend(i for i in node.inputs if i.is_linked)
    return found


def _node_label(node):
    return f"{node.bl_label} '{node.name}'" if node.name != node.bl_label else node.bl_label


def _quadratic_falloff(socket):
    """The strength of a Light Falloff node's Quadratic output feeding `socket` when it is a
    plain value: Cycles' lamps already fall off with the square of the distance, so without
    Smooth that output is its Strength. None for anything else."""
    found = nodes.source(socket)
    node = found.node
    if node is None or node.type != 'LIGHT_FALLOFF' or found.output_name != "Quadratic":
        return None
    strength, smooth = nodes.find_input(node, "Strength"), nodes.find_input(node, "Smooth")
    if strength is None or strength.is_linked or smooth is None or smooth.is_linked:
        return None
    if float(smooth.default_value) != 0.0:
        return None
    return float(strength.default_value)


def node_emission(light, name, reporter):
    """(colour factor, strength factor, IES arguments or None) of the light's own node tree (Use
    Nodes), which Cycles multiplies into the light's colour and power: the constant Color and
    Strength of the Emission node at its Light Output (a Blackbody node feeding the Color sets
    the spectrum instead, see light_spectrum; an IES Texture feeding the Strength gives a
    profile, see light_ies; a Light Falloff's Quadratic output without Smooth is its Strength).
    Photon does not evaluate other nodes feeding them (Light Falloff's Linear and Constant
    outputs or a Smooth, a texture): it warns, naming them, and renders the sockets' own
    values."""
    tree = light.node_tree if getattr(light, "use_nodes", False) else None
    if tree is None:
        return [1.0, 1.0, 1.0], 1.0, None
    output = nodes.output_node(tree, 'OUTPUT_LIGHT')
    surface = output.inputs.get("Surface") if output else None
    emission = nodes.source(surface).node if surface is not None else None
    if emission is None or emission.type != 'EMISSION':
        what = "nothing" if emission is None else _node_label(emission)
        reporter.warning(f"Light '{name}': its node tree has {what} at its Light Output, which "
                         f"Photon does not evaluate; the light is rendered as without nodes")
        return [1.0, 1.0, 1.0], 1.0, None
    color, strength, ies = [1.0, 1.0, 1.0], 1.0, None
    ignored = []
    color_socket = nodes.find_input(emission, "Color")
    if color_socket is not None:
        if color_socket.is_linked:
            if blackbody_temperature(light) is None:
                ignored += _upstream_nodes(tree, color_socket)
        else:
            color = [float(c) for c in color_socket.default_value[:3]]
    strength_socket = nodes.find_input(emission, "Strength")
    if strength_socket is not None:
        if strength_socket.is_linked:
            ies = light_ies.strength_profile(strength_socket, name, reporter)
            quadratic = _quadratic_falloff(strength_socket)
            if quadratic is not None:
                strength = quadratic
            elif ies is None:
                ignored += _upstream_nodes(tree, strength_socket)
        else:
            strength = float(strength_socket.default_value)
    if ignored:
        labels = ", ".join(dict.fromkeys(_node_label(n) for n in ignored))
        reporter.warning(f"Light '{name}': {labels} in its node tree not rendered by Photon "
                         f"yet; the Emission node's own Color and Strength values are used")
    return color, strength, ies


FLOAT32_MAX = float(np.finfo(np.float32).max)

# Cycles 3.x renders a spread narrower than a degree as a degree (Blender 3.x's own minimum);
# Blender 4.0+ goes down to 0, a parallel beam Photon renders as 1 degree.
MIN_SPREAD = math.radians(1.0)


def light_arguments(native, obj, matrix, reporter):
    """Scene.add_light keyword arguments of one light, or None when it adds no light. The
    "matrix" is the world matrix in double precision: sync rebases it (sync_origin) before
    making it float32."""
    light = obj.data
    if light.type == 'AREA' and getattr(getattr(light, "cycles", None), "is_portal", False):
        return portal_arguments(obj, matrix, reporter)
    node_color, node_strength, ies = node_emission(light, obj.name, reporter)
    power = float(light.energy) * node_strength * 2.0 ** float(getattr(light, "exposure", 0.0))
    color = [float(c) * f for c, f in zip(light.color, node_color)]
    if getattr(light, "use_temperature", False):
        # Blender 5.0+: Cycles multiplies the colour by the temperature's RGB colour.
        color = [c * float(t) for c, t in zip(color, light.temperature_color[:3])]
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
    if ies is not None:
        kwargs.update(ies)
    if light.type in {'POINT', 'SPOT'}:
        kwargs["radius"] = float(light.shadow_soft_size)
    if light.type == 'SPOT':
        kwargs["spot_size"] = float(light.spot_size)
        kwargs["spot_blend"] = float(light.spot_blend)
        # Measured before this: a 70 degree spot 7.3% darker than Cycles 4.3, the mean of the
        # cosine over its cone.
        kwargs["spot_cosine_falloff"] = bpy.app.version < (4, 0, 0)
    elif light.type == 'SUN':
        kwargs["sun_angle"] = float(light.angle)
    elif light.type == 'AREA':
        if bpy.app.version >= (4, 0, 0):
            # Cycles 4.0 made an area light of power P emit exactly P (radiance P / (pi A));
            # 3.x gave it radiance P / (4 A), the convention Photon's lamps follow. Measured:
            # Photon / Cycles 4.3 = 0.785 = pi / 4 on every area shape before this factor.
            kwargs["power"] = power * 4.0 / math.pi
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
        spread = float(getattr(light, "spread", math.pi))
        if spread < MIN_SPREAD * (1.0 - 1e-6):
            reporter.warning(f"Area light '{obj.name}': a spread of {math.degrees(spread):.2f} "
                             f"degrees is rendered as 1 degree, the narrowest Photon renders")
        kwargs["spread"] = max(spread, MIN_SPREAD)
    if not getattr(light, "normalize", True):
        kwargs["power"] *= unnormalized_power_factor(light)
    # The factors above can take a huge but finite power past float32, which the native light
    # would take as infinite and skip; at the largest float it is clamped with a warning there.
    kwargs["power"] = min(kwargs["power"], FLOAT32_MAX)
    return kwargs


def portal_arguments(obj, matrix, reporter):
    """Scene.add_portal keyword arguments of an area light marked as a portal (with "portal":
    True), or None for one without area. A portal emits nothing and no ray sees it, as in
    Cycles: it guides the world's light samples and photons through a window."""
    light = obj.data
    height = light.size if light.shape in {'SQUARE', 'DISK'} else light.size_y
    if not (light.size > 0.0 and height > 0.0):
        reporter.warning(f"Portal '{obj.name}' has zero size; skipped")
        return None
    return {
        "portal": True,
        "name": obj.name,
        "matrix": np.array(matrix, dtype=np.float64),
        "shape": light.shape,
        "size_x": float(light.size),
        "size_y": float(light.size_y),
    }


def unnormalized_power_factor(light):
    """Blender 5.0+'s Normalize switched off: Cycles no longer divides the light's strength by
    its emitting area (the sphere's 4 pi r^2 for a point or spot, the shape's area, pi
    tan^2(angle / 2) for the sun), so the light emits as a normalized one of power * area. A
    point-sized light is unchanged (Cycles divides by 1 either way). Measured in Cycles 5.2:
    unnormalized / normalized = 4 pi r^2 for points and spots of radius 0.3 and 0.6, soft
    falloff on or off."""
    if light.type in {'POINT', 'SPOT'}:
        area = 4.0 * math.pi * float(light.shadow_soft_size) ** 2
    elif light.type == 'SUN':
        area = math.pi * math.tan(float(light.angle) * 0.5) ** 2
    else:
        height = light.size if light.shape in {'SQUARE', 'DISK'} else light.size_y
        area = float(light.size) * float(height)
        if light.shape in {'DISK', 'ELLIPSE'}:
            area *= math.pi / 4.0
    return area if area > 0.0 and math.isfinite(area) else 1.0
