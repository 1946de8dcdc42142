"""bpy helpers that build test scenes from nothing (run inside Blender).

Used by make_scenes.py (the committed .blend files) and by the headless tests that build scenes
inline. Everything goes through bpy.data, not operators, so it works in background mode.
"""

import math

import bpy


def reset_scene(engine="PHOTON", width=128, height=128):
    """Empties the current file and returns its scene, set up for fast, deterministic renders."""
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.lights, bpy.data.cameras,
                       bpy.data.materials, bpy.data.worlds, bpy.data.images,
                       bpy.data.node_groups, bpy.data.curves):
        for block in list(collection):
            collection.remove(block)
    scene = bpy.context.scene
    scene.render.engine = engine
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.use_compositing = False
    scene.render.use_sequencer = False
    scene.render.film_transparent = False
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.frame_start = scene.frame_end = scene.frame_current = 1
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    scene.world = world
    return scene


def link(obj, scene=None):
    (scene or bpy.context.scene).collection.objects.link(obj)
    return obj


def diffuse_material(name, color):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*color, 1.0)
    links.new(bsdf.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    mat.diffuse_color = (*color, 1.0)
    return mat


# Principled BSDF v1 (Blender 3.x) input names and their Principled v2 (4.0+) names: scripts
# name the v1 input, and in 4.0+ the v2 socket of nearest meaning is used. (Specular Tint and
# Sheen Tint, factors in v1 and colours in v2, keep their names and need a value of each kind.)
PRINCIPLED_V2_NAMES = {
    "Subsurface": "Subsurface Weight", "Specular": "Specular IOR Level",
    "Sheen": "Sheen Weight", "Clearcoat": "Coat Weight", "Clearcoat Roughness": "Coat Roughness",
    "Clearcoat Normal": "Coat Normal", "Transmission": "Transmission Weight",
    "Emission": "Emission Color",
}


def principled_input(node, name):
    """The Principled BSDF `node`'s input of v1 `name` in the running Blender (None if gone,
    as Subsurface Color in 4.0+)."""
    if bpy.app.version >= (4, 0, 0) and node.type == 'BSDF_PRINCIPLED':
        name = PRINCIPLED_V2_NAMES.get(name, name)
    return node.inputs.get(name)


def set_principled(node, name, value):
    """Sets the v1-named input `name` of a Principled BSDF in any Blender (nothing where the
    input is gone); returns the socket or None."""
    socket = principled_input(node, name)
    if socket is not None:
        socket.default_value = value
    return socket


def new_group_socket(tree, in_out, socket_type, name):
    """Adds an input (in_out 'INPUT') or output ('OUTPUT') socket to a node group: 3.x's
    NodeTree.inputs/outputs, 4.0+'s NodeTree.interface."""
    if not hasattr(tree, "interface"):
        sockets = tree.inputs if in_out == 'INPUT' else tree.outputs
        return sockets.new(socket_type, name)
    factor = socket_type == 'NodeSocketFloatFactor'
    socket = tree.interface.new_socket(
        name, in_out=in_out, socket_type='NodeSocketFloat' if factor else socket_type)
    if factor:
        socket.subtype = 'FACTOR'
    return socket


def set_sharp(node):
    """A Glossy, Glass or Refraction node made perfectly smooth: 3.x's Sharp distribution, GGX
    at roughness 0 from 4.0 (where Sharp is gone)."""
    items = node.bl_rna.properties["distribution"].enum_items.keys()
    if 'SHARP' in items:
        node.distribution = 'SHARP'
    else:
        node.distribution = 'GGX'
        node.inputs["Roughness"].default_value = 0.0


def action_fcurves(animation_data):
    """The F-curves of an ID's action: Action.fcurves before Blender 5.0, the channel bag of
    the ID's action slot in 5.0's layered actions."""
    action = animation_data.action
    if hasattr(action, "fcurves"):
        return action.fcurves
    from bpy_extras import anim_utils
    return anim_utils.action_get_channelbag_for_slot(action, animation_data.action_slot).fcurves


def set_auto_smooth(mesh, angle=math.radians(30)):
    """Blender 3.x's Auto Smooth; from 4.1, where it is gone, sharp edges above `angle` instead
    (what Blender's own file conversion does)."""
    if hasattr(mesh, "use_auto_smooth"):
        mesh.use_auto_smooth = True
        mesh.auto_smooth_angle = angle
    else:
        mesh.set_sharp_from_angle(angle=angle)


def shader_material(name, node_type, **inputs):
    """A material whose output is one shader node of `node_type` with the given input values."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    node = nodes.new(node_type)
    for key, value in inputs.items():
        socket = principled_input(node, key)
        if socket is None:
            raise KeyError(f"{node.bl_label} has no input {key!r} in Blender "
                           f"{bpy.app.version_string}")
        socket.default_value = value
    links.new(node.outputs[0], nodes["Material Output"].inputs["Surface"])
    return mat


def mesh_object(name, vertices, faces, material=None, location=(0, 0, 0), smooth=False):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    mesh.update()
    if smooth:
        for poly in mesh.polygons:
            poly.use_smooth = True
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    if material is not None:
        mesh.materials.append(material)
    return link(obj)


def quad(name, corner, edge_u, edge_v, material=None):
    c = corner
    verts = [c,
             tuple(c[i] + edge_u[i] for i in range(3)),
             tuple(c[i] + edge_u[i] + edge_v[i] for i in range(3)),
             tuple(c[i] + edge_v[i] for i in range(3))]
    return mesh_object(name, verts, [(0, 1, 2, 3)], material)


def box(name, lo, hi, material=None):
    verts = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return mesh_object(name, verts, faces, material)


def keyframe_motion(camera_obj, moving, light, keys):
    """Animates a scene for animation tests: keys is [(frame, (camera x, object z, light
    power))], keyed on the camera's location, `moving`'s location and the light's energy."""
    for frame, (cam_x, z, power) in keys:
        camera_obj.location.x = cam_x
        camera_obj.keyframe_insert("location", frame=frame)
        moving.location.z = z
        moving.keyframe_insert("location", frame=frame)
        light.data.energy = power
        light.data.keyframe_insert("energy", frame=frame)


def uv_sphere(name, center, radius, segments=48, rings=24, material=None):
    verts = [(0.0, 0.0, radius)]
    for r in range(1, rings):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            verts.append((radius * math.sin(theta) * math.cos(phi),
                          radius * math.sin(theta) * math.sin(phi), radius * math.cos(theta)))
    verts.append((0.0, 0.0, -radius))
    faces = []
    for s in range(segments):
        faces.append((0, 1 + s, 1 + (s + 1) % segments))
    for r in range(rings - 2):
        a0 = 1 + r * segments
        b0 = a0 + segments
        for s in range(segments):
            s1 = (s + 1) % segments
            faces.append((a0 + s, b0 + s, b0 + s1, a0 + s1))
    last = len(verts) - 1
    base = 1 + (rings - 2) * segments
    for s in range(segments):
        faces.append((base + s, last, base + (s + 1) % segments))
    return mesh_object(name, verts, faces, material, location=center, smooth=True)


def camera(name="Camera", location=(0, -3.9, 1.0), rotation=(math.pi / 2, 0, 0), lens=50.0):
    data = bpy.data.cameras.new(name)
    data.lens = lens
    data.clip_start = 0.01
    data.clip_end = 100.0
    obj = link(bpy.data.objects.new(name, data))
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.camera = obj
    return obj


def light(name, light_type, energy, location, rotation=(0, 0, 0), **settings):
    data = bpy.data.lights.new(name, light_type)
    data.energy = energy
    for key, value in settings.items():
        setattr(data, key, value)
    obj = link(bpy.data.objects.new(name, data))
    obj.location = location
    obj.rotation_euler = rotation
    return obj


def cornell_box(width=256, height=256, samples=64, light_power=40.0):
    """The Cornell box of the demo and the regression suite: diffuse walls and boxes, a 0.5 m
    square area light under the ceiling. Same geometry as native test_scenes.cpp."""
    scene = reset_scene(width=width, height=height)
    white = diffuse_material("White", (0.73, 0.73, 0.73))
    red = diffuse_material("Red", (0.65, 0.05, 0.05))
    green = diffuse_material("Green", (0.12, 0.45, 0.15))
    quad("Floor", (-1, -1, 0), (2, 0, 0), (0, 2, 0), white)
    quad("Ceiling", (-1, -1, 2), (0, 2, 0), (2, 0, 0), white)
    quad("Back", (-1, 1, 0), (2, 0, 0), (0, 0, 2), white)
    quad("Left", (-1, -1, 0), (0, 2, 0), (0, 0, 2), red)
    quad("Right", (1, -1, 0), (0, 0, 2), (0, 2, 0), green)
    box("TallBox", (-0.6, -0.1, 0.0), (-0.05, 0.5, 1.2), white)
    box("ShortBox", (0.1, -0.6, 0.0), (0.65, -0.05, 0.6), white)
    light("CeilingLight", 'AREA', light_power, (0, 0, 1.98), size=0.5)
    camera()
    scene.photon.samples = samples
    scene.photon.max_depth = 8
    scene.photon.seed = 0
    return scene


# ---- Helpers added for the regression library (test_scenes/library.py) ----

def cornell_walls(white=None):
    """The five walls of cornell_box() (2 m wide, floor z=0, ceiling z=2, back wall y=+1),
    without boxes or light. Returns the white material."""
    white = white or diffuse_material("White", (0.73, 0.73, 0.73))
    red = diffuse_material("Red", (0.65, 0.05, 0.05))
    green = diffuse_material("Green", (0.12, 0.45, 0.15))
    quad("Floor", (-1, -1, 0), (2, 0, 0), (0, 2, 0), white)
    quad("Ceiling", (-1, -1, 2), (0, 2, 0), (2, 0, 0), white)
    quad("Back", (-1, 1, 0), (2, 0, 0), (0, 0, 2), white)
    quad("Left", (-1, -1, 0), (0, 2, 0), (0, 0, 2), red)
    quad("Right", (1, -1, 0), (0, 0, 2), (0, 2, 0), green)
    return white


def glass_material(name="Glass", ior=1.5, color=(1.0, 1.0, 1.0)):
    """A sharp Glass BSDF (Photon: dielectric with Fresnel)."""
    return shader_material(name, "ShaderNodeBsdfGlass", Color=(*color, 1.0), Roughness=0.0,
                           IOR=ior)


def mirror_material(name="Mirror", color=(0.9, 0.9, 0.9)):
    """A sharp Glossy BSDF (Photon: perfect mirror)."""
    return shader_material(name, "ShaderNodeBsdfGlossy", Color=(*color, 1.0), Roughness=0.0)


def aim(obj, target):
    """Rotates obj (camera or light, looking down its local -Z) to look at `target`."""
    from mathutils import Vector
    direction = Vector(target) - obj.location
    obj.rotation_euler = direction.to_track_quat('-Z', 'Y').to_euler()
    return obj


def subdivide(obj, cuts):
    """Splits every edge of the object's mesh `cuts` times, faces filled as grids."""
    import bmesh
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=cuts, use_grid_fill=True)
    bm.to_mesh(obj.data)
    bm.free()
    obj.data.update()
