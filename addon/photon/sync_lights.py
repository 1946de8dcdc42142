"""Blender lights to native lights, in Blender's units (watts; the sun in W/m^2)."""

import math

import numpy as np


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


def export_light(native, native_scene, obj, matrix, reporter):
    """Adds one light; returns True if it was added."""
    light = obj.data
    power = float(light.energy)
    color = [float(c) for c in light.color]
    if not all(math.isfinite(v) for v in color + [power]):
        reporter.warning(f"Light '{obj.name}': non-finite colour or power; skipped")
        return False
    if power <= 0.0 or max(color) <= 0.0:
        reporter.warning(f"Light '{obj.name}' has zero power; it adds no light")
        return False
    kwargs = {
        "name": obj.name,
        "type": light.type,
        "matrix": np.asarray(matrix, dtype=np.float32),
        "color": color,
        "power": power,
        "visibility": visibility_bits(native, obj),
    }
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
            return False
    native_scene.add_light(**kwargs)
    return True
