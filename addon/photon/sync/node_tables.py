"""Tables for the shader nodes whose data lives in Blender (colour ramps and curve mappings),
baked the way Cycles bakes them (intern/cycles/blender/util.h: colorramp_to_array,
curvemapping_color_to_array, curvemapping_float_to_array), so Photon's lookups
(native/src/photon/shading/color_nodes.cpp) see the same samples Cycles' kernel does.

Layouts (flat float lists, put in NodeDesc.table by the shader compiler):

ShaderNodeValToRGB:
    [interpolate, r0, g0, b0, a0, r1, g1, b1, a1, ...]
    interpolate is 0.0 for interpolation CONSTANT (Cycles then takes the sample below the
    factor), else 1.0; TABLE_SIZE RGBA samples of color_ramp.evaluate(i / (TABLE_SIZE - 1)).
    EASE, CARDINAL, B_SPLINE and the HSV/HSL colour modes are all inside Blender's evaluate().

ShaderNodeRGBCurve, ShaderNodeVectorCurve:
    [min_x, max_x, extrapolate, x0, y0, z0, x1, y1, z1, ...]
    min_x/max_x are the smallest first and largest last point location over the curves (C, R,
    G, B for RGB curves; X, Y, Z for vector curves), extrapolate is 1.0 when mapping.extend is
    EXTRAPOLATED; then TABLE_SIZE samples at t = min_x + i / (TABLE_SIZE - 1) * (max_x - min_x):
    RGB curves compose each channel's curve with the combined (C) curve, R(C(t)).

ShaderNodeFloatCurve:
    [min_x, max_x, extrapolate, v0, v1, ...]   (the one curve, sampled the same way)
"""

TABLE_SIZE = 256  # Cycles' RAMP_TABLE_SIZE

_CURVE_NODES = {"ShaderNodeRGBCurve": 4, "ShaderNodeVectorCurve": 3, "ShaderNodeFloatCurve": 1}


def _float32(value):
    """Rounds like the float the C++ side stores (and Cycles computes in)."""
    import struct

    return struct.unpack("f", struct.pack("f", value))[0]


def _ramp_table(ramp):
    table = [0.0 if ramp.interpolation == 'CONSTANT' else 1.0]
    for i in range(TABLE_SIZE):
        table.extend(ramp.evaluate(_float32(i / (TABLE_SIZE - 1))))
    return table


def _curve_range(mapping, count):
    """Cycles' curvemapping_minmax: the x extent of the first `count` curves' end points."""
    min_x, max_x = float("inf"), float("-inf")
    for curve in list(mapping.curves)[:count]:
        points = curve.points
        if len(points) == 0:
            continue
        min_x = min(min_x, points[0].location[0])
        max_x = max(max_x, points[len(points) - 1].location[0])
    if min_x > max_x:
        return 0.0, 1.0
    return min_x, max_x


def _curve_table(node, count):
    mapping = node.mapping
    mapping.initialize()
    min_x, max_x = _curve_range(mapping, count)
    # Cycles calls CurveMapping.update() (BKE_curvemapping_changed_all) before sampling.
    mapping.update()
    curves = list(mapping.curves)
    extrapolate = 1.0 if mapping.extend == 'EXTRAPOLATED' else 0.0
    table = [min_x, max_x, extrapolate]
    span = _float32(max_x - min_x)
    for i in range(TABLE_SIZE):
        t = _float32(min_x + _float32(_float32(i / (TABLE_SIZE - 1)) * span))
        if count == 4:
            combined = mapping.evaluate(curves[3], t)
            table.extend(mapping.evaluate(curves[c], combined) for c in range(3))
        elif count == 3:
            table.extend(mapping.evaluate(curves[c], t) for c in range(3))
        else:
            table.append(mapping.evaluate(curves[0], t))
    return table


def node_table(node):
    """The flat table Photon's colour nodes read for `node` (layouts above), or None when the
    node keeps no data in Blender."""
    idname = node.bl_idname
    if idname == "ShaderNodeValToRGB":
        return _ramp_table(node.color_ramp)
    if idname in _CURVE_NODES:
        return _curve_table(node, _CURVE_NODES[idname])
    return None
