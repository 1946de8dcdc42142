"""Writes the manifests of the shader-node features that Blender 4.x added, checked against
Cycles 4.x only ("min_blender"): noise_fractal.json (the Noise Texture's fractal types, which
replaced the Musgrave Texture in 4.1, with Lacunarity and Normalize), voronoi_fractal.json (the
Voronoi Texture's Detail, Roughness, Lacunarity and Normalize of 4.0) and nodes_4x.json (new
operations and blend modes, and the Wave Texture's unclamped detail roughness), gabor.json (the
Gabor Texture of 4.3).

  python3 test_scenes/nodes/make_fractal_manifests.py
  blender -b --factory-startup --python tools/node_refs.py -- \\
      test_scenes/nodes/noise_fractal.json test_scenes/nodes/noise_fractal/blender-4.3

The hit point's Object coordinate spans x, y in [-1, 1], z in [-0.25, 0.75].
"""

import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
TYPES = ['FBM', 'MULTIFRACTAL', 'HYBRID_MULTIFRACTAL', 'RIDGED_MULTIFRACTAL', 'HETERO_TERRAIN']


def used_inputs(kind, inputs):
    """The inputs a fractal type shows (Blender hides Offset and Gain where they do nothing)."""
    unused = {'FBM': ("Offset", "Gain"), 'MULTIFRACTAL': ("Offset", "Gain"),
              'HETERO_TERRAIN': ("Gain",)}.get(kind, ())
    return {k: v for k, v in inputs.items() if k not in unused}


def noise_cases():
    cases = []
    base = {"Scale": 3.0, "Detail": 2.5, "Roughness": 0.6, "Lacunarity": 2.2, "Offset": 0.3,
            "Gain": 1.5, "Distortion": 0.0}
    for dims in ('1D', '2D', '3D', '4D'):
        for kind in TYPES:
            inputs = dict(base)
            if dims == '4D':
                inputs["W"] = 0.4
            if kind in ('MULTIFRACTAL',):
                inputs["Roughness"] = 0.4
            cases.append({"name": f"noise_{dims.lower()}_{kind.lower()}",
                          "node": "ShaderNodeTexNoise",
                          "properties": {"noise_dimensions": dims, "noise_type": kind},
                          "inputs": used_inputs(kind, inputs),
                          "vector": "W" if dims == '1D' else "Vector",
                          "output": "Fac", "output_add": [0.5, 0.5, 0.5]})
    # fBM specifics: unnormalised, roughness above 1, a whole detail, lacunarity, colour, distortion.
    extra = [
        ("fbm_3d_raw", '3D', 'FBM', {"normalize": False}, {}, "Fac"),
        ("fbm_2d_raw_color", '2D', 'FBM', {"normalize": False}, {}, "Color"),
        ("fbm_3d_rough_above_1", '3D', 'FBM', {}, {"Roughness": 1.4, "Detail": 3.0}, "Fac"),
        ("fbm_3d_lacunarity", '3D', 'FBM', {}, {"Lacunarity": 3.5, "Detail": 4.3}, "Fac"),
        ("fbm_3d_detail0", '3D', 'FBM', {}, {"Detail": 0.0}, "Fac"),
        ("fbm_3d_color_distort", '3D', 'FBM', {}, {"Distortion": 0.8}, "Color"),
        ("fbm_4d_color", '4D', 'FBM', {}, {"W": 1.3}, "Color"),
        ("fbm_1d_color_distort", '1D', 'FBM', {}, {"Distortion": 0.6}, "Color"),
        ("ridged_3d_color", '3D', 'RIDGED_MULTIFRACTAL', {}, {"Offset": 1.0, "Gain": 2.0},
         "Color"),
        ("hybrid_3d_detail_high", '3D', 'HYBRID_MULTIFRACTAL', {},
         {"Detail": 7.6, "Offset": 0.7, "Gain": 1.1}, "Fac"),
        ("hetero_2d_color_distort", '2D', 'HETERO_TERRAIN', {},
         {"Distortion": 0.5, "Offset": 0.6}, "Color"),
        ("multifractal_3d_whole", '3D', 'MULTIFRACTAL', {}, {"Detail": 3.0, "Roughness": 0.3},
         "Fac"),
    ]
    for name, dims, kind, props, inputs, output in extra:
        merged = dict(base)
        merged.update(inputs)
        properties = {"noise_dimensions": dims, "noise_type": kind}
        properties.update(props)
        case = {"name": f"noise_{name}", "node": "ShaderNodeTexNoise", "properties": properties,
                "inputs": used_inputs(kind, merged), "vector": "W" if dims == '1D' else "Vector",
                "output": output}
        if kind != 'FBM' or props.get("normalize") is False:
            case["output_add"] = [0.5, 0.5, 0.5]
        cases.append(case)
    return cases


def voronoi_cases():
    cases = []
    base = {"Scale": 3.0, "Detail": 2.5, "Roughness": 0.55, "Lacunarity": 2.3,
            "Randomness": 0.9, "Smoothness": 0.6, "Exponent": 1.5}
    for dims in ('1D', '2D', '3D', '4D'):
        for feature in ('F1', 'F2', 'SMOOTH_F1', 'DISTANCE_TO_EDGE'):
            for normalize in (False, True):
                outputs = ["Distance"] if feature == 'DISTANCE_TO_EDGE' else \
                    ["Distance", "Color", "W" if dims == '1D' else "Position"]
                if normalize:
                    outputs = ["Distance"] if feature == 'DISTANCE_TO_EDGE' else \
                        ["Distance", "Color"]
                for output in outputs:
                    inputs = dict(base)
                    if dims == '4D':
                        inputs["W"] = 0.35
                    name = (f"voronoi_{dims.lower()}_{feature.lower()}"
                            f"{'_norm' if normalize else ''}_{output.lower()}")
                    cases.append({"name": name, "node": "ShaderNodeTexVoronoi",
                                  "properties": {"voronoi_dimensions": dims,
                                                 "feature": feature, "normalize": normalize},
                                  "inputs": inputs,
                                  "vector": "W" if dims == '1D' else "Vector",
                                  "output": output})
    extra = [
        ("3d_f1_manhattan_norm", '3D', 'F1', 'MANHATTAN', True, {}, "Distance"),
        ("2d_f2_chebychev_norm", '2D', 'F2', 'CHEBYCHEV', True, {}, "Distance"),
        ("3d_f1_minkowski_norm", '3D', 'F1', 'MINKOWSKI', True, {}, "Distance"),
        ("3d_f1_detail0", '3D', 'F1', 'EUCLIDEAN', False, {"Detail": 0.0}, "Distance"),
        ("3d_f1_rough0", '3D', 'F1', 'EUCLIDEAN', True, {"Roughness": 0.0}, "Color"),
        ("3d_f1_whole_detail", '3D', 'F1', 'EUCLIDEAN', True, {"Detail": 3.0}, "Distance"),
        ("3d_smooth_zero", '3D', 'SMOOTH_F1', 'EUCLIDEAN', False, {"Smoothness": 0.0},
         "Distance"),
        ("2d_edge_detail_high", '2D', 'DISTANCE_TO_EDGE', 'EUCLIDEAN', True,
         {"Detail": 6.4, "Roughness": 0.8}, "Distance"),
        ("3d_radius", '3D', 'N_SPHERE_RADIUS', 'EUCLIDEAN', False, {}, "Radius"),
    ]
    for name, dims, feature, metric, normalize, inputs, output in extra:
        merged = dict(base)
        merged.update(inputs)
        cases.append({"name": f"voronoi_{name}", "node": "ShaderNodeTexVoronoi",
                      "properties": {"voronoi_dimensions": dims, "feature": feature,
                                     "distance": metric, "normalize": normalize},
                      "inputs": merged, "vector": "Vector", "output": output})
    return cases


def misc_cases():
    cases = []
    for a_scale in (1.0,):
        cases.append({"name": "math_floored_modulo", "node": "ShaderNodeMath",
                      "properties": {"operation": 'FLOORED_MODULO'},
                      "inputs": {"#1": 0.23}, "vector": "#0", "vector_scale": 2.0,
                      "output": "#0", "output_add": [0.5, 0.5, 0.5]})
        cases.append({"name": "math_floored_modulo_negative_b", "node": "ShaderNodeMath",
                      "properties": {"operation": 'FLOORED_MODULO'},
                      "inputs": {"#1": -0.3}, "vector": "#0", "vector_scale": 2.0,
                      "output": "#0", "output_add": [0.5, 0.5, 0.5]})
    cases.append({"name": "mix_color_exclusion", "node": "ShaderNodeMix",
                  "properties": {"data_type": 'RGBA', "blend_type": 'EXCLUSION'},
                  "inputs": {"Factor": 0.7, "B": [0.8, 0.35, 0.05, 1.0]}, "vector": "A",
                  "output": "Result"})
    cases.append({"name": "mix_color_exclusion_clamp", "node": "ShaderNodeMix",
                  "properties": {"data_type": 'RGBA', "blend_type": 'EXCLUSION',
                                 "clamp_result": True},
                  "inputs": {"Factor": 1.0, "B": [0.8, 0.35, 0.05, 1.0]}, "vector": "A",
                  "vector_scale": 2.0, "output": "Result"})
    cases.append({"name": "mixrgb_exclusion", "node": "ShaderNodeMixRGB",
                  "properties": {"blend_type": 'EXCLUSION'},
                  "inputs": {"Fac": 0.6, "Color2": [0.8, 0.35, 0.05, 1.0]},
                  "vector": "Color1", "output": "Color"})
    cases.append({"name": "wave_rough_above_1", "node": "ShaderNodeTexWave",
                  "inputs": {"Scale": 2.0, "Distortion": 4.0, "Detail": 3.0,
                             "Detail Scale": 1.5, "Detail Roughness": 1.6},
                  "vector": "Vector", "output": "Fac"})
    cases.append({"name": "wave_detail_fraction", "node": "ShaderNodeTexWave",
                  "inputs": {"Scale": 2.0, "Distortion": 3.0, "Detail": 2.4,
                             "Detail Scale": 1.5, "Detail Roughness": 0.7},
                  "vector": "Vector", "output": "Fac"})
    return cases


def gabor_cases():
    cases = []
    for dims in ('2D', '3D'):
        for output in ('Value', 'Phase', 'Intensity'):
            cases.append({"name": f"gabor_{dims.lower()}_{output.lower()}",
                          "node": "ShaderNodeTexGabor", "properties": {"gabor_type": dims},
                          "inputs": {"Scale": 3.0, "Frequency": 2.5, "Anisotropy": 0.6},
                          "vector": "Vector", "output": output})
    cases.append({"name": "gabor_2d_anisotropic", "node": "ShaderNodeTexGabor",
                  "properties": {"gabor_type": '2D'},
                  "inputs": {"Scale": 2.0, "Frequency": 3.0, "Anisotropy": 1.0,
                             "Orientation 2D": 0.3}, "vector": "Vector", "output": "Value"})
    cases.append({"name": "gabor_3d_orientation", "node": "ShaderNodeTexGabor",
                  "properties": {"gabor_type": '3D'},
                  "inputs": {"Scale": 2.0, "Frequency": 1.5, "Anisotropy": 0.8,
                             "Orientation 3D": [0.2, -0.5, 0.8]},
                  "vector": "Vector", "output": "Value"})
    cases.append({"name": "gabor_2d_isotropic_intensity", "node": "ShaderNodeTexGabor",
                  "properties": {"gabor_type": '2D'},
                  "inputs": {"Scale": 4.0, "Frequency": 1.0, "Anisotropy": 0.0},
                  "vector": "Vector", "output": "Intensity"})
    return cases


def main():
    for name, cases, version in (("gabor", gabor_cases(), [4, 3]),
                                 ("noise_fractal", noise_cases(), [4, 1]),
                                 ("voronoi_fractal", voronoi_cases(), [4, 0]),
                                 ("nodes_4x", misc_cases(), [4, 0])):
        path = os.path.join(HERE, name + ".json")
        with open(path, "w") as f:
            json.dump({"min_blender": version, "cases": cases}, f, indent=1)
            f.write("\n")
        print(f"{path}: {len(cases)} cases")


if __name__ == "__main__":
    main()
