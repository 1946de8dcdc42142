"""Writes test_scenes/nodes/color.json: the colour/converter node conformance cases, with each
ramp or curve case's table baked by addon/photon/sync/node_tables.py from the node as
tools/node_refs.py sets it up (so the gtest, which cannot run Blender, has Blender's data).

  blender -b --factory-startup --python test_scenes/nodes/make_color_manifest.py
  blender -b --factory-startup --python tools/node_refs.py -- \
      test_scenes/nodes/color.json test_scenes/nodes/color

The hit point's Object coordinate spans x, y in [-1, 1], z in [-0.25, 0.75]; fed to a float
socket it becomes the average of its components (about [-0.6, 0.65]).
"""

import importlib.util
import json
import os

import bpy

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _load(name, path):
    spec = importlib.util.spec_from_file_location(name, os.path.join(ROOT, path))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


node_refs = _load("node_refs", "tools/node_refs.py")
node_tables = _load("node_tables", "addon/photon/sync/node_tables.py")

BLENDS = ['MIX', 'DARKEN', 'MULTIPLY', 'BURN', 'LIGHTEN', 'SCREEN', 'DODGE', 'ADD', 'OVERLAY',
          'SOFT_LIGHT', 'LINEAR_LIGHT', 'DIFFERENCE', 'SUBTRACT', 'DIVIDE', 'HUE', 'SATURATION',
          'COLOR', 'VALUE']
COLOR_A = [0.6, 0.25, 0.9, 1.0]
COLOR_B = [0.8, 0.35, 0.05, 1.0]  # colour sockets clamp constants at 0


def case(name, node, vector, output="#0", properties=None, inputs=None, setup=None):
    c = {"name": name, "node": node, "vector": vector, "output": output}
    if properties:
        c["properties"] = properties
    if inputs:
        c["inputs"] = inputs
    if setup:
        c["setup"] = setup
    return c


def mix_cases():
    cases = []
    for blend in BLENDS:
        low = blend.lower()
        props = {"data_type": 'RGBA', "blend_type": blend}
        cases.append(case(f"mix_color_{low}", "ShaderNodeMix", "A", "Result", props,
                          {"Factor": 0.7, "B": COLOR_B}))
        # B varies, factor beyond 1 without clamping, result clamped.
        cases.append(case(f"mix_color_{low}_b_unclamped", "ShaderNodeMix", "B", "Result",
                          dict(props, clamp_factor=False), {"Factor": 1.25, "A": COLOR_A}))
        cases.append(case(f"mix_color_{low}_clamp_result", "ShaderNodeMix", "A", "Result",
                          dict(props, clamp_result=True), {"Factor": 0.8, "B": COLOR_B}))
    for clamp in (True, False):
        tag = "clamp" if clamp else "noclamp"
        cases.append(case(f"mix_color_factor_{tag}", "ShaderNodeMix", "Factor", "Result",
                          {"data_type": 'RGBA', "blend_type": 'MIX', "clamp_factor": clamp},
                          {"A": COLOR_A, "B": COLOR_B}))
        cases.append(case(f"mix_float_factor_{tag}", "ShaderNodeMix", "Factor", "Result",
                          {"data_type": 'FLOAT', "clamp_factor": clamp},
                          {"A": -0.5, "B": 2.0}))
        cases.append(case(f"mix_float_a_{tag}", "ShaderNodeMix", "A", "Result",
                          {"data_type": 'FLOAT', "clamp_factor": clamp},
                          {"Factor": 1.3, "B": 0.7}))
        cases.append(case(f"mix_vector_factor_{tag}", "ShaderNodeMix", "Factor", "Result",
                          {"data_type": 'VECTOR', "clamp_factor": clamp},
                          {"A": [1.0, -2.0, 0.5], "B": [-0.5, 3.0, 2.0]}))
        cases.append(case(f"mix_vector_a_{tag}", "ShaderNodeMix", "A", "Result",
                          {"data_type": 'VECTOR', "clamp_factor": clamp},
                          {"Factor": -0.4, "B": [-0.5, 3.0, 2.0]}))
        cases.append(case(f"mix_vector_nonuniform_factor_{tag}", "ShaderNodeMix", "Factor",
                          "Result", {"data_type": 'VECTOR', "factor_mode": 'NON_UNIFORM',
                                     "clamp_factor": clamp},
                          {"A": [1.0, -2.0, 0.5], "B": [-0.5, 3.0, 2.0]}))
        cases.append(case(f"mix_vector_nonuniform_a_{tag}", "ShaderNodeMix", "A", "Result",
                          {"data_type": 'VECTOR', "factor_mode": 'NON_UNIFORM',
                           "clamp_factor": clamp},
                          {"Factor": [0.2, 1.5, -0.3], "B": [-0.5, 3.0, 2.0]}))
    return cases


def mix_rgb_cases():
    cases = []
    for blend in BLENDS:
        low = blend.lower()
        cases.append(case(f"mixrgb_{low}", "ShaderNodeMixRGB", "Color1", "Color",
                          {"blend_type": blend}, {"Fac": 0.6, "Color2": COLOR_B}))
        # The legacy node always clamps its factor; use_clamp clamps the result.
        cases.append(case(f"mixrgb_{low}_color2_clamp", "ShaderNodeMixRGB", "Color2", "Color",
                          {"blend_type": blend, "use_clamp": True},
                          {"Fac": 1.5, "Color1": COLOR_A}))
    cases.append(case("mixrgb_fac", "ShaderNodeMixRGB", "Fac", "Color", {"blend_type": 'MIX'},
                      {"Color1": COLOR_A, "Color2": COLOR_B}))
    return cases


def adjust_cases():
    return [
        case("hsv_color", "ShaderNodeHueSaturation", "Color", "Color", None,
             {"Hue": 0.3, "Saturation": 1.4, "Value": 0.8, "Fac": 0.9}),
        case("hsv_hue", "ShaderNodeHueSaturation", "Hue", "Color", None,
             {"Color": [0.7, 0.2, 0.4, 1.0], "Saturation": 0.6, "Value": 1.3, "Fac": 1.0}),
        case("hsv_fac", "ShaderNodeHueSaturation", "Fac", "Color", None,
             {"Color": [0.7, 0.2, 0.4, 1.0], "Hue": 0.8, "Saturation": 2.0}),
        case("invert_color", "ShaderNodeInvert", "Color", "Color", None, {"Fac": 0.7}),
        case("invert_fac", "ShaderNodeInvert", "Fac", "Color", None,
             {"Color": [0.7, 0.2, 1.4, 1.0]}),
        case("gamma_color", "ShaderNodeGamma", "Color", "Color", None, {"Gamma": 2.2}),
        case("gamma_zero", "ShaderNodeGamma", "Color", "Color", None, {"Gamma": 0.0}),
        case("gamma_gamma", "ShaderNodeGamma", "Gamma", "Color", None,
             {"Color": [0.3, 1.5, 0.0, 1.0]}),
        case("bright_contrast_color", "ShaderNodeBrightContrast", "Color", "Color", None,
             {"Bright": 0.1, "Contrast": 0.5}),
        case("bright_contrast_contrast", "ShaderNodeBrightContrast", "Contrast", "Color", None,
             {"Color": [0.3, 0.9, 0.6, 1.0], "Bright": -0.2}),
        case("rgb_to_bw", "ShaderNodeRGBToBW", "Color", "Val"),
    ]


def separate_combine_cases():
    cases = []
    for out in ("R", "G", "B"):
        cases.append(case(f"separate_rgb_{out.lower()}", "ShaderNodeSeparateRGB", "Image", out))
    cases.append(case("combine_rgb", "ShaderNodeCombineRGB", "G", "Image", None,
                      {"R": 0.3, "B": -0.4}))
    for out in ("X", "Y", "Z"):
        cases.append(case(f"separate_xyz_{out.lower()}", "ShaderNodeSeparateXYZ", "Vector", out))
    cases.append(case("combine_xyz", "ShaderNodeCombineXYZ", "Z", "Vector", None,
                      {"X": 0.3, "Y": -0.4}))
    for out in ("H", "S", "V"):
        cases.append(case(f"separate_hsv_{out.lower()}", "ShaderNodeSeparateHSV", "Color", out))
    for linked, others in (("H", {"S": 0.7, "V": 0.9}), ("S", {"H": 0.4, "V": 0.9}),
                           ("V", {"H": 0.85, "S": 0.6})):
        cases.append(case(f"combine_hsv_{linked.lower()}", "ShaderNodeCombineHSV", linked,
                          "Color", None, others))
    for mode in ("RGB", "HSV", "HSL"):
        for out in ("Red", "Green", "Blue"):
            cases.append(case(f"separate_color_{mode.lower()}_{out.lower()}",
                              "ShaderNodeSeparateColor", "Color", out, {"mode": mode}))
        for linked, others in (("Red", {"Green": 0.7, "Blue": 0.6}),
                               ("Green", {"Red": 0.4, "Blue": 0.6}),
                               ("Blue", {"Red": 0.85, "Green": 0.6})):
            cases.append(case(f"combine_color_{mode.lower()}_{linked.lower()}",
                              "ShaderNodeCombineColor", linked, "Color", {"mode": mode}, others))
    return cases


def spectrum_cases():
    cases = []
    # Constant inputs: the coordinate cannot reach kelvins or nanometres. Every segment of
    # Cycles' blackbody fit, both ends of its range, and the wavelength table's ends.
    for kelvin in (500, 799, 800, 900, 1000, 1200, 1500, 2500, 4000, 6500, 11999, 12000, 20000):
        cases.append(case(f"blackbody_{kelvin}", "ShaderNodeBlackbody", None, "Color", None,
                          {"Temperature": float(kelvin)}))
    for nm in (379.0, 380.0, 412.3, 455.0, 487.6, 532.7, 575.0, 610.2, 655.0, 700.0, 742.5, 779.0,
               779.9, 780.0, 790.0):
        cases.append(case(f"wavelength_{str(nm).replace('.', '_')}", "ShaderNodeWavelength",
                          None, "Color", None, {"Wavelength": nm}))
    return cases


RAMP_ELEMENTS = [[0.05, [0.9, 0.1, 0.1, 1.0]], [0.2, [0.1, 0.8, 0.2, 0.5]],
                 [0.35, [0.1, 0.2, 0.9, 0.0]], [0.5, [1.0, 0.9, 0.2, 0.8]],
                 [0.62, [0.3, 0.05, 0.6, 0.3]]]


def ramp_cases():
    cases = []
    for interpolation in ("CONSTANT", "LINEAR", "EASE", "CARDINAL", "B_SPLINE"):
        setup = {"color_ramp": {"interpolation": interpolation, "color_mode": 'RGB',
                                "elements": RAMP_ELEMENTS}}
        for out in ("Color", "Alpha"):
            cases.append(case(f"ramp_{interpolation.lower()}_{out.lower()}", "ShaderNodeValToRGB",
                              "Fac", out, setup=setup))
    for mode in ("HSV", "HSL"):
        for hue in ("NEAR", "FAR", "CW", "CCW"):
            setup = {"color_ramp": {"interpolation": 'LINEAR', "color_mode": mode,
                                    "hue_interpolation": hue, "elements": RAMP_ELEMENTS}}
            cases.append(case(f"ramp_{mode.lower()}_{hue.lower()}", "ShaderNodeValToRGB", "Fac",
                              "Color", setup=setup))
    cases.append(case("ramp_default", "ShaderNodeValToRGB", "Fac", "Color"))
    return cases


def curve_cases():
    cases = []
    rgb = [[[0.0, 0.1, 'AUTO'], [0.4, 0.7, 'AUTO'], [1.0, 0.9, 'AUTO']],
           [[0.0, 0.3, 'AUTO_CLAMPED'], [0.6, 0.2, 'AUTO_CLAMPED'], [1.0, 1.0, 'AUTO_CLAMPED']],
           [[0.0, 0.0, 'VECTOR'], [0.5, 0.8, 'VECTOR'], [1.0, 0.6, 'VECTOR']],
           [[0.0, 0.05, 'AUTO'], [0.3, 0.5, 'AUTO'], [1.0, 0.95, 'AUTO']]]
    wide = [[[-0.5, 0.2, 'AUTO'], [0.4, 0.7, 'AUTO'], [1.0, 0.9, 'AUTO']], None, None,
            [[0.0, 0.0, 'AUTO'], [1.3, 1.1, 'AUTO']]]
    for extend in ("EXTRAPOLATED", "HORIZONTAL"):
        setup = {"mapping": {"extend": extend, "curves": rgb}}
        cases.append(case(f"rgb_curves_{extend.lower()}", "ShaderNodeRGBCurve", "Color",
                          "Color", None, {"Fac": 0.9}, setup))
    cases.append(case("rgb_curves_wide_range", "ShaderNodeRGBCurve", "Color", "Color", None,
                      {"Fac": 1.0}, {"mapping": {"extend": 'EXTRAPOLATED', "curves": wide}}))
    cases.append(case("rgb_curves_fac", "ShaderNodeRGBCurve", "Fac", "Color", None,
                      {"Color": [0.2, 0.5, 1.3, 1.0]},
                      {"mapping": {"extend": 'EXTRAPOLATED', "curves": rgb}}))
    vec = [[[-1.0, -0.8, 'AUTO'], [0.0, 0.4, 'AUTO'], [1.0, 0.6, 'AUTO']],
           [[-1.0, 0.5, 'VECTOR'], [0.2, -0.5, 'VECTOR'], [1.0, 1.0, 'VECTOR']],
           [[-0.5, -1.0, 'AUTO_CLAMPED'], [0.3, 0.2, 'AUTO_CLAMPED'], [0.6, 0.9, 'AUTO_CLAMPED']]]
    for extend in ("EXTRAPOLATED", "HORIZONTAL"):
        setup = {"mapping": {"extend": extend, "curves": vec}}
        cases.append(case(f"vector_curves_{extend.lower()}", "ShaderNodeVectorCurve", "Vector",
                          "Vector", None, {"Fac": 0.8}, setup))
    cases.append(case("vector_curves_default", "ShaderNodeVectorCurve", "Vector", "Vector"))
    flt = [[[0.0, 0.2, 'AUTO'], [0.25, 0.9, 'AUTO'], [0.5, 0.1, 'VECTOR'], [0.8, 0.6, 'AUTO']]]
    for extend in ("EXTRAPOLATED", "HORIZONTAL"):
        setup = {"mapping": {"extend": extend, "curves": flt}}
        cases.append(case(f"float_curve_{extend.lower()}", "ShaderNodeFloatCurve", "Value",
                          "Value", None, {"Factor": 0.85}, setup))
    cases.append(case("float_curve_factor", "ShaderNodeFloatCurve", "Factor", "Value", None,
                      {"Value": 0.4}, {"mapping": {"extend": 'EXTRAPOLATED', "curves": flt}}))
    return cases


def add_tables(cases):
    """Bakes each ramp/curve case's table from the node exactly as node_refs sets it up."""
    for c in cases:
        if c["node"] not in ("ShaderNodeValToRGB", "ShaderNodeRGBCurve",
                             "ShaderNodeVectorCurve", "ShaderNodeFloatCurve"):
            continue
        mat = node_refs._material(c)
        node = next(n for n in mat.node_tree.nodes if n.bl_idname == c["node"])
        c["table"] = [round(v, 9) for v in node_tables.node_table(node)]


def main():
    cases = (mix_cases() + mix_rgb_cases() + adjust_cases() + separate_combine_cases()
             + spectrum_cases() + ramp_cases() + curve_cases())
    add_tables(cases)
    path = os.path.join(ROOT, "test_scenes", "nodes", "color.json")
    with open(path, "w") as f:
        json.dump({"cases": cases}, f, indent=1)
    print(f"wrote {len(cases)} cases to {path}")


main()
