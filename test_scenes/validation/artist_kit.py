"""Shared pieces of the artist-style validation scenes (test_scenes/validation/<name>/
make_<name>.py): settings, primitives made with Blender's own operators (so they carry the UV
maps and normals an artist's mesh has), node helpers, saving, and the sidecar's image regions.

Each generator is run headless:
    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \\
        -P test_scenes/validation/<name>/make_<name>.py
and writes test_scenes/validation/<scene>.blend and <scene>.json (the suite only looks at the
top of test_scenes/validation); the Cycles reference comes from
    python3 tools/regress.py test_scenes/validation --update --only <scene> --threads 2 ...
"""

import json
import math
import os
import sys

import bpy

VALIDATION = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(VALIDATION))
import builders  # noqa: E402
import library  # noqa: E402

# Image regions the sidecar lists and tests/blender/test_validation_artist_scenes.py checks
# (each tile's mean colour within 5% of Cycles'): a GRID x GRID grid of equal tiles.
GRID = 4


def base_scene(width=128, height=128, samples=64, seed=1):
    """An empty scene (black world) with the suite's pinned output and Photon settings."""
    scene = library.pin_settings(builders.reset_scene(width=width, height=height), samples, seed)
    return scene


def smooth(obj):
    for poly in obj.data.polygons:
        poly.use_smooth = True
    return obj


def uv_sphere(name, location, radius, material, segments=64, rings=32):
    """Blender's UV Sphere (with its UV map), smooth shaded."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=radius,
                                         location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(material)
    return smooth(obj)


def cube(name, location, size, material, rotation=(0.0, 0.0, 0.0)):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(material)
    return obj


def monkey(name, location, material, rotation=(0.0, 0.0, 0.0), subdivisions=2):
    """Suzanne, smooth shaded, with a Subdivision Surface modifier as artists render her."""
    bpy.ops.mesh.primitive_monkey_add(size=1.0, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(material)
    subsurf = obj.modifiers.new("Subdivision", 'SUBSURF')
    subsurf.levels = subsurf.render_levels = subdivisions
    return smooth(obj)


def floor(material, size=20.0, uv_repeat=1.0):
    """A size x size plane at z = 0 with a UV map spanning [0, uv_repeat]^2."""
    plane = builders.quad("Floor", (-size / 2, -size / 2, 0), (size, 0, 0), (0, size, 0),
                          material)
    r = uv_repeat
    plane.data.uv_layers.new(name="UVMap").data.foreach_set("uv", [0, 0, r, 0, r, r, 0, r])
    return plane


def principled(name, **inputs):
    """A node material with its default Principled BSDF; returns (material, nodes, links, bsdf)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes["Principled BSDF"]
    for key, value in inputs.items():
        bsdf.inputs[key].default_value = value
    return mat, nodes, links, bsdf


def color_ramp(nodes, stops, interpolation='LINEAR'):
    """A ColorRamp node with stops [(position, (r, g, b)), ...]."""
    ramp = nodes.new("ShaderNodeValToRGB")
    elements = ramp.color_ramp.elements
    ramp.color_ramp.interpolation = interpolation
    while len(elements) < len(stops):
        elements.new(0.5)
    for element, (position, color) in zip(elements, stops):
        element.position = position
        element.color = (*color, 1.0)
    return ramp


def camera_at(location, target, lens=50.0):
    cam = builders.camera(location=location, lens=lens)
    builders.aim(cam, target)
    return cam


def grid_regions(scene, grid=GRID):
    """{"tile_R_C": [x0, y0, x1, y1]} pixel rectangles (y down) tiling the image."""
    width, height = scene.render.resolution_x, scene.render.resolution_y
    regions = {}
    for row in range(grid):
        for col in range(grid):
            regions[f"tile_{row}_{col}"] = [col * width // grid, row * height // grid,
                                            (col + 1) * width // grid, (row + 1) * height // grid]
    return regions


def sidecar(scene, reference_samples, description, timeout=120):
    """The suite's thresholds for these scenes: the image mean within 2% of Cycles' (regress.py)
    and each region's mean colour within 5% (the Blender test); rel_rmse and the per-pixel
    fraction bound gross local errors that region means would average away."""
    return {
        "reference_engine": "CYCLES", "reference_samples": reference_samples,
        "timeout": timeout,
        "thresholds": {"mean_diff": 0.02, "rel_rmse": 0.1, "mean_rel": 0.08,
                       "pixel_threshold": 0.25, "pixel_fraction": 0.03, "alpha_max": 0.001},
        "regions": grid_regions(scene),
        "description": description,
    }


def save(scene, name, sidecar_data):
    """Writes test_scenes/validation/NAME.blend (paths relative) and NAME.json."""
    scene.name = "Scene"
    path = os.path.join(VALIDATION, f"{name}.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True, relative_remap=True)
    bpy.ops.file.make_paths_relative()
    bpy.ops.wm.save_mainfile(compress=True)
    if os.path.exists(path + "1"):
        os.remove(path + "1")
    with open(os.path.join(VALIDATION, f"{name}.json"), "w") as f:
        json.dump(sidecar_data, f, indent=2)
        f.write("\n")
    print(f"artist_kit: wrote {path}", flush=True)


def radians(*degrees):
    return tuple(math.radians(d) for d in degrees)
