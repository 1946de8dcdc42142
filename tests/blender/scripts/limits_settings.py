"""Sets scene.photon settings from `name=value` arguments after `--` (the rest of Blender's
command line then renders), and optionally bakes the lighting twice: `bake=1`."""

import bpy

import harness


def main():
    scene = bpy.context.scene
    bake = False
    for arg in harness.script_args():
        name, value = arg.split("=", 1)
        if name == "bake":
            bake = value == "1"
        elif name == "resolution":
            scene.render.resolution_x = scene.render.resolution_y = int(value)
            scene.render.resolution_percentage = 100
        else:
            setattr(scene.photon, name, type(getattr(scene.photon, name))(float(value)))
    print(f"limits_settings: threads property = {scene.photon.threads}", flush=True)
    if bake:
        for _ in range(2):
            print(f"limits_settings: bake {sorted(bpy.ops.photon.bake_lighting())}", flush=True)


main()
