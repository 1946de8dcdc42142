"""Renders the README's spectral pictures with Photon in spectral mode: a narrow beam through a
flint glass prism throwing a spectrum on a wall (docs/prism.png) and the caustic of a dispersive
glass ball (docs/dispersive_ball.png). Run inside Blender:

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \\
        --python tools/spectral_pictures.py -- docs [--size 640x360] [--samples 64]
"""

import argparse
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "test_scenes"))
import builders  # noqa: E402


def glass(name, abbe, ior=1.6):
    mat = builders.glass_material(name, ior=ior)
    next(n for n in mat.node_tree.nodes if n.type == 'BSDF_GLASS').distribution = 'SHARP'
    mat.photon.abbe_number = abbe
    return mat


def prism(name, side, height, material):
    """An equilateral prism standing on the floor, its apex pointing to -x, edges along z."""
    r = side / math.sqrt(3.0)
    corners = [(-r, 0.0), (r / 2, side / 2), (r / 2, -side / 2)]
    verts = [(x, y, z) for z in (0.0, height) for x, y in corners]
    faces = [(0, 1, 2), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)]
    centre = (0.0, 0.0, height / 2)
    return builders.mesh_object(name, verts, [outward(verts, f, centre) for f in faces], material)


def outward(verts, face, centre):
    """`face` wound so its normal points away from `centre` (glass needs outward normals)."""
    a, b, c = (verts[i] for i in face[:3])
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    mid = [sum(verts[i][k] for i in face) / len(face) - centre[k] for k in range(3)]
    return face if sum(n[k] * mid[k] for k in range(3)) > 0 else tuple(reversed(face))


def dim_world(scene, value):
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (value,) * 3 + (1,)


def settings(scene, samples, caustic_photons):
    p = scene.photon
    p.spectral = True
    p.spectral_samples = 4
    p.integrator = 'PHOTON_MAP'
    p.samples = samples
    p.caustic_photons = caustic_photons
    p.caustic_gather_count = 80
    p.photons = 200000
    p.max_depth = 16
    scene.view_settings.view_transform = 'Filmic'
    scene.render.image_settings.file_format = 'PNG'
    scene.render.image_settings.color_depth = '8'


def prism_scene(width, height, samples):
    """A spot lamp behind a vertical slit sends a thin sheet of light onto the prism's face at
    the minimum-deviation angle of its d-line index; the spectrum fans out onto the wall, blue
    bent furthest towards the prism's base."""
    scene = builders.reset_scene(width=width, height=height)
    settings(scene, samples, 4000000)
    dim_world(scene, 0.04)
    floor = builders.diffuse_material("Floor", (0.3, 0.3, 0.3))
    wall = builders.diffuse_material("Wall", (0.85, 0.85, 0.85))
    black = builders.diffuse_material("Black", (0.0, 0.0, 0.0))
    builders.quad("Floor", (-6, -3, 0), (12, 0, 0), (0, 5, 0), floor)
    builders.quad("Wall", (-6, 2, 0), (12, 0, 0), (0, 0, 3), wall)
    # The beam runs 0.8 m above the floor: floor points near the wall stay beyond the caustic
    # gather radius of the spectrum's dense band of photons (a k-nearest query almost
    # equidistant from a long line of them visits most of the line).
    prism("Prism", 0.3, 1.1, glass("Flint", abbe=15.0))
    # Minimum deviation for n = 1.6 and a 60 degree apex: 2 asin(n / 2) - 60 degrees; the beam
    # arrives turned by half of it from the prism's base direction (+y).
    half = 0.5 * (2.0 * math.asin(0.8) - math.pi / 3.0)
    direction = (-math.sin(half), math.cos(half), 0.0)
    target = (0.0, 0.0, 0.8)
    # The slit: two black plates across the beam 1.2 m before the prism, 8 mm apart.
    for side in (-1, 1):
        plate = builders.box(f"Slit{side}", (0.004 if side > 0 else -0.3, -0.01, 0.55),
                             (0.3 if side > 0 else -0.004, 0.01, 1.05), black)
        plate.location = tuple(target[i] - direction[i] * 1.2 for i in range(2)) + (0.0,)
        plate.rotation_euler = (0.0, 0.0, half)
    spot = builders.light("Beam", 'SPOT', 20000.0,
                          tuple(target[i] - direction[i] * 3.0 for i in range(3)),
                          spot_size=math.radians(4.0), spot_blend=0.0, shadow_soft_size=0.0)
    builders.aim(spot, target)
    camera = builders.camera(location=(2.2, -1.2, 1.6), lens=28.0)
    builders.aim(camera, (0.4, 0.9, 0.7))
    return scene


def ball_scene(width, height, samples):
    """A dispersive glass ball resting on a pale floor, lit from one side by a small lamp at the
    elevation that puts the floor at the ball's paraxial focus (f = n R / (2 (n - 1)) from the
    centre): blue, refracted more, focuses nearer and spreads into a halo around the warmer
    focus."""
    scene = builders.reset_scene(width=width, height=height)
    settings(scene, samples, 10000000)
    scene.photon.caustic_gather_count = 100
    scene.view_settings.view_transform = 'Standard'
    dim_world(scene, 0.03)
    floor = builders.diffuse_material("Floor", (0.8, 0.8, 0.8))
    builders.quad("Floor", (-4, -4, 0), (8, 0, 0), (0, 8, 0), floor)
    builders.uv_sphere("Ball", (0.0, 0.0, 0.3), 0.3, segments=128, rings=64,
                       material=glass("DenseFlint", abbe=8.0, ior=1.5))
    elevation = math.asin(0.3 / (1.5 * 0.3 / (2.0 * 0.5)))  # floor 0.3 below the centre, at f
    lamp = builders.light("Lamp", 'POINT', 120.0,
                          (-2.5 * math.cos(elevation), 0.0, 0.3 + 2.5 * math.sin(elevation)),
                          shadow_soft_size=0.005)
    lamp.data.photon.spectrum = 'BLACKBODY'
    lamp.data.photon.temperature = 6500.0
    camera = builders.camera(location=(0.8, -1.3, 1.0), lens=50.0)
    builders.aim(camera, (0.25, 0.0, 0.12))
    return scene


def render(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    print(f"wrote {path}")


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("out_dir")
    parser.add_argument("--size", default="640x360")
    parser.add_argument("--samples", type=int, default=64)
    parser.add_argument("--only", choices=("prism", "ball"))
    args = parser.parse_args(argv)
    width, height = (int(v) for v in args.size.split("x"))
    if args.only in (None, "prism"):
        render(prism_scene(width, height, args.samples), os.path.join(args.out_dir, "prism.png"))
    if args.only in (None, "ball"):
        render(ball_scene(width, height, args.samples),
               os.path.join(args.out_dir, "dispersive_ball.png"))


main()
