"""Reports scene.photon's generated properties (RNA defaults and ranges) next to the schema they
were generated from, and optionally sets out-of-range values straight into the ID properties
(bypassing the UI's and RNA's clamping, as an old .blend or a script can): `name=value` after
the result path. The rest of Blender's command line then renders."""

import json
import math

import bpy

import harness


def rna_info(props, name):
    rna = props.bl_rna.properties[name]
    info = {"type": rna.type}
    if rna.type == "ENUM":
        info["default"] = rna.default
        info["items"] = [item.identifier for item in rna.enum_items]
    elif rna.type == "BOOLEAN":
        info["default"] = rna.default
    else:
        info.update(default=rna.default, min=rna.hard_min, max=rna.hard_max,
                    soft_min=rna.soft_min, soft_max=rna.soft_max, subtype=rna.subtype)
        if rna.type == "FLOAT":
            info["unit"] = rna.unit
    return info


def main(*overrides):
    from photon import schema
    props = bpy.context.scene.photon
    result = {"schema": schema.GROUPS, "load_error": schema.LOAD_ERROR, "rna": {}}
    for p in schema.params():
        result["rna"][p["name"]] = rna_info(props, p["name"])
    try:
        from photon import _photon
        result["native_schema"] = _photon.parameter_schema() if _photon else None
    except ImportError:
        result["native_schema"] = None
    with open(schema.SCHEMA_FILE, encoding="utf-8") as f:
        result["json_schema"] = json.load(f)
    for arg in overrides:
        name, value = arg.split("=", 1)
        number = float(value)
        props[name] = int(number) if number.is_integer() else number
        read = getattr(props, name)
        result.setdefault("read_back", {})[name] = None if math.isnan(read) else read
    return result


harness.run(main)
