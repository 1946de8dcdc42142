"""Renders the open .blend with an iterative Photon integrator at several iteration counts in one
Blender process (each count a render of its own, as a user's would be). Args: out_prefix,
integrator (SPPM or VCM), photons per iteration, resolution percentage, counts... Returns
{"renders": [{"iterations", "path", "seconds"}]}: the EXR written and the render's wall time
(scene sync included)."""

import time

import bpy

from harness import run


def main(out_prefix, integrator, photons, percentage, *counts):
    scene = bpy.context.scene
    scene.render.engine = 'PHOTON'
    scene.render.resolution_percentage = int(percentage)
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    photon = scene.photon
    photon.integrator = integrator
    # Each integrator's own budget: photons (SPPM) or light paths (VCM) per iteration.
    prefix, paths = ("vcm_", "light_paths") if integrator == "VCM" else ("sppm_",
                                                                         "photons_per_iteration")
    setattr(photon, prefix + paths, int(photons))
    renders = []
    for count in map(int, counts):
        setattr(photon, prefix + "iterations", count)
        scene.render.filepath = f"{out_prefix}{count}.exr"
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        renders.append({"iterations": count, "path": scene.render.filepath,
                        "seconds": time.perf_counter() - t0})
    return {"renders": renders}


run(main)
