"""Renders mesh-attribute materials with Cycles and with Photon on one small triangle grid and
writes both images per case: a byte colour attribute (the active render one, corners), a float
colour on points, a float on faces, a vector on points, a second UV map driving a Checker, and a
missing attribute. Args: OUT_DIR."""

import os

import bpy
import numpy as np

import harness

GRID = 6
RESOLUTION = 48


def _hash(i, seed):
    """A deterministic value in [0, 1) per element (no Python random state)."""
    x = (i * 2654435761 + seed * 40503) & 0xFFFFFFFF
    x ^= x >> 13
    x = (x * 1274126177) & 0xFFFFFFFF
    return (x ^ (x >> 16)) / 4294967296.0


def _mesh():
    verts, faces = [], []
    for j in range(GRID + 1):
        for i in range(GRID + 1):
            x, y = -1.0 + 2.0 * i / GRID, -1.0 + 2.0 * j / GRID
            # Jittered (border vertices along the border) so that no triangle edge passes
            # exactly through pixel centres, where the engines could pick different sides.
            if 0 < i < GRID:
                x += (_hash(j * 31 + i, 1) - 0.5) * 0.12
            if 0 < j < GRID:
                y += (_hash(j * 31 + i, 2) - 0.5) * 0.12
            verts.append((x, y, 0.0))
    for j in range(GRID):
        for i in range(GRID):
            a = j * (GRID + 1) + i
            b, c, d = a + 1, a + GRID + 2, a + GRID + 1
            faces += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
    mesh = bpy.data.meshes.new("grid")
    mesh.from_pydata(verts, [], faces)
    first = mesh.uv_layers.new(name="UVMap")
    second = mesh.uv_layers.new(name="Second")
    uv = np.empty(len(mesh.loops) * 2, dtype=np.float32)
    first.data.foreach_get("uv", uv)
    # The second map: the first one rotated and stretched, so a checker on it is not the first's.
    u, v = uv[0::2].copy(), uv[1::2].copy()
    # (Kept positive: Photon clamps negative emission, which is not what is tested here.)
    uv[0::2], uv[1::2] = 0.8 * u + 0.6 * v, -1.3 * u + 0.9 * v + 1.4
    second.data.foreach_set("uv", uv)
    mesh.uv_layers.active = first
    col = mesh.color_attributes.new("Col", 'BYTE_COLOR', 'CORNER')
    col.data.foreach_set("color", [_hash(k, 3 + k % 4) for k in range(len(col.data) * 4)])
    pcol = mesh.color_attributes.new("PCol", 'FLOAT_COLOR', 'POINT')
    pcol.data.foreach_set("color", [_hash(k, 7) * 2.0 for k in range(len(pcol.data) * 4)])
    # The active colour is not the render one: Color Attribute without a name reads "Col".
    mesh.color_attributes.active_color = pcol
    names = [a.name for a in mesh.color_attributes]  # listed by domain: not creation order
    mesh.color_attributes.render_color_index = names.index("Col")
    f = mesh.attributes.new("f", 'FLOAT', 'FACE')
    f.data.foreach_set("value", [_hash(k, 11) for k in range(len(f.data))])
    vec = mesh.attributes.new("v", 'FLOAT_VECTOR', 'POINT')
    vec.data.foreach_set("vector", [_hash(k, 13) + 0.25 for k in range(len(vec.data) * 3)])
    return mesh


# name: (node, properties, output, via) where via = None (straight to the Emission) or
# "checker" (the output is the Vector of a Checker texture).
CASES = {
    "render_color": ("ShaderNodeVertexColor", {"layer_name": ""}, "Color", None),
    "byte_alpha": ("ShaderNodeVertexColor", {"layer_name": "Col"}, "Alpha", None),
    "point_color": ("ShaderNodeAttribute", {"attribute_name": "PCol"}, "Color", None),
    "point_color_fac": ("ShaderNodeAttribute", {"attribute_name": "PCol"}, "Fac", None),
    "face_float": ("ShaderNodeAttribute", {"attribute_name": "f"}, "Fac", None),
    "point_vector": ("ShaderNodeAttribute", {"attribute_name": "v"}, "Vector", None),
    "second_uv": ("ShaderNodeUVMap", {"uv_map": "Second"}, "UV", None),
    "second_uv_checker": ("ShaderNodeUVMap", {"uv_map": "Second"}, "UV", "checker"),
    "uv_by_attribute": ("ShaderNodeAttribute", {"attribute_name": "Second"}, "Vector", None),
    "missing_alpha": ("ShaderNodeAttribute", {"attribute_name": "nope"}, "Alpha", None),
    "missing_color": ("ShaderNodeAttribute", {"attribute_name": "nope"}, "Color", None),
}


def _material(name, case):
    node_type, props, output, via = case
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    emission = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(emission.outputs[0], out.inputs["Surface"])
    node = tree.nodes.new(node_type)
    node.name = "attr"
    for key, value in props.items():
        setattr(node, key, value)
    socket = node.outputs[output]
    if via == "checker":
        checker = tree.nodes.new("ShaderNodeTexChecker")
        checker.inputs["Scale"].default_value = 3.0
        checker.inputs["Color1"].default_value = (0.9, 0.5, 0.1, 1.0)
        checker.inputs["Color2"].default_value = (0.1, 0.3, 0.8, 1.0)
        tree.links.new(socket, checker.inputs["Vector"])
        socket = checker.outputs["Color"]
    tree.links.new(socket, emission.inputs["Color"])
    return mat


def _scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    import addon_utils
    addon_utils.enable("photon", default_set=True)
    scene = bpy.context.scene
    scene.render.resolution_x = scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.render.image_settings.color_mode = 'RGB'
    scene.view_settings.view_transform = 'Standard'
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.cycles.pixel_filter_type = 'BOX'
    scene.cycles.filter_width = 0.01
    scene.cycles.max_bounces = 0
    scene.photon.integrator = 'RAY_TRACE'
    scene.photon.samples = 1
    scene.photon.filter_width = 0.01
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    obj = bpy.data.objects.new("grid", _mesh())
    scene.collection.objects.link(obj)
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = 'ORTHO'
    cam_data.ortho_scale = 2.0
    camera = bpy.data.objects.new("camera", cam_data)
    camera.location = (0.0, 0.0, 5.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    return scene, obj


def main(out_dir):
    os.makedirs(out_dir, exist_ok=True)
    scene, obj = _scene()
    result = {}
    for name, case in CASES.items():
        obj.data.materials.clear()
        obj.data.materials.append(_material(name, case))
        images = {}
        for engine in ('CYCLES', 'PHOTON'):
            scene.render.engine = engine
            path = os.path.join(out_dir, f"{name}_{engine.lower()}.exr")
            scene.render.filepath = path
            bpy.ops.render.render(write_still=True)
            images[engine] = harness.read_image(path)[:, :, :3]
        cycles, photon = images['CYCLES'], images['PHOTON']
        # Both engines place their one sample within 0.01 pixel of the pixel centre (a Box
        # filter of width 0.01): the values may differ by that offset times the image's
        # gradient, estimated from the largest step to a 4-neighbour.
        padded = np.pad(cycles, ((1, 1), (1, 1), (0, 0)), mode='edge')
        step = np.max([np.abs(padded[1:-1, 1:-1] - padded[:-2, 1:-1]),
                       np.abs(padded[1:-1, 1:-1] - padded[2:, 1:-1]),
                       np.abs(padded[1:-1, 1:-1] - padded[1:-1, :-2]),
                       np.abs(padded[1:-1, 1:-1] - padded[1:-1, 2:])], axis=0)
        diff = np.abs(cycles - photon)
        scale = np.maximum(1.0, np.abs(cycles))
        over = diff > 1e-4 * scale + 0.03 * step  # margin for gradients that bend
        result[name] = {"max_rel": float((diff / scale).max()),
                        "max_beyond_jitter": float(np.max(diff - 0.03 * step)),
                        "over": int(over.any(axis=2).sum()),
                        "pixels": RESOLUTION * RESOLUTION,
                        "cycles_range": [float(images['CYCLES'].min()),
                                         float(images['CYCLES'].max())],
                        "photon_range": [float(images['PHOTON'].min()),
                                         float(images['PHOTON'].max())]}
    return result


harness.run(main)
