"""Regenerates the committed test scenes (and, with --references, their Photon reference EXRs).

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \
        -P test_scenes/make_scenes.py -- [--references]
"""

import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import builders  # noqa: E402

SCENES = {
    "cornell_box": builders.cornell_box,
}


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    render_references = "--references" in argv
    for name, build in SCENES.items():
        scene = build()
        path = os.path.join(HERE, f"{name}.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
        print(f"wrote {path}")
        if render_references:
            scene.render.filepath = os.path.join(HERE, f"{name}.exr")
            scene.render.use_file_extension = False
            bpy.ops.render.render(write_still=True)
            print(f"wrote {scene.render.filepath}")


main()
