"""Specular-diffuse-specular (SDS) scenes in Blender: the same triangles, normals, materials,
lights and camera as native/src/photon/testing/sds_scenes.cpp builds (see there for what each
scene shows), so the native tests, Photon in Blender and Cycles render one scene.

Writes NAME.blend into a folder (default build/sds; the files are not kept in the repository,
the pool's mesh alone is 1 MB), run inside Blender with the add-on:

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \
        -P test_scenes/sds.py [-- --out DIR --only NAME ...]

The references, test_scenes/sds/NAME.exr, are made by test_scenes/sds/make_references.py.
"""

import math
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import builders  # noqa: E402
import library  # noqa: E402

# References: SIZE x SIZE pixels (the native tests render SIZE / 2 and compare 2 x 2 means).
SIZE = 96

# The pool's waves: (amplitude, kx, ky, phase), as kWaves in sds_scenes.cpp.
WAVES = ((0.004, 22.0, 8.0, 0.3), (0.003, -12.0, 27.0, 1.1), (0.0025, 30.0, -18.0, 2.0))


# ---- Meshes built as sds_scenes.cpp / test_scenes.cpp build them ----

def triangle_mesh(name, positions, triangles, normals, material_slots=None, materials=()):
    """A mesh object of the given triangles (vertex index triples) whose corner normals are
    `normals` (three per triangle), set as custom split normals."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(map(float, p)) for p in positions], [],
                     [tuple(map(int, t)) for t in triangles])
    for mat in materials:
        mesh.materials.append(mat)
    if material_slots is not None:
        mesh.polygons.foreach_set("material_index", np.asarray(material_slots, dtype=np.int32))
    mesh.polygons.foreach_set("use_smooth", np.ones(len(triangles), dtype=bool))
    if hasattr(mesh, "use_auto_smooth"):  # custom normals need it before Blender 4.1
        mesh.use_auto_smooth = True
    mesh.update()
    mesh.normals_split_custom_set([tuple(map(float, n)) for n in normals])
    obj = bpy.data.objects.new(name, mesh)
    return builders.link(obj)


def uv_sphere_triangles(center, radius, segments, rings, inside_out=False):
    """make_uv_sphere: rings + 1 rings of `segments` vertices (the poles repeated), quads split
    (a, c, d), (a, d, b), corner normals radial; the triangles degenerate at the poles (which
    the native side drops) are left out. Inside out: wound the other way, normals inward.
    Returns (positions, triangles, corner normals)."""
    c = np.asarray(center, dtype=np.float64)
    positions = []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2.0 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi),
                 math.cos(theta))
            positions.append(c + radius * np.asarray(n))
    triangles = []
    for r in range(rings):
        for s in range(segments):
            a, b = r * segments + s, r * segments + (s + 1) % segments
            cc, d = a + segments, b + segments
            if r != rings - 1:
                triangles.append((a, cc, d))
            if r != 0:
                triangles.append((a, d, b))
    if inside_out:
        triangles = [(a, cc, b) for a, b, cc in triangles]
    sign = -1.0 if inside_out else 1.0
    normals = [sign * (positions[i] - c) / radius for t in triangles for i in t]
    return positions, triangles, normals


def uv_sphere(name, center, radius, segments, rings, material):
    positions, triangles, normals = uv_sphere_triangles(center, radius, segments, rings)
    return triangle_mesh(name, positions, triangles, normals, materials=(material,))


def glass_shell(name, center, outer, inner, material):
    """The glass_light scene's shell: a 64 x 32 UV sphere of radius `outer` and, turned inside
    out, one of radius `inner` (the air cavity), in one mesh."""
    positions, triangles, normals = uv_sphere_triangles(center, outer, 64, 32)
    p2, t2, n2 = uv_sphere_triangles(center, inner, 64, 32, inside_out=True)
    offset = len(positions)
    return triangle_mesh(name, positions + p2,
                         triangles + [tuple(i + offset for i in t) for t in t2], normals + n2,
                         materials=(material,))


def emissive_sphere(center, radius, radiance):
    """add_emissive_sphere: a 24 x 12 UV sphere with an Emission shader of that radiance."""
    light = builders.shader_material("Light", "ShaderNodeEmission", Color=(1, 1, 1, 1),
                                     Strength=radiance)
    return uv_sphere("Light", center, radius, 24, 12, light)


def wave_height(x, y):
    return sum(a * np.sin(kx * x + ky * y + p) for a, kx, ky, p in WAVES)


def wave_normal(x, y):
    dx = sum(a * np.cos(kx * x + ky * y + p) * kx for a, kx, ky, p in WAVES)
    dy = sum(a * np.cos(kx * x + ky * y + p) * ky for a, kx, ky, p in WAVES)
    n = np.stack([-dx, -dy, np.ones_like(dx)], -1)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def wavy_slab(name, half, bottom, top, cells, material):
    """make_wavy_slab: a closed slab with a wavy top grid (analytic normals), flat bottom and
    sides, faces pointing out."""
    n = cells + 1
    coords = -half + 2.0 * half * np.arange(n) / cells
    positions = [np.array([x, y, top + wave_height(x, y)]) for y in coords for x in coords]
    triangles, normals = [], []

    def smooth(a, b, c):
        triangles.append((a, b, c))
        normals.extend(wave_normal(positions[k][0], positions[k][1]) for k in (a, b, c))

    def flat(a, b, c):
        nf = np.cross(positions[b] - positions[a], positions[c] - positions[a])
        triangles.append((a, b, c))
        normals.extend([nf / np.linalg.norm(nf)] * 3)

    def top_index(i, j):
        return j * n + i

    for j in range(cells):
        for i in range(cells):
            a, b = top_index(i, j), top_index(i + 1, j)
            c, d = top_index(i + 1, j + 1), top_index(i, j + 1)
            smooth(a, b, c)
            smooth(a, c, d)
    base = len(positions)
    positions += [np.array(p, dtype=float) for p in ((-half, -half, bottom), (half, -half, bottom),
                                                     (half, half, bottom), (-half, half, bottom))]
    flat(base, base + 2, base + 1)
    flat(base, base + 3, base + 2)

    def side(top_at, outward):
        for k in range(cells):
            t0, t1 = top_at(k), top_at(k + 1)
            p0, p1 = positions[t0], positions[t1]
            b0 = len(positions)
            positions.append(np.array([p0[0], p0[1], bottom]))
            positions.append(np.array([p1[0], p1[1], bottom]))
            nf = np.cross(p1 - p0, positions[b0] - p0)
            if np.dot(nf, outward) > 0.0:
                flat(t0, t1, b0)
                flat(t1, b0 + 1, b0)
            else:
                flat(t0, b0, t1)
                flat(t1, b0, b0 + 1)

    side(lambda k: top_index(k, 0), (0, -1, 0))
    side(lambda k: top_index(cells, k), (1, 0, 0))
    side(lambda k: top_index(k, cells), (0, 1, 0))
    side(lambda k: top_index(0, k), (-1, 0, 0))
    return triangle_mesh(name, positions, triangles, normals, materials=(material,))


def checker_floor(name, half, tiles, materials):
    """make_checker_floor: tiles x tiles squares at z = 0, material slot (i + j) % 2."""
    n = tiles + 1
    positions = [(-half + 2.0 * half * i / tiles, -half + 2.0 * half * j / tiles, 0.0)
                 for j in range(n) for i in range(n)]
    triangles, slots = [], []
    for j in range(tiles):
        for i in range(tiles):
            a = j * n + i
            triangles += [(a, a + 1, a + 1 + n), (a, a + 1 + n, a + n)]
            slots += [(i + j) % 2] * 2
    normals = [(0.0, 0.0, 1.0)] * (3 * len(triangles))
    return triangle_mesh(name, positions, triangles, normals, slots, materials)


def sharp(material, node_name):
    """Sets the material's Glass or Glossy node to the Sharp distribution (a perfect mirror or
    dielectric in Cycles and Photon, as Material::glass and Material::mirror)."""
    material.node_tree.nodes[node_name].distribution = 'SHARP'
    return material


def look_at_camera(eye, target, fov_y):
    """make_look_at_camera: vertical field of view fov_y (radians), world +Z up."""
    cam = builders.camera(location=eye)
    cam.data.sensor_fit = 'VERTICAL'
    cam.data.angle_y = fov_y
    builders.aim(cam, target)
    return cam


# ---- The scenes ----

def settings(scene):
    """Photon: SPPM (the reference's integrator) at the test resolution; Cycles: the unbiased
    reference settings of the validation scenes."""
    library.pin_settings(scene, samples=16)
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    photon = scene.photon
    photon.integrator = 'SPPM'
    photon.sppm_iterations = 64
    photon.sppm_photons_per_iteration = 100000
    library.cycles_reference(scene, samples=4096, max_bounces=32, caustics=True)
    return scene


def glass_light():
    """(a) A thick glass shell (IOR 1.5, radii 0.4 and 0.25) holding a small emissive sphere in
    its air cavity, in the Cornell room: every wall is lit through the glass (caustics), and
    the ball shows them refracted (E S D S L)."""
    scene = builders.reset_scene(width=SIZE, height=SIZE)
    builders.cornell_walls()
    glass = sharp(builders.glass_material("Glass", 1.5), "Glass BSDF")
    glass_shell("GlassBall", (0.0, 0.1, 0.7), 0.4, 0.25, glass)
    emissive_sphere((0.0, 0.1, 0.82), 0.06, 60.0)
    look_at_camera((0.0, -3.9, 1.0), (0.0, 0.0, 1.0), 0.69)
    return settings(scene)


def mirror_caustic():
    """(b) A glass ball focusing a small emissive sphere onto a white floor in front of a flat
    mirror; the camera sees the caustic only in the mirror (E S D S S L)."""
    scene = builders.reset_scene(width=SIZE, height=SIZE)
    white = builders.diffuse_material("White", (0.75, 0.75, 0.75))
    mirror = sharp(builders.mirror_material("Mirror", (0.95, 0.95, 0.95)), "Glossy BSDF")
    glass = sharp(builders.glass_material("Glass", 1.5), "Glass BSDF")
    builders.quad("Floor", (-1.5, -1.5, 0), (3, 0, 0), (0, 3, 0), white)
    builders.quad("Wall", (-1.5, -1.5, 0), (0, 0, 2), (3, 0, 0), white)  # behind the camera
    builders.quad("Mirror", (-1.0, 1.0, 0.0), (2, 0, 0), (0, 0, 1.6), mirror)
    uv_sphere("GlassBall", (0.0, -0.35, 0.6), 0.25, 64, 32, glass)
    emissive_sphere((0.0, -0.35, 1.6), 0.04, 500.0)
    look_at_camera((0.0, -1.1, 1.35), (0.0, 1.0, 0.69), 0.45)
    return settings(scene)


def pool():
    """(c) A closed glass slab (IOR 1.33) with a wavy top over a checkered floor, a small
    emissive sphere above, the camera looking down through the surface (E S S D S S L)."""
    scene = builders.reset_scene(width=SIZE, height=SIZE)
    tiles = (builders.diffuse_material("TileWhite", (0.8, 0.8, 0.8)),
             builders.diffuse_material("TileBlue", (0.1, 0.3, 0.6)))
    checker_floor("Floor", 1.0, 8, tiles)
    water = sharp(builders.glass_material("Water", 1.33), "Glass BSDF")
    wavy_slab("Water", 1.0, 0.02, 0.45, 128, water)
    emissive_sphere((0.2, -1.6, 1.6), 0.08, 300.0)  # behind the camera: no glints
    look_at_camera((0.0, -0.9, 2.2), (0.0, 0.05, 0.0), 0.6)
    return settings(scene)


SCENES = {"glass_light": glass_light, "mirror_caustic": mirror_caustic, "pool": pool}


def main():
    import argparse
    parser = argparse.ArgumentParser(prog="sds.py")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(HERE), "build", "sds"),
                        help="folder of the .blend files (default build/sds)")
    parser.add_argument("--only", nargs="+", choices=list(SCENES), default=list(SCENES))
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
    os.makedirs(args.out, exist_ok=True)
    for name in args.only:
        scene = SCENES[name]()
        scene.name = "Scene"
        path = os.path.join(args.out, f"{name}.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
        print(f"sds: wrote {path}", flush=True)


if __name__ == "__main__":
    main()
