"""Two small bright emitters seen straight on by an orthographic camera (1 Blender unit per
pixel) over a black world, rendered by Cycles and by Photon into EXRs in the folder given, so the
pixels around them show the pixel filter. Args: out_dir, samples. Cases (name: Cycles' Film
settings, read by both engines):
  default: Blackman-Harris 1.5 px, Cycles' defaults left untouched;
  gaussian: Gaussian 1.5 px;  box: Box (Cycles' width left at 1.5, which Cycles ignores);
  box2: Box with Photon's box width 2 (Photon only);
  exposure2: default filter, film exposure 2 (Photon only).
Returns {case: {"cycles": path, "photon": path}} (no "cycles" for the Photon-only cases) and
{"emitters": [(left, top, size) in pixels]}."""

import os

import bpy
from harness import run

SIZE = 32
# Emitters as (left, top, size) in pixels of the 32 x 32 frame: a one-pixel square off the
# pixel grid, and a quarter-pixel one (almost a point), each emitting ~1 per pixel it covers.
EMITTERS = ((9.3, 11.6, 1.0), (20.4, 19.8, 0.25))
CASES = {
    "default": {},
    "gaussian": {"pixel_filter_type": "GAUSSIAN", "filter_width": 1.5},
    # Cycles' Box is one pixel whatever its (hidden) width; Photon's Box width is its own.
    "box": {"pixel_filter_type": "BOX", "filter_width": 1.5},
    "box2": {"pixel_filter_type": "BOX", "photon_filter_width": 2.0},
    "exposure2": {"film_exposure": 2.0},
}
PHOTON_ONLY = ("box2", "exposure2")


def build(engine, samples, film):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if engine == 'PHOTON':
        import addon_utils
        addon_utils.enable("photon", default_set=True)
    scene = bpy.context.scene
    scene.render.engine = engine
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.view_settings.view_transform = 'Standard'
    for name, value in film.items():
        if name.startswith("photon_"):
            if engine == 'PHOTON':
                setattr(scene.photon, name[len("photon_"):], value)
        else:
            setattr(scene.cycles, name, value)
    if engine == 'CYCLES':
        scene.cycles.samples = samples
        scene.cycles.seed = 3
        scene.cycles.use_denoising = False
        scene.cycles.use_adaptive_sampling = False
        scene.cycles.max_bounces = 0
    else:
        scene.photon.integrator = 'RAY_TRACE'
        scene.photon.samples = samples
        scene.photon.max_depth = 0
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    if world.node_tree is not None:  # Blender 5.0+ gives a new world a grey Background node
        for node in world.node_tree.nodes:
            if node.type == 'BACKGROUND':
                node.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    scene.world = world
    mat = bpy.data.materials.new("emit")
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    out = nodes.new("ShaderNodeOutputMaterial")
    mat.node_tree.links.new(emission.outputs[0], out.inputs["Surface"])
    verts, faces = [], []
    for left, top, size in EMITTERS:
        # Frame pixel (px, py) from the top-left is world (px - 16, 16 - py).
        x0, y1 = left - SIZE / 2, SIZE / 2 - top
        x1, y0 = x0 + size, y1 - size
        base = len(verts)
        verts += [(x0, y0, 0.0), (x1, y0, 0.0), (x1, y1, 0.0), (x0, y1, 0.0)]
        faces.append((base, base + 1, base + 2, base + 3))
    mesh = bpy.data.meshes.new("emitters")
    mesh.from_pydata(verts, [], faces)
    mesh.materials.append(mat)
    scene.collection.objects.link(bpy.data.objects.new("emitters", mesh))
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = 'ORTHO'
    cam_data.ortho_scale = SIZE
    cam = bpy.data.objects.new("camera", cam_data)
    cam.location = (0.0, 0.0, 10.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    return scene


def main(out_dir, samples):
    result = {"emitters": EMITTERS}
    for case, film in CASES.items():
        result[case] = {}
        engines = ("PHOTON",) if case in PHOTON_ONLY else ("CYCLES", "PHOTON")
        for engine in engines:
            scene = build(engine, int(samples), film)
            path = os.path.join(out_dir, f"{case}_{engine.lower()}.exr")
            scene.render.filepath = path
            bpy.ops.render.render(write_still=True)
            result[case][engine.lower()] = path
    return result


if __name__ == "__main__":
    run(main)
