"""Runs inside Blender: renders the open .blend several times with the settings given, timing
each render, for the benchmark scripts (convergence_curves.py).

    blender -b --factory-startup --addons photon FILE.blend -P tests/bench/render_series.py \\
        -- SPEC.json RESULT.json

SPEC.json is a list of {"engine": "PHOTON" or "CYCLES", "settings": {"photon.NAME": value,
"cycles.NAME": value, "render.NAME": value}, "out": "path.exr"}. RESULT.json receives, per
render, the spec plus "seconds": the wall time of bpy.ops.render.render (scene sync and the
render; not Blender's start-up or the file load).
"""

import json
import sys
import time

import bpy


def apply(scene, settings):
    for key, value in settings.items():
        group, name = key.split(".", 1)
        setattr(getattr(scene, group), name, value)


def main():
    spec_path, result_path = sys.argv[sys.argv.index("--") + 1:][:2]
    with open(spec_path) as f:
        spec = json.load(f)
    scene = bpy.context.scene
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    results = []
    for item in spec:
        scene.render.engine = item["engine"]
        apply(scene, item.get("settings", {}))
        scene.render.filepath = item["out"]
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        results.append(dict(item, seconds=time.perf_counter() - t0))
        print(f"render_series: {item['engine']} {item.get('settings')} "
              f"{results[-1]['seconds']:.2f} s", flush=True)
        with open(result_path, "w") as f:
            json.dump(results, f, indent=1)


main()
