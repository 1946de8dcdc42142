"""The regression and validation scene library (bpy builders; run inside Blender through
make_library.py).

Every scene: small resolution, few samples, fixed scene.photon.seed, compositing off, 32-bit
float RGBA OPEN_EXR output. Each entry of SCENES gives the folder ("regression": references
rendered by Photon; "validation": references rendered by Cycles), the builder and the sidecar
written next to the .blend (see docs/regression.md).
"""

import math
import os

import bpy
import numpy as np

import builders

SIZE = 128           # regression scenes: SIZE x SIZE pixels
SAMPLES = 16         # regression scenes: Photon samples per pixel
VALIDATION_SIZE = 128
VALIDATION_SAMPLES = 256


def pin_settings(scene, samples, seed=1):
    """Sets every output and Photon setting the suite relies on explicitly."""
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.render.image_settings.color_mode = 'RGBA'
    scene.render.use_compositing = False
    scene.render.film_transparent = False
    photon = scene.photon
    photon.integrator = 'PHOTON_MAP'
    photon.photons = 100000
    photon.caustic_photons = 50000
    photon.gather_count = 100
    photon.caustic_gather_count = 50
    photon.gather_radius = 0.0
    photon.final_gather_rays = 8
    photon.photon_time = 0.0
    photon.radiosity_patch_size = 0.0
    photon.radiosity_rays = 8000
    photon.radiosity_threshold = 0.01
    photon.radiosity_iterations = 4
    photon.samples = samples
    photon.max_depth = 8
    photon.seed = seed
    photon.threads = 0
    photon.tile_size = 32
    return scene


def base_scene(width=SIZE, height=SIZE, samples=SAMPLES):
    """An empty scene (black world) with the suite's settings."""
    return pin_settings(builders.reset_scene(width=width, height=height), samples)


def cycles_reference(scene, samples=2048, max_bounces=32, caustics=True):
    """Settings of the Cycles reference render (validation scenes). Denoising, adaptive
    sampling and clamping are off so the reference is unbiased; the box filter of width 1
    matches Photon's jittered box filter."""
    cycles = scene.cycles
    cycles.device = 'CPU'
    cycles.samples = samples
    cycles.seed = 7
    cycles.use_animated_seed = False
    cycles.use_denoising = False
    cycles.use_adaptive_sampling = False
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.light_sampling_threshold = 0.0
    cycles.pixel_filter_type = 'BOX'
    cycles.filter_width = 1.0
    cycles.max_bounces = max_bounces
    for attr in ("diffuse_bounces", "glossy_bounces", "transmission_bounces"):
        setattr(cycles, attr, max_bounces)
    cycles.transparent_max_bounces = max(8, max_bounces)
    cycles.min_light_bounces = 0
    cycles.caustics_reflective = caustics
    cycles.caustics_refractive = caustics
    cycles.blur_glossy = 0.0


def floor_camera():
    """A camera looking down at the origin from the front (no horizon in view)."""
    cam = builders.camera(location=(0.0, -4.2, 3.2))
    builders.aim(cam, (0.0, 0.1, 0.3))
    return cam


def floor_and_objects():
    """A 20 m diffuse floor with a sphere, a box and a small sphere standing on it."""
    floor = builders.diffuse_material("Floor", (0.7, 0.7, 0.7))
    builders.quad("Floor", (-10, -10, 0), (20, 0, 0), (0, 20, 0), floor)
    builders.uv_sphere("Ball", (-0.6, 0.2, 0.45), 0.45, segments=48, rings=24,
                       material=builders.diffuse_material("Orange", (0.8, 0.35, 0.1)))
    builders.box("Block", (0.2, -0.3, 0.0), (0.9, 0.4, 0.7),
                 builders.diffuse_material("Blue", (0.15, 0.25, 0.7)))
    builders.uv_sphere("Pebble", (0.2, -0.9, 0.2), 0.2, segments=32, rings=16,
                       material=builders.diffuse_material("Green", (0.2, 0.6, 0.25)))


# ---- Regression scenes ----

def cornell_box():
    """The demo Cornell box (diffuse walls and boxes, square area light in the ceiling)."""
    return pin_settings(builders.cornell_box(width=SIZE, height=SIZE), samples=16)


def caustic_box():
    """Cornell walls with a glass ball and a mirror ball under a small sphere light."""
    scene = base_scene(samples=16)
    builders.cornell_walls()
    builders.uv_sphere("GlassBall", (-0.45, 0.2, 0.35), 0.35, segments=64, rings=32,
                       material=builders.glass_material())
    builders.uv_sphere("MirrorBall", (0.45, -0.2, 0.35), 0.35, segments=64, rings=32,
                       material=builders.mirror_material())
    builders.light("SphereLight", 'POINT', 60.0, (0, 0, 1.8), shadow_soft_size=0.05)
    builders.camera()
    return scene


LIGHT_SETUPS = {
    "point": ('POINT', 150.0, (1.0, -1.2, 2.0), {"shadow_soft_size": 0.25}),
    "spot": ('SPOT', 400.0, (0.8, -1.6, 2.6), {"spot_size": math.radians(55),
                                               "spot_blend": 0.3, "shadow_soft_size": 0.1}),
    "sun": ('SUN', 3.0, (0.0, 0.0, 5.0), {"angle": math.radians(4)}),
    "area_square": ('AREA', 200.0, (0.3, -0.8, 2.0), {"shape": 'SQUARE', "size": 1.0}),
    "area_disk": ('AREA', 200.0, (0.3, -0.8, 2.0), {"shape": 'DISK', "size": 1.0}),
    "area_rect": ('AREA', 200.0, (0.3, -0.8, 2.0), {"shape": 'RECTANGLE', "size": 1.6,
                                                      "size_y": 0.4}),
    "area_ellipse": ('AREA', 200.0, (0.3, -0.8, 2.0), {"shape": 'ELLIPSE', "size": 1.6,
                                                         "size_y": 0.6}),
}


def lights_scene(case):
    """Diffuse floor and objects lit by the one light of LIGHT_SETUPS[case]."""
    def build():
        scene = base_scene()
        floor_and_objects()
        light_type, energy, location, settings = LIGHT_SETUPS[case]
        lamp = builders.light(f"Light_{case}", light_type, energy, location, **settings)
        lamp.data.color = (1.0, 0.92, 0.8)
        if light_type == 'SUN':
            lamp.rotation_euler = (math.radians(35), 0.0, math.radians(30))
        else:
            builders.aim(lamp, (0.0, 0.0, 0.0))
        floor_camera()
        return scene
    build.__name__ = f"lights_{case}"
    build.__doc__ = f"Diffuse floor and objects under one {case.replace('_', ' ')} light."
    return build


def scatter_group(material, density=160.0, radius=0.035, seed=3):
    """Geometry nodes: the input mesh plus ico spheres instanced on random points of its faces
    (Distribute Points on Faces + Instance on Points, random scale)."""
    group = bpy.data.node_groups.new("Scatter", 'GeometryNodeTree')
    group.inputs.new('NodeSocketGeometry', "Geometry")
    group.outputs.new('NodeSocketGeometry', "Geometry")
    nodes, links = group.nodes, group.links
    group_in, group_out = nodes.new('NodeGroupInput'), nodes.new('NodeGroupOutput')
    distribute = nodes.new('GeometryNodeDistributePointsOnFaces')
    distribute.distribute_method = 'RANDOM'
    distribute.inputs["Density"].default_value = density
    distribute.inputs["Seed"].default_value = seed
    ico = nodes.new('GeometryNodeMeshIcoSphere')
    ico.inputs["Radius"].default_value = radius
    ico.inputs["Subdivisions"].default_value = 2
    set_material = nodes.new('GeometryNodeSetMaterial')
    set_material.inputs["Material"].default_value = material
    scale = nodes.new('FunctionNodeRandomValue')
    scale.data_type = 'FLOAT'
    scale.inputs[2].default_value = 0.5   # Min (float)
    scale.inputs[3].default_value = 1.5   # Max (float)
    instance = nodes.new('GeometryNodeInstanceOnPoints')
    join = nodes.new('GeometryNodeJoinGeometry')
    links.new(group_in.outputs[0], distribute.inputs["Mesh"])
    links.new(ico.outputs["Mesh"], set_material.inputs["Geometry"])
    links.new(distribute.outputs["Points"], instance.inputs["Points"])
    links.new(set_material.outputs["Geometry"], instance.inputs["Instance"])
    links.new(next(o for o in scale.outputs if o.type == 'VALUE'), instance.inputs["Scale"])
    links.new(group_in.outputs[0], join.inputs[0])
    links.new(instance.outputs["Instances"], join.inputs[0])
    links.new(join.outputs[0], group_out.inputs[0])
    return group


def instancing():
    """A geometry-nodes scatter of ~640 small spheres (instances of one mesh) on a 2 m plane,
    lit by an area light."""
    scene = base_scene()
    ground = builders.quad("Ground", (-1, -1, 0), (2, 0, 0), (0, 2, 0),
                           builders.diffuse_material("Ground", (0.6, 0.6, 0.6)))
    dots = builders.diffuse_material("Dots", (0.8, 0.2, 0.2))
    ground.data.materials.append(dots)
    modifier = ground.modifiers.new("Scatter", 'NODES')
    modifier.node_group = scatter_group(dots)
    builders.light("Key", 'AREA', 150.0, (0.5, -1.0, 2.5), size=1.0)
    builders.aim(bpy.data.objects["Key"], (0, 0, 0))
    builders.aim(builders.camera(location=(0.0, -2.6, 2.6)), (0, 0, 0))
    return scene


def modifiers():
    """Subdivision surface (a cube becomes a smooth blob), an array of boxes and an array of
    subdivided cubes, on a diffuse floor."""
    scene = base_scene()
    builders.quad("Floor", (-10, -10, 0), (20, 0, 0), (0, 20, 0),
                  builders.diffuse_material("Floor", (0.7, 0.7, 0.7)))
    blob = builders.box("Blob", (-1.1, -0.2, 0.0), (-0.3, 0.6, 0.8),
                        builders.diffuse_material("Blob", (0.7, 0.3, 0.6)))
    subsurf = blob.modifiers.new("Subdivision", 'SUBSURF')
    subsurf.levels = subsurf.render_levels = 3
    for poly in blob.data.polygons:
        poly.use_smooth = True
    row = builders.box("Row", (-0.2, -1.0, 0.0), (0.05, -0.75, 0.5),
                       builders.diffuse_material("Row", (0.2, 0.5, 0.8)))
    array = row.modifiers.new("Array", 'ARRAY')
    array.count = 5
    array.relative_offset_displace = (1.6, 0.0, 0.0)
    beads = builders.box("Beads", (0.3, 0.2, 0.0), (0.5, 0.4, 0.2),
                         builders.diffuse_material("Beads", (0.9, 0.8, 0.2)))
    stack = beads.modifiers.new("Array", 'ARRAY')
    stack.count = 4
    stack.relative_offset_displace = (0.0, 0.0, 1.3)
    smooth = beads.modifiers.new("Subdivision", 'SUBSURF')
    smooth.levels = smooth.render_levels = 2
    builders.light("Key", 'AREA', 250.0, (1.0, -1.5, 2.5), size=1.2)
    builders.aim(bpy.data.objects["Key"], (0, 0, 0))
    floor_camera()
    return scene


def checker_png(path, size=64, checks=8):
    """Writes a red/white checker PNG (sRGB) with bpy; returns the path."""
    cell = size // checks
    yy, xx = np.mgrid[0:size, 0:size]
    odd = ((yy // cell + xx // cell) % 2).astype(bool)
    pixels = np.ones((size, size, 4), dtype=np.float32)
    pixels[odd, 1:3] = 0.1
    pixels[odd, 0] = 0.8
    image = bpy.data.images.new("checker_tmp", size, size, alpha=True)
    image.pixels.foreach_set(pixels.ravel())
    image.filepath_raw = path
    image.file_format = 'PNG'
    image.save()
    bpy.data.images.remove(image)
    return path


def image_material(name, image_path):
    """Principled BSDF whose Base Color comes from an Image Texture node."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(image_path)
    links.new(texture.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
    return mat


def textures(folder):
    """A UV-mapped plane and a cube with an image-textured Principled material
    (//textures/checker.png), sampled through OpenImageIO's TextureSystem."""
    scene = base_scene()
    os.makedirs(os.path.join(folder, "textures"), exist_ok=True)
    path = checker_png(os.path.join(folder, "textures", "checker.png"))
    mat = image_material("Checker", path)
    plane = builders.quad("Plane", (-1.5, -1.5, 0), (3, 0, 0), (0, 3, 0), mat)
    uv = plane.data.uv_layers.new(name="UVMap")
    uv.data.foreach_set("uv", [0, 0, 2, 0, 2, 2, 0, 2])
    builders.box("Cube", (-0.4, -0.4, 0.0), (0.4, 0.4, 0.8), mat)
    builders.light("Key", 'AREA', 200.0, (0.6, -1.2, 2.4), size=1.0)
    builders.aim(bpy.data.objects["Key"], (0, 0, 0))
    floor_camera()
    return scene


def keyframe(obj, path, values):
    """Sets obj.<path> to values[i] at frame i+1 and keys it."""
    for frame, value in enumerate(values, 1):
        setattr(obj, path, value)
        obj.keyframe_insert(data_path=path, frame=frame)


def animation():
    """3 frames: a ball slides, a box turns, the light moves and brightens."""
    scene = base_scene()
    floor_and_objects()
    keyframe(bpy.data.objects["Ball"], "location",
             [(-0.6, 0.2, 0.45), (-0.3, 0.0, 0.45), (0.0, -0.2, 0.45)])
    keyframe(bpy.data.objects["Block"], "rotation_euler",
             [(0, 0, 0), (0, 0, math.radians(20)), (0, 0, math.radians(40))])
    lamp = builders.light("Key", 'POINT', 80.0, (1.0, -1.2, 2.0), shadow_soft_size=0.2)
    keyframe(lamp, "location", [(1.0, -1.2, 2.0), (0.0, -1.2, 2.2), (-1.0, -1.2, 2.0)])
    for frame, energy in enumerate((80.0, 160.0, 240.0), 1):
        lamp.data.energy = energy
        lamp.data.keyframe_insert(data_path="energy", frame=frame)
    floor_camera()
    scene.frame_start, scene.frame_end = 1, 3
    scene.frame_set(1)
    return scene


def empty_scene():
    """A camera and a dim blue world, no objects: the render is the world colour."""
    scene = base_scene()
    builders.camera()
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.05, 0.08, 0.12,
                                                                                1.0)
    return scene


def no_lights():
    """Cornell geometry, no lights, black world: a black image (and a warning)."""
    scene = cornell_box()
    bpy.data.objects.remove(bpy.data.objects["CeilingLight"])
    return scene


def bad_geometry():
    """Cornell box plus a box with NaN and infinite vertices, a zero-area triangle, a face whose
    corners coincide and a zero-size quad: the bad geometry is dropped with a warning, the rest
    renders."""
    scene = cornell_box()
    obj = builders.box("NaNBox", (-0.2, -0.2, 0.5), (0.2, 0.2, 0.9),
                       builders.diffuse_material("NaN", (0.9, 0.9, 0.1)))
    co = np.empty(len(obj.data.vertices) * 3, dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    co[0] = math.nan
    co[4] = math.inf
    obj.data.vertices.foreach_set("co", co)
    obj.data.update()
    builders.mesh_object("Degenerate", [(0, 0, 1), (0.5, 0, 1), (1, 0, 1), (0.3, 0.3, 1)],
                         [(0, 1, 2)])
    builders.mesh_object("Collapsed", [(0.3, -0.5, 0.3)] * 3 + [(0.5, -0.5, 0.3)] * 3,
                         [(0, 1, 2), (3, 4, 5)])
    builders.quad("ZeroQuad", (0.4, -0.4, 1.0), (0, 0, 0), (0, 0, 0))
    # A sound ball next to the bad geometry must still render normally.
    builders.uv_sphere("GoodBall", (0.45, -0.3, 0.9), 0.2, segments=32, rings=16,
                       material=builders.diffuse_material("Good", (0.2, 0.4, 0.9)))
    return scene


# ---- Validation scenes (references rendered by Cycles) ----

def cornell_gi():
    """Diffuse Cornell box with full global illumination in the Cycles reference."""
    scene = pin_settings(builders.cornell_box(width=VALIDATION_SIZE, height=VALIDATION_SIZE),
                         VALIDATION_SAMPLES)
    cycles_reference(scene, samples=4096, max_bounces=32)
    return scene


def cornell_radiosity():
    """cornell_gi rendered by the RADIOSITY integrator (automatic patch size, 16M rays),
    compared with the same Cycles reference (a copy of cornell_gi.exr)."""
    scene = cornell_gi()
    photon = scene.photon
    photon.integrator = 'RADIOSITY'
    photon.radiosity_rays = 16000
    photon.samples = 64  # anti-aliasing only: the radiosity solution is smooth
    return scene


def caustic_validation():
    """The caustic box (glass and mirror balls, small sphere light) with Photon's default
    photon-mapping settings, against Cycles with caustics (16384 spp)."""
    scene = caustic_box()
    pin_settings(scene, VALIDATION_SAMPLES)
    photon = scene.photon
    photon.photons, photon.caustic_photons, photon.final_gather_rays = 200000, 100000, 16
    cycles_reference(scene, samples=16384, max_bounces=32, caustics=True)
    return scene


def direct_lights():
    """A diffuse plane and objects lit by a point, a spot, a sun and an area light; the Cycles
    reference has max_bounces 0 (direct light only)."""
    scene = base_scene(VALIDATION_SIZE, VALIDATION_SIZE, VALIDATION_SAMPLES)
    scene.photon.integrator = 'RAY_TRACE'  # direct light only, like the reference
    floor_and_objects()
    for name, (light_type, energy, location, settings) in {
            "Point": ('POINT', 60.0, (-1.5, -1.0, 1.6), {"shadow_soft_size": 0.2}),
            "Spot": ('SPOT', 150.0, (1.2, -1.5, 2.2), {"spot_size": math.radians(45),
                                                      "spot_blend": 0.25,
                                                      "shadow_soft_size": 0.1}),
            "Area": ('AREA', 80.0, (0.0, 1.2, 1.8), {"shape": 'RECTANGLE', "size": 1.0,
                                                    "size_y": 0.5}),
    }.items():
        lamp = builders.light(name, light_type, energy, location, **settings)
        builders.aim(lamp, (0.0, 0.0, 0.0))
    bpy.data.objects["Point"].data.color = (1.0, 0.8, 0.6)
    bpy.data.objects["Spot"].data.color = (0.7, 0.8, 1.0)
    sun = builders.light("Sun", 'SUN', 1.0, (0, 0, 5), (math.radians(50), 0, math.radians(-40)),
                         angle=math.radians(3))
    sun.data.color = (1.0, 0.95, 0.9)
    floor_camera()
    cycles_reference(scene, samples=1024, max_bounces=0, caustics=False)
    return scene


def mirror_glass():
    """A mirror ball and a glass ball (IOR 1.5) on a diffuse floor under an area light; the
    Cycles reference includes reflections, refraction and the balls' caustics."""
    scene = base_scene(VALIDATION_SIZE, VALIDATION_SIZE, VALIDATION_SAMPLES)
    builders.quad("Floor", (-10, -10, 0), (20, 0, 0), (0, 20, 0),
                  builders.diffuse_material("Floor", (0.7, 0.7, 0.7)))
    builders.uv_sphere("MirrorBall", (0.55, 0.1, 0.45), 0.45, segments=64, rings=32,
                       material=builders.mirror_material())
    builders.uv_sphere("GlassBall", (-0.55, -0.2, 0.45), 0.45, segments=64, rings=32,
                       material=builders.glass_material())
    builders.uv_sphere("Pebble", (0.0, 0.7, 0.25), 0.25, segments=32, rings=16,
                       material=builders.diffuse_material("Orange", (0.8, 0.35, 0.1)))
    lamp = builders.light("Key", 'AREA', 300.0, (-0.8, -0.6, 2.5), shape='DISK', size=1.0)
    builders.aim(lamp, (0.0, 0.0, 0.0))
    floor_camera()
    cycles_reference(scene, samples=8192, max_bounces=16, caustics=True)
    return scene


def principled_material(name, **inputs):
    """A Principled BSDF material with the given input values (socket name -> value)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes["Principled BSDF"]
    for key, value in inputs.items():
        node.inputs[key].default_value = value
    return mat


SPHERES = {  # name -> (centre, Principled inputs); radius 0.4 each
    "Gold": ((-1.35, 0.0, 0.4), {"Base Color": (1.0, 0.766, 0.336, 1.0), "Metallic": 1.0,
                                  "Roughness": 0.25}),
    "BluePlastic": ((-0.45, 0.0, 0.4), {"Base Color": (0.05, 0.12, 0.6, 1.0), "Roughness": 0.4}),
    "Clay": ((0.45, 0.0, 0.4), {"Base Color": (0.65, 0.38, 0.28, 1.0), "Roughness": 1.0,
                                "Specular": 0.2}),
    "Glass": ((1.35, 0.0, 0.4), {"Base Color": (1.0, 1.0, 1.0, 1.0), "Transmission": 1.0,
                                 "Roughness": 0.0, "IOR": 1.45}),
}


def material_spheres(folder):
    """Principled spheres (gold metal rough 0.25, blue plastic rough 0.4, clay, glass) on an
    image-textured Principled floor, lit by an area light and an emissive panel, against Cycles
    (tests/blender/test_material_spheres.py compares each object's mean colour)."""
    scene = base_scene(192, 128, 64)
    scene.photon.final_gather_rays = 16
    os.makedirs(os.path.join(folder, "textures"), exist_ok=True)
    checker = checker_png(os.path.join(folder, "textures", "checker.png"))
    floor = image_material("Checker", checker)
    floor.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 0.8
    plane = builders.quad("Floor", (-6, -4, 0), (12, 0, 0), (0, 8, 0), floor)
    plane.data.uv_layers.new(name="UVMap").data.foreach_set("uv", [0, 0, 6, 0, 6, 4, 0, 4])
    for name, (centre, inputs) in SPHERES.items():
        builders.uv_sphere(name, centre, 0.4, segments=64, rings=32,
                           material=principled_material(name, **inputs))
    panel = principled_material("Panel", **{"Base Color": (0.0, 0.0, 0.0, 1.0),
                                            "Emission": (1.0, 0.85, 0.6, 1.0),
                                            "Emission Strength": 4.0, "Specular": 0.0})
    builders.quad("Panel", (-1.2, 1.6, 0.3), (2.4, 0, 0), (0, 0, 1.0), panel)
    lamp = builders.light("Key", 'AREA', 150.0, (1.2, -2.0, 3.0), shape='DISK', size=1.0)
    builders.aim(lamp, (0.0, 0.0, 0.3))
    world = bpy.data.worlds.new("Grey")
    world.color = (0.05, 0.05, 0.05)
    scene.world = world
    cam = builders.camera(location=(0.0, -5.2, 1.9), lens=45.0)
    builders.aim(cam, (0.0, 0.0, 0.35))
    cycles_reference(scene, samples=2048, max_bounces=16, caustics=True)
    return scene


def projected_regions(scene):
    """Pixel regions of each sphere (a disc inside its silhouette: [cx, cy, r], y down) and of
    the emissive panel and the floor (rectangles [x0, y0, x1, y1]), for per-object means."""
    from bpy_extras.object_utils import world_to_camera_view
    from mathutils import Vector
    width, height = scene.render.resolution_x, scene.render.resolution_y
    cam = scene.camera

    def pixel(point):
        v = world_to_camera_view(scene, cam, Vector(point))
        return v.x * width, (1.0 - v.y) * height

    right = cam.matrix_world.to_3x3() @ Vector((1.0, 0.0, 0.0))
    regions = {}
    for name, (centre, _) in SPHERES.items():
        cx, cy = pixel(centre)
        ex, ey = pixel(Vector(centre) + 0.4 * right)
        regions[name] = [round(cx, 2), round(cy, 2), round(0.8 * math.hypot(ex - cx, ey - cy), 2)]
    x0, y0 = pixel((-1.0, 1.6, 1.2))
    x1, y1 = pixel((1.0, 1.6, 0.95))  # above the spheres' silhouettes
    regions["Panel"] = [int(x0) + 1, int(y0) + 1, int(x1) - 1, int(y1) - 1]
    fx0, fy0 = pixel((-1.8, -1.4, 0.0))
    fx1, fy1 = pixel((1.8, -0.7, 0.0))
    regions["Floor"] = [int(fx0) + 1, int(fy1) + 1, int(fx1) - 1, int(fy0) - 1]
    return regions


def material_spheres_sidecar(scene):
    return {
        "reference_engine": "CYCLES", "reference_samples": 2048, "timeout": 400,
        "thresholds": {"mean_diff": 0.03, "rel_rmse": 0.2, "mean_rel": 0.05,
                       "pixel_threshold": 0.5, "pixel_fraction": 0.05, "alpha_max": 0.001},
        "regions": projected_regions(scene),
        "description": "Principled materials against Cycles (2048 spp, 16 bounces, caustics "
                       "on): gold metal roughness 0.25, blue plastic roughness 0.4, clay, glass, "
                       "an image-textured floor and an emissive panel. The image mean within 3%; "
                       "tests/blender/test_material_spheres.py checks each object's mean colour "
                       "(the 'regions') within 5%."}


# name -> (folder, builder, sidecar). Builders taking a folder argument get the output folder.
REGRESSION = "regression"
VALIDATION = "validation"
SCENES = {
    "cornell_box": (REGRESSION, cornell_box, {}),
    "caustic_box": (REGRESSION, caustic_box, {}),
    **{f"lights_{case}": (REGRESSION, lights_scene(case), {}) for case in LIGHT_SETUPS},
    "instancing": (REGRESSION, instancing, {}),
    "modifiers": (REGRESSION, modifiers, {}),
    "textures": (REGRESSION, textures, {}),
    "animation": (REGRESSION, animation, {"frames": [1, 2, 3]}),
    "empty_scene": (REGRESSION, empty_scene, {}),
    "no_lights": (REGRESSION, no_lights, {}),
    "bad_geometry": (REGRESSION, bad_geometry, {}),
    # Validation thresholds: what a correct renderer must meet. The noise floor, measured as
    # two Cycles renders with different seeds at the reference sample count (2048, 1024 and
    # 4096 spp), was rel_rmse 0.023 / 0.008 / 0.031 and mean_diff < 0.0003; the references
    # use twice those counts for cornell_gi and mirror_glass.
    "cornell_gi": (VALIDATION, cornell_gi, {
        "reference_engine": "CYCLES", "reference_samples": 4096, "timeout": 300,
        "thresholds": {"mean_diff": 0.02, "rel_rmse": 0.06, "mean_rel": 0.05,
                       "pixel_threshold": 0.25, "pixel_fraction": 0.02, "alpha_max": 0.001},
        "description": "Diffuse Cornell box, full global illumination (Cycles reference: 32 "
                       "bounces, box filter, 4096 spp): checks indirect diffuse light and colour "
                       "bleeding. Image mean within 2% of Cycles', relative RMSE below 0.06 "
                       "(the two Cycles seeds differ by 0.016 at this sample count), fewer than "
                       "2% of pixels off by more than 25%. RAY_TRACE (direct light only) fails "
                       "this until the photon-mapping integrator lands."}),
    "cornell_radiosity": (VALIDATION, cornell_radiosity, {
        "reference_engine": "CYCLES", "reference_samples": 4096, "timeout": 300,
        "thresholds": {"mean_diff": 0.03, "rel_rmse": 0.06, "mean_rel": 0.05,
                       "pixel_threshold": 0.25, "pixel_fraction": 0.02, "alpha_max": 0.001},
        "description": "The diffuse Cornell box of cornell_gi rendered by the RADIOSITY "
                       "integrator (stochastic Jacobi radiosity, automatic patch size: ~20k "
                       "patches, 16M rays), against cornell_gi's Cycles reference "
                       "(cornell_radiosity.exr is a copy of cornell_gi.exr; do not --update it "
                       "separately). Image mean within 3% of Cycles' (measured 0.34%), relative "
                       "RMSE below 0.06 (measured 0.035: solution noise and patch-sized "
                       "shadows), fewer than 2% of pixels off by more than 25% (measured "
                       "0.45%)."}),
    "caustic_validation": (VALIDATION, caustic_validation, {
        "reference_engine": "CYCLES", "reference_samples": 16384, "timeout": 300,
        "thresholds": {"mean_diff": 0.03, "rel_rmse": 0.15, "mean_rel": 0.1,
                       "pixel_threshold": 0.5, "pixel_fraction": 0.03, "alpha_max": 0.001},
        # Floor pixels (x0, y0, x1, y1) around the caustic under the glass ball, for
        # tests/blender/test_photon_map.py.
        "regions": {"caustic": [30, 100, 52, 114]},
        "description": "The caustic box against Cycles with caustics (16384 spp): the caustic "
                       "under the glass ball (tests/blender/test_photon_map.py compares its "
                       "position and power), the mirror ball's reflections and the diffuse "
                       "interreflection. Cycles' own noise from the small light is high at the "
                       "caustics, so rel_rmse is loose; the mean within 3%."}),
    "direct_lights": (VALIDATION, direct_lights, {
        "reference_engine": "CYCLES", "reference_samples": 1024, "timeout": 300,
        "thresholds": {"mean_diff": 0.01, "rel_rmse": 0.02, "mean_rel": 0.02,
                       "pixel_threshold": 0.1, "pixel_fraction": 0.01, "alpha_max": 0.001},
        "description": "Diffuse plane and objects lit by point (with radius), spot, sun and "
                       "rectangular area lights; Cycles reference with max_bounces 0 (direct "
                       "light only): checks light units, falloff, spot cone and blend, sun and "
                       "soft shadows. Image mean within 1%, relative RMSE below 0.02 (Cycles' "
                       "own noise: 0.006), fewer than 1% of pixels off by more than 10%."}),
    "material_spheres": (VALIDATION, material_spheres, material_spheres_sidecar),
    "mirror_glass": (VALIDATION, mirror_glass, {
        "reference_engine": "CYCLES", "reference_samples": 8192, "timeout": 300,
        "thresholds": {"mean_diff": 0.02, "rel_rmse": 0.1, "mean_rel": 0.05,
                       "pixel_threshold": 0.25, "pixel_fraction": 0.03, "alpha_max": 0.001},
        "description": "A mirror ball and a glass ball (IOR 1.5) on a diffuse floor under a "
                       "disk area light; Cycles reference with caustics on and the glossy "
                       "filter off (8192 spp): checks mirror reflection, refraction with "
                       "Fresnel, and the caustics of both balls on the floor, which RAY_TRACE "
                       "does not render (it fails on the image mean until photon mapping "
                       "lands). Image mean within 2%, relative RMSE below 0.1 (Cycles' own "
                       "noise: 0.015; about 90% of Photon's squared error sits in the ~50 pixels "
                       "that see the lamp through the glass ball, and without the 10 worst "
                       "pixels the relative RMSE is 0.05), fewer than 3% of pixels off by more "
                       "than 25%."}),
}
