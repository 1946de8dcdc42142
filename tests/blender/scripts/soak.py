"""Soak runs inside one Blender process, sampling the resident set size (VmRSS) as they go.

Args: RESULT_PATH MODE BLEND_PATH
  make    builds the animated scene (a small Cornell box whose camera, ball and lamp move over
          60 frames, 16 x 16 pixels, 1 sample) and saves it as BLEND_PATH;
  render  is run before `-a` on that file: a render_post handler prints one
          "Photon soak: frame N rss KB" line per frame (the test parses stdout, since `-a` runs
          after this script has returned);
  bake    runs photon.bake_lighting 30 times on the loaded file (colour attributes and
          lightmaps) and returns the RSS after every bake.
"""

import bpy

import builders
import harness

FRAMES = 60
BAKES = 30


def rss_kb():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS in /proc/self/status")


def make(blend_path):
    scene = builders.cornell_box(width=16, height=16, samples=1)
    scene.frame_start, scene.frame_end = 1, FRAMES
    settings = scene.photon
    # Enough native memory per frame (photon maps of ~1 MB, a 4k-triangle ball's BVH and
    # arrays) that keeping one frame's worth alive would show as several percent growth.
    settings.photons = 50000
    settings.caustic_photons = 10000
    settings.final_gather_rays = 2
    settings.bake_samples = 2
    settings.bake_target = 'BOTH'
    settings.lightmap_size = 16
    ball = builders.uv_sphere("Ball", (0.0, -0.3, 0.8), 0.2, segments=64, rings=32,
                              material=builders.diffuse_material("Ball", (0.2, 0.3, 0.9)))
    cam = scene.camera
    light = bpy.data.objects["CeilingLight"]
    builders.keyframe_motion(cam, ball, light, [(1, (-0.2, 0.3, 20.0)),
                                                (FRAMES, (0.2, 1.3, 80.0))])
    bpy.ops.wm.save_as_mainfile(filepath=blend_path)
    return {"saved": blend_path}


def watch_render():
    def report(scene, *_):
        print(f"Photon soak: frame {scene.frame_current} rss {rss_kb()}", flush=True)

    bpy.app.handlers.render_post.append(report)
    return {"watching": True}


def bake():
    rss, results = [], []
    for _ in range(BAKES):
        results.append(sorted(bpy.ops.photon.bake_lighting()))
        rss.append(rss_kb())
    return {"rss": rss, "results": results, "images": len(bpy.data.images)}


def main(mode, blend_path=None):
    if mode == "make":
        return make(blend_path)
    if mode == "render":
        return watch_render()
    return bake()


harness.run(main)
