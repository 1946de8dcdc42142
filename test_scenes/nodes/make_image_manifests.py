#!/usr/bin/env python3
"""Writes the conformance manifests of the image, normal-map, object-info and camera-coordinate
nodes (image.json, normal_map.json, object_info.json, camera_coords.json) beside this script;
tools/node_refs.py renders them:

  /usr/bin/python3 test_scenes/nodes/make_image_manifests.py
  for m in image normal_map object_info camera_coords; do
    blender -b --factory-startup --python tools/node_refs.py -- \
        test_scenes/nodes/$m.json test_scenes/nodes/$m
  done

The textures (image/tex.png, image/tex.exr) come from image/make_image.py. The hit point's
Object coordinate spans x, y in [-1, 1], z in [-0.25, 0.75]; the flat-projection cases scale it
by 0.75 so part of the plane lies outside the [0, 1] image square (the extension modes show)
with a texel about 3 x 5 pixels wide.
"""

import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
FILES = {"png": {"file": "image/tex.png", "colorspace": "sRGB", "alpha_mode": "STRAIGHT"},
         "exr": {"file": "image/tex.exr", "colorspace": "Non-Color", "alpha_mode": "STRAIGHT"}}
TRANSFORM = {"location": [0.1, -0.2, 0.3], "rotation": [0.4, -0.25, 0.3], "scale": [1.3, 0.8, 1.1]}


def image_cases():
    cases = []
    for interpolation in ("Closest", "Linear", "Cubic", "Smart"):
        for extension in ("REPEAT", "EXTEND", "CLIP"):
            for key, image in FILES.items():
                for output in ("Color", "Alpha"):
                    cases.append({
                        "name": f"image_flat_{interpolation.lower()}_{extension.lower()}_"
                                f"{key}_{output.lower()}",
                        "node": "ShaderNodeTexImage", "image": image,
                        "properties": {"interpolation": interpolation, "extension": extension},
                        "vector_scale": 0.75, "output": output})
    for mode in ("PREMUL", "CHANNEL_PACKED", "NONE"):
        for output in ("Color", "Alpha"):
            cases.append({"name": f"image_alpha_{mode.lower()}_{output.lower()}",
                          "node": "ShaderNodeTexImage",
                          "image": dict(FILES["png"], alpha_mode=mode),
                          "properties": {"interpolation": "Linear"},
                          "vector_scale": 0.75, "output": output})
    # Colour read while the Alpha output is used too (it drives the Emission's Strength): Cycles
    # then divides the premultiplied colour by alpha after the lookup.
    for interpolation in ("Closest", "Linear", "Cubic"):
        for key, image in (("png", FILES["png"]), ("exr_srgb", dict(FILES["exr"], colorspace="sRGB")),
                           ("png_noncolor", dict(FILES["png"], colorspace="Non-Color"))):
            cases.append({"name": f"image_color_times_alpha_{interpolation.lower()}_{key}",
                          "node": "ShaderNodeTexImage", "image": image,
                          "properties": {"interpolation": interpolation},
                          "vector_scale": 0.75, "output": "Color",
                          "strength_output": "Alpha"})
    cases.append({"name": "image_png_noncolor", "node": "ShaderNodeTexImage",
                  "image": dict(FILES["png"], colorspace="Non-Color"),
                  "properties": {"interpolation": "Linear"}, "vector_scale": 0.75,
                  "output": "Color"})
    cases.append({"name": "image_exr_srgb", "node": "ShaderNodeTexImage",
                  "image": dict(FILES["exr"], colorspace="sRGB"),
                  "properties": {"interpolation": "Linear"}, "vector_scale": 0.75,
                  "output": "Color"})
    for blend in (0.0, 0.5, 1.0):
        for key in FILES:
            cases.append({"name": f"image_box_{int(blend * 10)}_{key}", "node": "ShaderNodeTexImage",
                          "image": FILES[key],
                          "properties": {"projection": "BOX", "projection_blend": blend,
                                         "interpolation": "Linear"},
                          "vector_scale": 0.75, "output": "Color"})
    cases.append({"name": "image_box_5_rotated", "node": "ShaderNodeTexImage",
                  "image": FILES["png"],
                  "properties": {"projection": "BOX", "projection_blend": 0.5},
                  "vector_scale": 0.75, "output": "Color", "object": TRANSFORM})
    for projection in ("SPHERE", "TUBE"):
        for extension in ("REPEAT", "CLIP"):
            cases.append({"name": f"image_{projection.lower()}_{extension.lower()}",
                          "node": "ShaderNodeTexImage", "image": FILES["png"],
                          "properties": {"projection": projection, "extension": extension,
                                         "interpolation": "Linear"},
                          "output": "Color"})
    cases.append({"name": "image_uv_default", "node": "ShaderNodeTexImage",
                  "image": FILES["png"], "properties": {"interpolation": "Linear"},
                  "vector": None, "output": "Color"})
    cases.append({"name": "image_uv_default_rotated", "node": "ShaderNodeTexImage",
                  "image": FILES["exr"], "properties": {"interpolation": "Closest"},
                  "vector": None, "output": "Color", "object": TRANSFORM})
    for generated in ("COLOR_GRID", "UV_GRID"):
        cases.append({"name": f"image_generated_{generated.lower()}",
                      "node": "ShaderNodeTexImage",
                      "image": {"generated": generated, "size": [16, 8]},
                      "properties": {"interpolation": "Closest"}, "vector_scale": 0.75,
                      "output": "Color"})
    # Environment Texture as a surface node: its vector (normalised, as Cycles does) is the
    # hit point's Object coordinate, a direction per pixel over a wide solid angle.
    for projection in ("EQUIRECTANGULAR", "MIRROR_BALL"):
        for interpolation in ("Closest", "Linear", "Cubic"):
            for key in FILES:
                cases.append({"name": f"environment_{projection.lower()}_"
                                      f"{interpolation.lower()}_{key}",
                              "node": "ShaderNodeTexEnvironment", "image": FILES[key],
                              "properties": {"projection": projection,
                                             "interpolation": interpolation},
                              "output": "Color"})
    return cases


def normal_map_cases():
    cases = []
    for space in ("TANGENT", "OBJECT", "WORLD", "BLENDER_OBJECT", "BLENDER_WORLD"):
        tag = space.lower()
        cases.append({"name": f"normal_map_{tag}_constant", "node": "ShaderNodeNormalMap",
                      "properties": {"space": space},
                      "inputs": {"Color": [0.65, 0.4, 0.85, 1.0], "Strength": 1.0},
                      "vector": None, "output": "Normal", "output_add": [1, 1, 1]})
        for strength in (0.5, 1.0, 2.0):
            cases.append({"name": f"normal_map_{tag}_linked_{int(strength * 10)}",
                          "node": "ShaderNodeNormalMap", "properties": {"space": space},
                          "inputs": {"Strength": strength}, "vector": "Color",
                          "output": "Normal", "output_add": [1, 1, 1]})
        cases.append({"name": f"normal_map_{tag}_transformed", "node": "ShaderNodeNormalMap",
                      "properties": {"space": space}, "inputs": {"Strength": 0.8},
                      "vector": "Color", "output": "Normal", "output_add": [1, 1, 1],
                      "object": TRANSFORM})
    cases.append({"name": "normal_map_tangent_named_uv", "node": "ShaderNodeNormalMap",
                  "properties": {"space": "TANGENT", "uv_map": "UVMap"},
                  "inputs": {"Strength": 1.0}, "vector": "Color", "output": "Normal",
                  "output_add": [1, 1, 1], "object": TRANSFORM})
    return cases


def object_info_cases():
    cases = []
    base = dict(TRANSFORM, pass_index=7, color=[0.8, 0.3, 0.15, 0.6])
    for output in ("Location", "Color", "Alpha", "Object Index", "Material Index", "Random"):
        cases.append({"name": f"object_info_{output.lower().replace(' ', '_')}",
                      "node": "ShaderNodeObjectInfo", "vector": None, "output": output,
                      "output_add": [1, 1, 1], "object": base,
                      "material": {"pass_index": 5}})
    for k, name in enumerate(("plane", "Cube.001", "Würfel", "立方体", "a", "Object with spaces")):
        cases.append({"name": f"object_info_random_{k}", "node": "ShaderNodeObjectInfo",
                      "vector": None, "output": "Random", "object": dict(base, name=name)})
    return cases


def camera_cases():
    cases = []
    for output in ("Window", "Camera"):
        for k, transform in enumerate((None, TRANSFORM)):
            case = {"name": f"texcoord_{output.lower()}" + ("_transformed" if k else ""),
                    "node": "ShaderNodeTexCoord", "vector": None, "output": output,
                    "output_add": [1, 1, 1]}
            if transform:
                case["object"] = transform
            cases.append(case)
    for output in ("View Vector", "View Z Depth", "View Distance"):
        for k, transform in enumerate((None, TRANSFORM)):
            case = {"name": "camera_data_" + output.lower().replace(" ", "_")
                            + ("_transformed" if k else ""),
                    "node": "ShaderNodeCameraData", "vector": None, "output": output,
                    "output_add": [1, 1, 1]}
            if transform:
                case["object"] = transform
            cases.append(case)
    return cases


def main():
    for name, cases in (("image", image_cases()), ("normal_map", normal_map_cases()),
                        ("object_info", object_info_cases()), ("camera_coords", camera_cases())):
        (HERE / f"{name}.json").write_text(json.dumps({"cases": cases}, indent=1,
                                                      ensure_ascii=False) + "\n")
        print(name, len(cases))


if __name__ == "__main__":
    main()
