"""Holdout and shadow-catcher scenes, rendered with Photon (and optionally Cycles), measured in
regions found by projecting the scene's geometry into the image.

Args: OUT_DIR CASE [ENGINES] [PHOTON_INTEGRATOR]
  CASE:
    holdout_node        a sphere whose material is a Holdout node, in front of a lit wall
    holdout_mix         the same sphere with Mix(0.5, Diffuse, Holdout)
    holdout_object      a diffuse sphere with Object > Visibility > Holdout (is_holdout)
    holdout_collection  a diffuse sphere in a collection marked Holdout in the view layer
    catcher             a sphere over a floor that is a shadow catcher, lit by a sun
  A suffix "_opaque" renders without Film > Transparent (default: transparent film).
  ENGINES: comma-separated subset of photon,cycles (default photon).
Reports, per engine, the mean RGB and alpha of each region (x0, y0, x1, y1 in pixels, y down).
"""

import math
import os

import bpy
import numpy as np
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

import builders
import harness

WIDTH, HEIGHT = 80, 60
SPHERE_RADIUS = 0.5
SUN_DIRECTION = Vector((0.5, 0.3, -1.0)).normalized()  # direction the sunlight travels


def _pixel(scene, camera, point):
    """(x, y) pixel coordinates of a world point, y down."""
    bpy.context.view_layer.update()  # matrix_world of objects moved since the last update
    v = world_to_camera_view(scene, camera, Vector(point))
    return v.x * WIDTH, (1.0 - v.y) * HEIGHT


def _disc(scene, camera, center, radius, scale):
    """Box of the pixels within `scale` times the projected radius of a sphere."""
    cx, cy = _pixel(scene, camera, center)
    edge_x, _ = _pixel(scene, camera, Vector(center) + camera.matrix_world.to_3x3() @
                       Vector((radius, 0.0, 0.0)))
    r = abs(edge_x - cx) * scale
    return cx, cy, r


def _common(scene, transparent):
    scene.render.film_transparent = transparent
    scene.photon.samples = 32
    scene.photon.seed = 0
    scene.photon.photons = 20000
    scene.photon.caustic_photons = 0
    scene.photon.final_gather_rays = 8
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 64
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.seed = 1


def build_holdout(variant, transparent):
    scene = builders.reset_scene(width=WIDTH, height=HEIGHT)
    _common(scene, transparent)
    white = builders.diffuse_material("White", (0.8, 0.8, 0.8))
    builders.quad("Wall", (-4, 1, -3), (8, 0, 0), (0, 0, 6), white)
    if variant == "node":
        material = builders.shader_material("Hole", "ShaderNodeHoldout")
    elif variant == "mix":
        material = bpy.data.materials.new("HalfHole")
        material.use_nodes = True
        nodes, links = material.node_tree.nodes, material.node_tree.links
        nodes.remove(nodes["Principled BSDF"])
        mix = nodes.new("ShaderNodeMixShader")
        mix.inputs["Fac"].default_value = 0.5
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (0.8, 0.2, 0.2, 1.0)
        holdout = nodes.new("ShaderNodeHoldout")
        links.new(diffuse.outputs[0], mix.inputs[1])
        links.new(holdout.outputs[0], mix.inputs[2])
        links.new(mix.outputs[0], nodes["Material Output"].inputs["Surface"])
    else:
        material = builders.diffuse_material("Red", (0.8, 0.2, 0.2))
    center = (0.0, 0.0, 0.0)
    sphere = builders.uv_sphere("Sphere", center, SPHERE_RADIUS, material=material)
    if variant == "object":
        sphere.is_holdout = True
    elif variant == "collection":
        collection = bpy.data.collections.new("Holdouts")
        scene.collection.children.link(collection)
        scene.collection.objects.unlink(sphere)
        collection.objects.link(sphere)
        layer = bpy.context.view_layer.layer_collection.children["Holdouts"]
        layer.holdout = True
    builders.light("Lamp", 'AREA', 300.0, (0.0, -3.0, 2.0), size=2.0)
    builders.aim(bpy.data.objects["Lamp"], (0.0, 1.0, 0.0))
    camera = builders.camera(location=(0.0, -4.0, 0.0))
    builders.aim(camera, (0.0, 0.0, 0.0))
    cx, cy, r = _disc(scene, camera, center, SPHERE_RADIUS, 1.0)
    inner = r * 0.6
    regions = {
        "sphere": (cx - inner, cy - inner, cx + inner, cy + inner),
        # The wall to either side of the sphere, well clear of its rim.
        "wall_left": (cx - 2.4 * r, cy - 0.5 * r, cx - 1.4 * r, cy + 0.5 * r),
        "wall_right": (cx + 1.4 * r, cy - 0.5 * r, cx + 2.4 * r, cy + 0.5 * r),
    }
    return scene, regions


def build_catcher(transparent):
    scene = builders.reset_scene(width=WIDTH, height=HEIGHT)
    _common(scene, transparent)
    # A blue-grey world behind the catcher, so the opaque-film image shows it (and its shadow).
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.2, 0.3, 0.5, 1)
    scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.3
    grey = builders.diffuse_material("Grey", (0.8, 0.8, 0.8))
    floor = builders.quad("Floor", (-20, -20, 0), (40, 0, 0), (0, 40, 0), grey)
    floor.is_shadow_catcher = True
    red = builders.diffuse_material("Red", (0.8, 0.2, 0.2))
    center = Vector((0.0, 0.0, 0.7))
    builders.uv_sphere("Sphere", tuple(center), SPHERE_RADIUS, material=red)
    sun = builders.light("Sun", 'SUN', 3.0, (0.0, 0.0, 5.0), angle=math.radians(2.0))
    sun.rotation_euler = SUN_DIRECTION.to_track_quat('-Z', 'Y').to_euler()
    camera = builders.camera(location=(0.0, -6.0, 3.5))
    builders.aim(camera, (0.4, 0.4, 0.2))
    cx, cy, r = _disc(scene, camera, center, SPHERE_RADIUS, 1.0)
    inner = r * 0.5
    # The sphere's shadow is its centre projected along the sunlight onto the floor.
    t = -center.z / SUN_DIRECTION.z
    shadow_center = center + SUN_DIRECTION * t
    sx, sy = _pixel(scene, camera, shadow_center)
    sh = r * 0.25
    # Floor well away from the shadow and the sphere: to the left, towards the camera.
    ax, ay = _pixel(scene, camera, (-1.4, -0.6, 0.0))
    regions = {
        "sphere": (cx - inner, cy - inner, cx + inner, cy + inner),
        "shadow": (sx - sh, sy - sh, sx + sh, sy + sh),
        "away": (ax - 3, ay - 3, ax + 3, ay + 3),
    }
    return scene, regions


def region_stats(pixels, box):
    x0, y0, x1, y1 = (int(round(v)) for v in box)
    x0, y0 = max(x0, 0), max(y0, 0)
    x1, y1 = min(max(x1, x0 + 1), WIDTH), min(max(y1, y0 + 1), HEIGHT)
    patch = pixels[y0:y1, x0:x1]
    return {"box": [x0, y0, x1, y1], "rgb": [float(patch[:, :, c].mean()) for c in range(3)],
            "alpha": float(patch[:, :, 3].mean())}


def render(scene, engine, out_dir, name):
    scene.render.engine = engine
    path = os.path.join(out_dir, f"{name}_{engine.lower()}.exr")
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    return path, harness.read_image(path)


def main(out_dir, case, engines="photon", integrator="PHOTON_MAP"):
    os.makedirs(out_dir, exist_ok=True)
    transparent = not case.endswith("_opaque")
    base = case[:-len("_opaque")] if not transparent else case
    if base.startswith("holdout_"):
        scene, regions = build_holdout(base[len("holdout_"):], transparent)
    elif base == "catcher":
        scene, regions = build_catcher(transparent)
    else:
        raise ValueError(f"unknown case {case}")
    scene.photon.integrator = integrator
    result = {}
    for engine in engines.split(","):
        path, pixels = render(scene, engine.upper(), out_dir, f"{case}_{integrator.lower()}")
        stats = {name: region_stats(pixels, box) for name, box in regions.items()}
        stats["path"] = path
        stats["finite"] = bool(np.isfinite(pixels).all())
        result[engine] = stats
    return result


if __name__ == "__main__":
    harness.run(main)
