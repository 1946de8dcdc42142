"""Renders shader-node conformance cases: each case's node output drives an Emission shader on
a tilted plane seen by an orthographic camera, with no lights, so the image *is* the node's output
at each pixel's hit point. Cycles renders are the stored references; Photon renders the same
scenes for the conformance suite.

Run inside Blender:
  blender -b --factory-startup [--addons photon] --python tools/node_refs.py -- \
      MANIFEST.json OUT_DIR [--engine CYCLES|PHOTON] [--cases NAME,...]

A manifest is {"cases": [CASE, ...]} with CASE:
  {"name": "noise_3d",                       # file OUT_DIR/<name>.exr
   "node": "ShaderNodeTexNoise",             # bl_idname of the node under test
   "properties": {"noise_dimensions": "3D"}, # node attributes set before linking
   "inputs": {"Scale": 5.0, "W": 0.3},       # unlinked input values (by name or index "#2")
   "vector": "Vector",                       # input fed the hit point's Object coordinate (or null)
   "output": "Color",                        # output (name or "#index") shown by the Emission
   "output_values": {"#0": [0, 0, 1]},       # optional: output sockets' default_value (the
                                             # Normal node's direction)
   "vector_scale": 4.0,                      # optional: the coordinate times this (Vector Math
                                             # SCALE) before it reaches the input
   "object": {"location": [0, 0, 0.5],       # optional: the plane object's transform (Euler XYZ
              "rotation": [0.3, 0, 0],       # radians); the case then gets its own coordinate
              "scale": [1, 2, 1]}}           # image OUT_DIR/<name>_coords.exr
Optional keys for the image, object and camera nodes (absent, nothing changes):
  "image": {"file": "tex.png",               # the node's image, relative to the manifest's folder
            "colorspace": "sRGB",            # colorspace_settings.name
            "alpha_mode": "STRAIGHT"}        # or {"generated": "COLOR_GRID", "size": [16, 8]}
  "object": {..., "name": "Würfel", "pass_index": 3, "color": [r, g, b, a]}
  "material": {"pass_index": 2}             # the plane material's pass index
  "output_add": [1, 1, 1]                    # added (Vector Math ADD) to the output before the
                                             # Emission, so negative components show
  "strength_output": "Alpha"                 # a second output of the node drives the Emission's
                                             # Strength (the image shows output x that one)
Ramp and curve nodes take their data from an optional "setup" (see _setup_data):
  "setup": {"color_ramp": {"interpolation": "EASE", "color_mode": "HSV",
                           "hue_interpolation": "FAR", "elements": [[0.1, [r, g, b, a]], ...]},
            "mapping": {"extend": "EXTRAPOLATED",
                        "curves": [[[x, y, "AUTO"], ...], ...]}}   # per curve, None = keep
A manifest-level "mesh" replaces the plane (same plane, same extent) by a jittered triangle grid
carrying attributes for the attribute nodes (see _attribute_mesh), and writes OUT_DIR/mesh.txt:
its vertices, triangles and every attribute's values per triangle corner, as Blender holds them:
  "mesh": {"grid": 7, "jitter": 0.1, "uv_maps": ["Second"], "render_color": "Col",
           "attributes": [{"name": "Col", "type": "BYTE_COLOR", "domain": "CORNER"}, ...]}
Every render also writes OUT_DIR/coords.exr: the Object coordinate of each pixel's hit point plus
(4, 4, 4), so tests can evaluate a node at exactly the point the render shaded (Emission colours
stay positive). The plane spans x, y in [-1, 1] with z = 0.3 x + 0.2 y + 0.25.

A case this Blender cannot build (its node type, a property, an enum value or a named input does
not exist here: Musgrave and Separate RGB are gone in 4.x, Gabor is new in 4.3) is not rendered;
OUT_DIR/<name>.skip then says why, and the conformance suite skips the case for this Blender.
A manifest may say "min_blender": [4, 1]: older Blenders skip all of its cases that way.

World cases ("world": true) render the node through the world's Background (strength 1) seen by
an equirectangular panoramic camera with nothing in the scene, at "resolution": [w, h] (default
64 x 32); "camera": {"latitude_min": ..., "longitude_max": ..., ...} narrows the panorama (to look
at a sun disc) and "camera_rotation": [x, y, z] (radians) turns the camera. Each world case also
writes OUT_DIR/<name>.coords.exr: every pixel's world ray direction plus (4, 4, 4).
"""

import json
import os
import sys

import bpy

RESOLUTION = 64
COORD_OFFSET = 4.0
MANIFEST_DIR = "."


def _argv():
    argv = sys.argv
    return argv[argv.index("--") + 1:] if "--" in argv else []


def _socket(sockets, key):
    if isinstance(key, str) and key.startswith("#"):
        return sockets[int(key[1:])]
    found = [s for s in sockets if s.name == key and s.enabled]
    # A hidden socket of that name (4.x's sockets["name"] no longer finds unavailable ones).
    found = found or [s for s in sockets if s.name == key]
    return found[0] if found else sockets[key]


def _scene(engine):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if engine != 'CYCLES':  # factory settings disable add-ons: enable the engine's again
        import addon_utils
        addon_utils.enable(engine.lower(), default_set=True)
    scene = bpy.context.scene
    scene.render.engine = engine
    scene.render.resolution_x = scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.render.image_settings.color_mode = 'RGB'
    scene.view_settings.view_transform = 'Standard'
    scene.view_settings.look = 'None'
    if hasattr(scene, "cycles"):  # Cycles' Film, which Photon reads too: a Box filter
        scene.cycles.pixel_filter_type = 'BOX'
        scene.cycles.filter_width = 0.01
    if engine == 'CYCLES':
        scene.cycles.samples = 1
        scene.cycles.use_denoising = False
        scene.cycles.max_bounces = 0
    if engine == 'PHOTON':  # direct emission only, one sample per pixel
        scene.photon.integrator = 'RAY_TRACE'
        scene.photon.samples = 1
        scene.photon.filter_width = 0.01  # Photon's Box width: pixel centres, as the references
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    mesh = bpy.data.meshes.new("plane")
    corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
    mesh.from_pydata([(x, y, 0.3 * x + 0.2 * y + 0.25) for x, y in corners], [],
                     [(0, 1, 2, 3)])
    mesh.uv_layers.new(name="UVMap")
    plane = bpy.data.objects.new("plane", mesh)
    scene.collection.objects.link(plane)
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = 'ORTHO'
    cam_data.ortho_scale = 2.0
    cam_data.clip_start, cam_data.clip_end = 0.1, 100.0
    camera = bpy.data.objects.new("camera", cam_data)
    camera.location = (0.0, 0.0, 10.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    return scene, plane


def _hash(i, seed):
    """A deterministic value in [0, 1) per element."""
    x = (i * 2654435761 + seed * 40503) & 0xFFFFFFFF
    x ^= x >> 13
    x = (x * 1274126177) & 0xFFFFFFFF
    return (x ^ (x >> 16)) / 4294967296.0


_ATTRIBUTE_PROPS = {'FLOAT': ("value", 1), 'FLOAT2': ("vector", 2), 'FLOAT_VECTOR': ("vector", 3),
                    'FLOAT_COLOR': ("color", 4), 'BYTE_COLOR': ("color", 4),
                    'INT': ("value", 1), 'BOOLEAN': ("value", 1)}


def _attribute_mesh(spec):
    """The plane as a grid of spec["grid"]^2 cells of two triangles (diagonals alternating),
    interior vertices jittered within the plane, with the spec's UV maps and attributes filled
    with hashed values (colours up to 2, vectors in [-0.25, 0.75))."""
    import numpy as np
    n, jitter = spec.get("grid", 7), spec.get("jitter", 0.1)
    verts, faces = [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = -1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n
            if 0 < i < n and 0 < j < n:
                x += (_hash(j * 131 + i, 1) - 0.5) * jitter
                y += (_hash(j * 131 + i, 2) - 0.5) * jitter
            verts.append((x, y, 0.3 * x + 0.2 * y + 0.25))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            faces += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
    mesh = bpy.data.meshes.new("attribute_grid")
    mesh.from_pydata(verts, [], faces)
    mesh.uv_layers.new(name="UVMap")
    for k, name in enumerate(spec.get("uv_maps", [])):
        layer = mesh.uv_layers.new(name=name)
        values = []
        for loop in mesh.loops:
            x, y, _ = verts[loop.vertex_index]
            offset = 0.1 * _hash(loop.index, 20 + k)  # per corner: not a point attribute
            values += [0.4 * x + 0.3 * y + 0.5 + offset, -0.5 * x + 0.45 * y + 0.5]
        layer.data.foreach_set("uv", values)
    mesh.uv_layers.active = mesh.uv_layers["UVMap"]
    for k, attr in enumerate(spec.get("attributes", [])):
        kind, domain = attr["type"], attr["domain"]
        if kind in ('FLOAT_COLOR', 'BYTE_COLOR'):
            layer = mesh.color_attributes.new(attr["name"], kind, domain)
        else:
            layer = mesh.attributes.new(attr["name"], kind, domain)
        prop, comps = _ATTRIBUTE_PROPS[kind]
        count = len(layer.data) * comps
        if kind in ('FLOAT_COLOR',):
            values = [2.0 * _hash(e, 40 + k) for e in range(count)]
        elif kind == 'BYTE_COLOR':
            values = [_hash(e, 40 + k) for e in range(count)]
        elif kind == 'INT':
            values = [int(_hash(e, 40 + k) * 10) for e in range(count)]
        elif kind == 'BOOLEAN':
            values = [_hash(e, 40 + k) < 0.5 for e in range(count)]
        else:
            values = [_hash(e, 40 + k) - 0.25 for e in range(count)]
        layer.data.foreach_set(prop, values)
    if spec.get("render_color"):
        names = [a.name for a in mesh.color_attributes]
        mesh.color_attributes.render_color_index = names.index(spec["render_color"])
        mesh.color_attributes.active_color = mesh.color_attributes[
            [a for a in names if a != spec["render_color"]][0] if len(names) > 1 else 0]
    return mesh


def _write_mesh(mesh, path):
    """Vertices, loop triangles and each UV map / attribute per triangle corner (float32 values
    as Blender reads them back) for the C++ conformance test."""
    import numpy as np
    mesh.calc_loop_triangles()
    tris = [tuple(t.vertices) for t in mesh.loop_triangles]
    loops = np.array([i for t in mesh.loop_triangles for i in t.loops])
    points = np.array([i for t in tris for i in t])
    faces = np.repeat([t.polygon_index for t in mesh.loop_triangles], 3)
    lines = [f"vertices {len(mesh.vertices)}"]
    lines += [" ".join(repr(float(c)) for c in v.co) for v in mesh.vertices]
    lines += [f"triangles {len(tris)}"] + [" ".join(map(str, t)) for t in tris]
    layers = [(uv.name, 'CORNER', uv.data, "uv", 2) for uv in mesh.uv_layers]
    for attr in mesh.attributes:
        if attr.data_type in _ATTRIBUTE_PROPS and attr.domain in ('POINT', 'CORNER', 'FACE') \
                and not attr.name.startswith("."):
            layers.append((attr.name, attr.domain, attr.data) + _ATTRIBUTE_PROPS[attr.data_type])
    render = mesh.color_attributes[mesh.color_attributes.render_color_index] \
        if len(mesh.color_attributes) else None
    for name, domain, data, prop, comps in layers:
        if any(name == uv.name for uv in mesh.uv_layers) and prop != "uv":
            continue  # 3.4 lists UV maps among attributes too
        values = np.empty(len(data) * comps, dtype=np.float32)
        data.foreach_get(prop, values)
        values = values.reshape(-1, comps)
        index = {'CORNER': loops, 'POINT': points, 'FACE': faces}[domain]
        tag = " render_color" if render is not None and name == render.name else ""
        lines.append(f"attribute {name} {comps}{tag}")
        lines += [" ".join(repr(float(c)) for c in row) for row in values[index]]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def _setup_data(node, setup):
    """Colour ramp elements and curve-mapping points, which node attributes cannot set."""
    ramp_setup = setup.get("color_ramp")
    if ramp_setup:
        ramp = node.color_ramp
        for name in ("color_mode", "hue_interpolation", "interpolation"):
            if name in ramp_setup:
                setattr(ramp, name, ramp_setup[name])
        elements = ramp_setup.get("elements", [])
        if elements:
            while len(ramp.elements) > 1:
                ramp.elements.remove(ramp.elements[-1])
            ramp.elements[0].position, ramp.elements[0].color = elements[0]
            for position, color in elements[1:]:
                ramp.elements.new(position).color = color
    map_setup = setup.get("mapping")
    if map_setup:
        mapping = node.mapping
        if "extend" in map_setup:
            mapping.extend = map_setup["extend"]
        for curve, points in zip(mapping.curves, map_setup.get("curves", [])):
            if points is None:
                continue
            while len(curve.points) > 2:
                curve.points.remove(curve.points[-1])
            ends = (points[0], points[-1])
            for point, (x, y, handle) in zip(curve.points, ends):
                point.location, point.handle_type = (x, y), handle
            for x, y, handle in points[1:-1]:
                curve.points.new(x, y).handle_type = handle
        mapping.update()


def _image(spec):
    """The image of an "image" case key: a file beside the manifest or a generated image."""
    if "generated" in spec:
        width, height = spec.get("size", (16, 8))
        image = bpy.data.images.new("generated", width, height, alpha=True,
                                    float_buffer=spec.get("float", False))
        image.generated_type = spec["generated"]
    else:
        image = bpy.data.images.load(os.path.join(MANIFEST_DIR, spec["file"]))
    if "colorspace" in spec:
        image.colorspace_settings.name = spec["colorspace"]
    if "alpha_mode" in spec:
        image.alpha_mode = spec["alpha_mode"]
    return image


def _material(case):
    mat = bpy.data.materials.new(case["name"])
    mat.pass_index = case.get("material", {}).get("pass_index", 0)
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    emission = tree.nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    tree.links.new(emission.outputs[0], out.inputs["Surface"])
    coords = tree.nodes.new("ShaderNodeTexCoord")
    if case.get("node") is None:  # the coordinate image
        add = tree.nodes.new("ShaderNodeVectorMath")
        add.operation = 'ADD'
        add.inputs[1].default_value = (COORD_OFFSET,) * 3
        tree.links.new(coords.outputs["Object"], add.inputs[0])
        tree.links.new(add.outputs[0], emission.inputs["Color"])
        return mat
    node = tree.nodes.new(case["node"])
    for name, value in case.get("properties", {}).items():
        setattr(node, name, value)
    _setup_data(node, case.get("setup", {}))
    if "image" in case:
        node.image = _image(case["image"])
    for name, value in case.get("inputs", {}).items():
        _socket(node.inputs, name).default_value = value
    for name, value in case.get("output_values", {}).items():
        _socket(node.outputs, name).default_value = value
    vector = case.get("vector", "Vector")
    if vector is not None:
        source = coords.outputs["Object"]
        if case.get("vector_scale") is not None:
            scale = tree.nodes.new("ShaderNodeVectorMath")
            scale.operation = 'SCALE'
            scale.inputs["Scale"].default_value = case["vector_scale"]
            tree.links.new(source, scale.inputs[0])
            source = scale.outputs["Vector"]
        tree.links.new(source, _socket(node.inputs, vector))
    output = _socket(node.outputs, case.get("output", "#0"))
    if case.get("output_add") is not None:
        add = tree.nodes.new("ShaderNodeVectorMath")
        add.operation = 'ADD'
        add.inputs[1].default_value = case["output_add"]
        tree.links.new(output, add.inputs[0])
        output = add.outputs[0]
    tree.links.new(output, emission.inputs["Color"])
    if case.get("strength_output") is not None:
        tree.links.new(_socket(node.outputs, case["strength_output"]),
                       emission.inputs["Strength"])
    return mat


def _world_nodes(case, scene):
    """The world shows the case's node (or, with no node, the ray direction + 4)."""
    world = scene.world
    world.use_nodes = True
    tree = world.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputWorld")
    background = tree.nodes.new("ShaderNodeBackground")
    background.inputs["Strength"].default_value = 1.0
    tree.links.new(background.outputs[0], out.inputs["Surface"])
    coords = tree.nodes.new("ShaderNodeTexCoord")
    if case.get("node") is None:  # in a world shader, Object is the ray direction
        add = tree.nodes.new("ShaderNodeVectorMath")
        add.operation = 'ADD'
        add.inputs[1].default_value = (COORD_OFFSET,) * 3
        tree.links.new(coords.outputs["Object"], add.inputs[0])
        tree.links.new(add.outputs[0], background.inputs["Color"])
        return
    node = tree.nodes.new(case["node"])
    for name, value in case.get("properties", {}).items():
        setattr(node, name, value)
    for name, value in case.get("inputs", {}).items():
        _socket(node.inputs, name).default_value = value
    vector = case.get("vector")
    if vector is not None:
        tree.links.new(coords.outputs["Object"], _socket(node.inputs, vector))
    tree.links.new(_socket(node.outputs, case.get("output", "#0")), background.inputs["Color"])


def _world_camera(case, scene, plane):
    bpy.data.objects.remove(plane)
    scene.render.resolution_x, scene.render.resolution_y = case.get("resolution", (64, 32))
    cam_data = scene.camera.data
    cam_data.type = 'PANO'
    # Blender 3.4 keeps the panorama settings in Cycles' camera properties.
    settings = cam_data.cycles if hasattr(cam_data, "cycles") and hasattr(
        cam_data.cycles, "panorama_type") else cam_data
    settings.panorama_type = 'EQUIRECTANGULAR'
    for name, value in case.get("camera", {}).items():
        setattr(settings, name, value)
    scene.camera.rotation_euler = case.get("camera_rotation", (0.0, 0.0, 0.0))


def unavailable(case):
    """Why this Blender cannot build `case` (None when it can): a node type, property, enum value
    or input socket the case names that does not exist here."""
    node_type = case.get("node")
    if node_type is None:
        return None
    rna = getattr(bpy.types, node_type, None)
    if rna is None:
        return f"{node_type} does not exist in Blender {bpy.app.version_string}"
    props = rna.bl_rna.properties
    for name, value in case.get("properties", {}).items():
        if name not in props:
            return f"{node_type}.{name} does not exist in Blender {bpy.app.version_string}"
        prop = props[name]
        if prop.type == 'ENUM' and isinstance(value, str) and \
                value not in {item.identifier for item in prop.enum_items}:
            return f"{node_type}.{name} has no '{value}' in Blender {bpy.app.version_string}"
    tree = bpy.data.node_groups.new("probe", 'ShaderNodeTree')
    try:
        node = tree.nodes.new(node_type)
        for name, value in case.get("properties", {}).items():
            setattr(node, name, value)
        names = list(case.get("inputs", {}))
        if case.get("vector", "Vector") is not None:
            names.append(case.get("vector", "Vector"))
        for name in names:
            try:
                _socket(node.inputs, name)
            except (KeyError, IndexError):
                return f"{node_type} has no input '{name}' in Blender {bpy.app.version_string}"
        for key in ("output", "strength_output"):
            if case.get(key) is not None:
                try:
                    _socket(node.outputs, case[key])
                except (KeyError, IndexError):
                    return (f"{node_type} has no output '{case[key]}' in Blender "
                            f"{bpy.app.version_string}")
    finally:
        bpy.data.node_groups.remove(tree)
    return None


def render(case, engine, out_dir, mesh_spec=None):
    scene, plane = _scene(engine)
    if mesh_spec and not case.get("world"):
        old = plane.data
        plane.data = _attribute_mesh(mesh_spec)
        bpy.data.meshes.remove(old)
    if case.get("world"):
        _world_camera(case, scene, plane)
        _world_nodes({"node": None}, scene)
        scene.render.filepath = os.path.join(out_dir, case["name"] + ".coords.exr")
        bpy.ops.render.render(write_still=True)
        _world_nodes(case, scene)
    else:
        transform = case.get("object")
        if transform:
            plane.location = transform.get("location", (0.0, 0.0, 0.0))
            plane.rotation_euler = transform.get("rotation", (0.0, 0.0, 0.0))
            plane.scale = transform.get("scale", (1.0, 1.0, 1.0))
            if "name" in transform:
                plane.name = transform["name"]
            plane.pass_index = transform.get("pass_index", 0)
            if "color" in transform:
                plane.color = transform["color"]
        plane.data.materials.append(_material(case))
    scene.render.filepath = os.path.join(out_dir, case["name"] + ".exr")
    bpy.ops.render.render(write_still=True)


def main():
    global MANIFEST_DIR
    args = _argv()
    manifest, out_dir = args[0], args[1]
    MANIFEST_DIR = os.path.dirname(os.path.abspath(manifest))
    engine = args[args.index("--engine") + 1] if "--engine" in args else 'CYCLES'
    only = set(args[args.index("--cases") + 1].split(",")) if "--cases" in args else None
    with open(manifest) as f:
        data = json.load(f)
    cases, mesh_spec = data["cases"], data.get("mesh")
    os.makedirs(out_dir, exist_ok=True)
    render({"name": "coords", "node": None}, engine, out_dir, mesh_spec)
    if mesh_spec:
        _write_mesh(_attribute_mesh(mesh_spec), os.path.join(out_dir, "mesh.txt"))
    too_old = tuple(bpy.app.version[:2]) < tuple(data.get("min_blender", (0, 0)))
    for case in cases:
        if only is None or case["name"] in only:
            skip_file = os.path.join(out_dir, case["name"] + ".skip")
            reason = (f"needs Blender {'.'.join(map(str, data['min_blender']))} or newer"
                      if too_old else unavailable(case))
            if reason is not None:
                print(f"node_refs: skipping {case['name']}: {reason}")
                with open(skip_file, "w") as f:
                    f.write(reason + "\n")
                continue
            if os.path.exists(skip_file):
                os.remove(skip_file)
            try:
                if case.get("object"):  # the transformed plane's own coordinate image
                    render({"name": case["name"] + "_coords", "node": None,
                            "object": case["object"]}, engine, out_dir, mesh_spec)
                render(case, engine, out_dir, mesh_spec)
            except Exception:  # one broken case leaves no image; the others still render
                import traceback
                print(f"node_refs: {case['name']} failed:")
                traceback.print_exc()


if __name__ == "__main__":
    main()
