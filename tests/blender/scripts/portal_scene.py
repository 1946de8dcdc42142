"""A closed room lit by a uniform sky through one window, with an area light marked as a portal
in the window, rendered to EXR in the folder given: by Cycles with the portal (direct light
only, and all of it), and by Photon's ray tracing (direct light only) and photon map, with the
portal and without it (the light removed). Args: out_dir, photon_samples, cycles_samples.
Returns {name: path} for cycles_direct, cycles, photon_direct, photon, photon_direct_no_portal,
photon_no_portal, and "version"."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
from harness import run  # noqa: E402
from principled_extras import clear, render  # noqa: E402

# The room [-1, 1]^2 x [0, 2] and its window in the wall x = 1: y in [-0.4, 0.4], z in
# [0.7, 1.3].
ROOM_QUADS = [
    [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],            # floor
    [(-1, -1, 2), (-1, 1, 2), (1, 1, 2), (1, -1, 2)],            # ceiling
    [(-1, -1, 0), (-1, 1, 0), (-1, 1, 2), (-1, -1, 2)],          # x = -1
    [(-1, -1, 0), (-1, -1, 2), (1, -1, 2), (1, -1, 0)],          # y = -1
    [(-1, 1, 0), (1, 1, 0), (1, 1, 2), (-1, 1, 2)],              # y = 1
    [(1, -1, 0), (1, -1, 0.7), (1, 1, 0.7), (1, 1, 0)],          # x = 1 below the window
    [(1, -1, 1.3), (1, -1, 2), (1, 1, 2), (1, 1, 1.3)],          # above it
    [(1, -1, 0.7), (1, -1, 1.3), (1, -0.4, 1.3), (1, -0.4, 0.7)],  # beside it
    [(1, 0.4, 0.7), (1, 0.4, 1.3), (1, 1, 1.3), (1, 1, 0.7)],
]


# Walls 0.1 thick, as a building's: the outside faces (the room's grown by 0.1, facing out) and
# the window's reveal. With walls of no thickness a photon map lets the sky's photons on the
# outside face leak into the lookups of the inside one (measured: the room 7% above Cycles).
T = 0.1
OUTSIDE_QUADS = [
    [(-1 - T, -1 - T, -T), (-1 - T, 1 + T, -T), (1 + T, 1 + T, -T), (1 + T, -1 - T, -T)],
    [(-1 - T, -1 - T, 2 + T), (1 + T, -1 - T, 2 + T), (1 + T, 1 + T, 2 + T),
     (-1 - T, 1 + T, 2 + T)],
    [(-1 - T, -1 - T, -T), (-1 - T, -1 - T, 2 + T), (-1 - T, 1 + T, 2 + T),
     (-1 - T, 1 + T, -T)],
    [(-1 - T, -1 - T, -T), (1 + T, -1 - T, -T), (1 + T, -1 - T, 2 + T),
     (-1 - T, -1 - T, 2 + T)],
    [(-1 - T, 1 + T, -T), (-1 - T, 1 + T, 2 + T), (1 + T, 1 + T, 2 + T),
     (1 + T, 1 + T, -T)],
    [(1 + T, -1 - T, -T), (1 + T, 1 + T, -T), (1 + T, 1 + T, 0.7), (1 + T, -1 - T, 0.7)],
    [(1 + T, -1 - T, 1.3), (1 + T, 1 + T, 1.3), (1 + T, 1 + T, 2 + T), (1 + T, -1 - T, 2 + T)],
    [(1 + T, -1 - T, 0.7), (1 + T, -0.4, 0.7), (1 + T, -0.4, 1.3), (1 + T, -1 - T, 1.3)],
    [(1 + T, 0.4, 0.7), (1 + T, 1 + T, 0.7), (1 + T, 1 + T, 1.3), (1 + T, 0.4, 1.3)],
    # the reveal: sill, lintel and jambs
    [(1, -0.4, 0.7), (1 + T, -0.4, 0.7), (1 + T, 0.4, 0.7), (1, 0.4, 0.7)],
    [(1, -0.4, 1.3), (1, 0.4, 1.3), (1 + T, 0.4, 1.3), (1 + T, -0.4, 1.3)],
    [(1, -0.4, 0.7), (1, -0.4, 1.3), (1 + T, -0.4, 1.3), (1 + T, -0.4, 0.7)],
    [(1, 0.4, 0.7), (1 + T, 0.4, 0.7), (1 + T, 0.4, 1.3), (1, 0.4, 1.3)],
]


def room():
    verts, faces = [], []
    for quad in ROOM_QUADS + OUTSIDE_QUADS:
        faces.append([len(verts) + i for i in range(4)])
        verts.extend(quad)
    mesh = bpy.data.meshes.new("room")
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new("room", mesh)
    bpy.context.scene.collection.objects.link(obj)
    material = bpy.data.materials.new("walls")
    material.use_nodes = True
    bsdf = next(n for n in material.node_tree.nodes if n.type == 'BSDF_PRINCIPLED')
    bsdf.inputs["Base Color"].default_value = (0.7, 0.7, 0.7, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    for name in ("Specular", "Specular IOR Level"):
        if name in bsdf.inputs:
            bsdf.inputs[name].default_value = 0.0
    mesh.materials.append(material)


def portal():
    data = bpy.data.lights.new("window", 'AREA')
    data.shape = 'RECTANGLE'
    data.size = 0.6    # along the light's X: vertical once turned
    data.size_y = 0.8  # along its Y: the window's width
    data.energy = 1000.0  # a portal emits nothing whatever its power
    data.cycles.is_portal = True
    obj = bpy.data.objects.new("window", data)
    obj.location = (1.0 + T, 0.0, 1.0)  # in the window's outer face
    obj.rotation_euler = (0.0, math.pi / 2, 0.0)  # its -Z, where the light goes, along -x
    bpy.context.scene.collection.objects.link(obj)
    return obj


def main(out_dir, photon_samples, cycles_samples):
    clear()
    scene = bpy.context.scene
    scene.render.resolution_x = scene.render.resolution_y = 64
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.view_settings.view_transform = 'Standard'
    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.6, 0.75, 1.0, 1.0)
    background.inputs["Strength"].default_value = 3.0
    scene.world = world
    room()
    window = portal()
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.lens = 18.0
    camera.location = (-0.9, -0.6, 1.5)
    camera.rotation_euler = (math.radians(70.0), 0.0, math.radians(-72.0))  # at the window
    scene.collection.objects.link(camera)
    scene.camera = camera

    # Cycles with the portal: direct light only, and every bounce (light bounces many times in
    # a closed pale room: Cycles' default of 4 diffuse bounces left it 14% darker than 64 do).
    scene.render.engine = 'CYCLES'
    scene.cycles.samples = int(cycles_samples)
    scene.cycles.use_denoising = False
    scene.cycles.sample_clamp_indirect = 0.0
    scene.cycles.pixel_filter_type = 'BOX'
    scene.cycles.seed = 1
    paths = {}
    for name, bounces in (("cycles_direct", 0), ("cycles", 64)):
        scene.cycles.max_bounces = scene.cycles.diffuse_bounces = bounces
        paths[name] = os.path.join(out_dir, f"portal_{name}.exr")
        render(scene, paths[name])
    # Photon: direct light only (RAY_TRACE: the room is all diffuse) and the photon map, with
    # the portal and without it.
    scene.render.engine = 'PHOTON'
    scene.photon.samples = int(photon_samples)
    scene.photon.max_depth = 64
    scene.photon.seed = 1
    for suffix in ("", "_no_portal"):
        if suffix:
            bpy.data.objects.remove(window)
        for name, integrator in (("photon_direct", 'RAY_TRACE'), ("photon", 'PHOTON_MAP')):
            scene.photon.integrator = integrator
            paths[name + suffix] = os.path.join(out_dir, f"portal_{name}{suffix}.exr")
            render(scene, paths[name + suffix])
    return dict(paths, version=list(bpy.app.version))


if __name__ == "__main__":
    run(main)
