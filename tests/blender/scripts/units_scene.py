"""Renders one light type over a diffuse plane with Photon and with Cycles (direct light only)
and reports both images' mean RGB.  Args: LIGHT_CASE OUT_DIR"""

import math
import os

import bpy

import builders
import harness

LIGHTS = {
    "point": ('POINT', 100.0, (0.3, 0.2, 2.0), (0, 0, 0), {"shadow_soft_size": 0.0}),
    "point_radius": ('POINT', 100.0, (0.0, 0.0, 1.5), (0, 0, 0), {"shadow_soft_size": 0.5}),
    "spot": ('SPOT', 200.0, (0.0, 0.0, 2.0), (0, 0, 0),
             {"spot_size": math.radians(70), "spot_blend": 0.4, "shadow_soft_size": 0.1}),
    "sun": ('SUN', 3.0, (0, 0, 5), (math.radians(30), 0, 0), {"angle": math.radians(5)}),
    "area_square": ('AREA', 100.0, (0.0, 0.0, 1.2), (0, 0, 0), {"shape": 'SQUARE', "size": 1.0}),
    "area_rectangle": ('AREA', 100.0, (0.2, 0.0, 1.0), (math.radians(25), 0, 0),
                       {"shape": 'RECTANGLE', "size": 1.5, "size_y": 0.5}),
    "area_disk": ('AREA', 100.0, (0.0, 0.0, 1.2), (0, 0, 0), {"shape": 'DISK', "size": 1.0}),
    "area_ellipse": ('AREA', 100.0, (0.0, -0.3, 1.0), (0, math.radians(20), 0),
                     {"shape": 'ELLIPSE', "size": 1.2, "size_y": 0.6}),
    # Blender 5.0+: Exposure, Temperature and Normalize (off: strength per unit area).
    "point_unnormalized": ('POINT', 400.0, (0.2, 0.0, 1.5), (0, 0, 0),
                           {"shadow_soft_size": 0.3, "normalize": False, "exposure": -1.5}),
    "spot_temperature": ('SPOT', 150.0, (0.0, 0.3, 2.0), (math.radians(15), 0, 0),
                         {"spot_size": math.radians(100), "spot_blend": 0.2,
                          "use_temperature": True, "temperature": 3200.0, "exposure": 0.5}),
    "sun_unnormalized": ('SUN', 400.0, (0, 0, 5), (0, math.radians(20), 0),
                         {"angle": math.radians(6), "normalize": False}),
    "area_unnormalized": ('AREA', 60.0, (0.0, 0.0, 1.2), (0, 0, 0),
                          {"shape": 'ELLIPSE', "size": 1.0, "size_y": 0.7, "normalize": False,
                           "use_temperature": True, "temperature": 9000.0}),
}


def render_mean(scene, path):
    scene.render.filepath = path
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    pixels = harness.read_image(path)
    return [float(pixels[:, :, c].mean()) for c in range(3)]


def main(case, out_dir):
    light_type, energy, location, rotation, settings = LIGHTS[case]
    missing = [key for key in settings if key not in bpy.types.Light.bl_rna.properties
               and key not in getattr(bpy.types, light_type.title() + "Light").bl_rna.properties]
    if missing:
        return {"skipped": f"Blender {bpy.app.version_string} has no light {', '.join(missing)}"}
    scene = builders.reset_scene(width=48, height=48)
    plane_mat = builders.diffuse_material("Plane", (0.8, 0.6, 0.4))
    builders.quad("Plane", (-10, -10, 0), (20, 0, 0), (0, 20, 0), plane_mat)
    cam = builders.camera(location=(0, 0, 5), rotation=(0, 0, 0))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = 5.0
    light = builders.light("Light", light_type, energy, location, rotation, **settings)
    light.data.color = (1.0, 0.9, 0.8)

    scene.photon.samples = 256
    photon = render_mean(scene, os.path.join(out_dir, f"units_{case}_photon.exr"))

    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 512
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0
    scene.cycles.seed = 1
    cycles = render_mean(scene, os.path.join(out_dir, f"units_{case}_cycles.exr"))
    return {"photon": photon, "cycles": cycles}


harness.run(main)
