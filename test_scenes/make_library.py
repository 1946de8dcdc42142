"""Writes the scene library: test_scenes/regression/NAME.blend and test_scenes/validation/
NAME.blend, each with its sidecar NAME.json (see library.py and docs/regression.md).

    BLENDER_USER_SCRIPTS=build/stage blender -b --factory-startup --addons photon \\
        -P test_scenes/make_library.py -- [--only NAME ...]

References are rendered afterwards by the regression tool:
    python3 tools/regress.py test_scenes/regression test_scenes/validation --update ...
"""

import inspect
import json
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import library  # noqa: E402


def script_args():
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def describe(build):
    """The builder's docstring as one line (the sidecar's default description)."""
    return " ".join((build.__doc__ or "").split())


def write_scene(name, folder_name, build, sidecar):
    folder = os.path.join(HERE, folder_name)
    os.makedirs(folder, exist_ok=True)
    takes_folder = bool(inspect.signature(build).parameters)
    scene = build(folder) if takes_folder else build()
    scene.name = "Scene"
    path = os.path.join(folder, f"{name}.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True, relative_remap=True)
    bpy.ops.file.make_paths_relative()  # textures as //textures/..., valid wherever the repo is
    bpy.ops.wm.save_mainfile(compress=True)
    if os.path.exists(path + "1"):  # the backup the second save leaves
        os.remove(path + "1")
    data = dict(sidecar(scene) if callable(sidecar) else sidecar)
    data.setdefault("description", describe(build))
    with open(os.path.join(folder, f"{name}.json"), "w") as f:
        json.dump(data, f, indent=2)
        f.write("\n")
    print(f"make_library: wrote {path}", flush=True)


def main():
    args = script_args()
    only = set(args[args.index("--only") + 1:]) if "--only" in args else None
    unknown = (only or set()) - set(library.SCENES)
    if unknown:
        raise SystemExit(f"make_library: unknown scene(s) {sorted(unknown)}; known: "
                         f"{', '.join(library.SCENES)}")
    for name, (folder, build, sidecar) in library.SCENES.items():
        if only is None or name in only:
            write_scene(name, folder, build, sidecar)


main()
