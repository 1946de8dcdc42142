"""Lists the Properties-editor panels shown for the PHOTON engine, by context, for
test_panels.py: (class name, label, parent, order) of every panel whose COMPAT_ENGINES has
PHOTON."""

import json
import sys

import bpy

result_path = sys.argv[sys.argv.index("--") + 1]
panels = {}
for panel in bpy.types.Panel.__subclasses__():
    engines = getattr(panel, "COMPAT_ENGINES", None)
    if not engines or "PHOTON" not in engines or \
            getattr(panel, "bl_space_type", "") != "PROPERTIES":
        continue
    panels.setdefault(getattr(panel, "bl_context", ""), []).append(
        [panel.__name__, getattr(panel, "bl_label", ""), getattr(panel, "bl_parent_id", ""),
         getattr(panel, "bl_order", 0)])
with open(result_path, "w") as f:
    json.dump(panels, f)
