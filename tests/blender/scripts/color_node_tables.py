"""Bakes every ramp/curve case of test_scenes/nodes/color.json with the staged add-on's
photon.sync.node_tables, from the node as tools/node_refs.py sets it up, and reports the tables
next to the manifest's (which the C++ conformance test reads), plus a few nodes with known
tables: Blender's default ramp and curves, a CONSTANT ramp, and a curve with bad data."""

import importlib.util
import json
from pathlib import Path

import bpy

import harness

REPO = Path(__file__).resolve().parents[3]


def _node_refs():
    spec = importlib.util.spec_from_file_location("node_refs", REPO / "tools" / "node_refs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    from photon.sync.node_tables import TABLE_SIZE, node_table
    node_refs = _node_refs()
    with open(REPO / "test_scenes" / "nodes" / "color.json") as f:
        cases = json.load(f)["cases"]
    result = {"table_size": TABLE_SIZE, "cases": {}}
    for case in cases:
        if "table" not in case:
            continue
        mat = node_refs._material(case)
        node = next(n for n in mat.node_tree.nodes if n.bl_idname == case["node"])
        result["cases"][case["name"]] = {"manifest": case["table"], "baked": node_table(node)}
    tree = bpy.data.materials.new("defaults")
    tree.use_nodes = True
    nodes = tree.node_tree.nodes
    result["defaults"], result["extend"] = {}, {}
    for idname in ("ShaderNodeValToRGB", "ShaderNodeRGBCurve", "ShaderNodeVectorCurve",
                   "ShaderNodeFloatCurve", "ShaderNodeMath"):
        node = nodes.new(idname)
        result["defaults"][idname] = node_table(node)
        if hasattr(node, "mapping"):
            result["extend"][idname] = node.mapping.extend
    constant = nodes.new("ShaderNodeValToRGB")
    constant.color_ramp.interpolation = 'CONSTANT'
    result["constant_ramp"] = node_table(constant)
    return result


harness.run(main)
