"""The render parameters' schema, declared once in the native library (render_params.h): from
_photon.parameter_schema(), or from parameter_schema.json staged beside it at build time when the
native module does not import. properties.py generates scene.photon's properties from it,
ui.py draws them, render_settings.make_settings copies them into the native settings by name."""

import json
import os

from . import native

INT32_MAX = (1 << 31) - 1
SCHEMA_FILE = os.path.join(os.path.dirname(__file__), "parameter_schema.json")


def _load():
    if native.MODULE is not None:
        return native.MODULE.parameter_schema(), None
    try:
        with open(SCHEMA_FILE, encoding="utf-8") as f:
            return json.load(f), None
    except (OSError, ValueError) as exc:
        return [], f"{type(exc).__name__}: {exc}"


GROUPS, LOAD_ERROR = _load()


def group(name):
    for g in GROUPS:
        if g["name"] == name:
            return g
    return None


def params():
    for g in GROUPS:
        yield from g["params"]


def _int32(value):
    return max(-INT32_MAX - 1, min(INT32_MAX, int(value)))


def make_property(p, update=None):
    """The bpy.props definition of schema parameter p. Integer and float properties hold
    value / ui_scale (radiosity rays in thousands); Blender integers stop at 2^31 - 1.
    `update(self, context)` runs after every change."""
    from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty
    common = {"name": p["label"], "description": p["description"]}
    if update is not None:
        common["update"] = update
    kind = p["type"]
    if kind == "bool":
        return BoolProperty(default=bool(p["default"]), **common)
    if kind == "enum":
        items = [(i["id"], i["label"], i["description"]) for i in p["items"]]
        return EnumProperty(items=items, default=p["default"], **common)
    scale = p["ui_scale"]
    ranges = {k: p[k] / scale for k in ("min", "max", "soft_min", "soft_max") if k in p}
    if p["subtype"]:
        common["subtype"] = p["subtype"]
    if kind == "float":
        if p["unit"]:
            common["unit"] = p["unit"]
        if p["precision"] >= 0:
            common["precision"] = p["precision"]
        return FloatProperty(default=p["default"] / scale, **ranges, **common)
    return IntProperty(default=_int32(p["default"] / scale),
                       **{k: _int32(v) for k, v in ranges.items()}, **common)


def native_value(p, value):
    """The Blender property's value as the native field wants it (unclamped: the native
    session clamps out-of-range values with a warning)."""
    kind = p["type"]
    if kind == "bool":
        return bool(value)
    if kind == "enum":
        return str(value)
    if kind == "float":
        return float(value) * p["ui_scale"]
    return int(value) * int(p["ui_scale"])


def draw(layout, props, group_name):
    """Draws one group's parameters in schema order: consecutive parameters sharing a ui column
    are aligned in one column, ui.active_if greys a parameter out while another is zero."""
    g = group(group_name)
    if g is None:
        return
    column_id, column = 0, None
    for p in g["params"]:
        ui = p["ui"]
        if ui["column"]:
            if ui["column"] != column_id:
                column_id, column = ui["column"], layout.column(align=True)
            target = column
        else:
            column_id, target = 0, layout
        if ui["active_if"]:
            target = target.row()
            target.active = bool(getattr(props, ui["active_if"]))
        if ui["text"]:
            target.prop(props, p["name"], text=ui["text"])
        else:
            target.prop(props, p["name"])
