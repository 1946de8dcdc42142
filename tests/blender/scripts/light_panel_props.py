"""Draws Photon's light panels for each light type into a layout that records what they show
(no window needed), for test_panels.py: the properties drawn, and any that the light lacks."""

import json
import sys

import bpy


class RecordingLayout:
    """Stands in for bpy.types.UILayout: records prop() calls; rows and columns record into
    the same list."""

    def __init__(self, shown):
        self.shown = shown
        self.use_property_split = self.use_property_decorate = self.active = True

    def prop(self, data, name, **_kwargs):
        self.shown.append([type(data).__name__, name, hasattr(data, name)])

    def row(self, **_kwargs):
        return self

    column = row

    def separator(self, **_kwargs):
        pass

    label = separator


class Context:
    def __init__(self, light):
        self.light = light


result_path = sys.argv[sys.argv.index("--") + 1]
found = {}
for light_type in ('POINT', 'SPOT', 'SUN', 'AREA'):
    light = bpy.data.lights.new(light_type.lower(), light_type)
    shown = []
    for name in ("PHOTON_PT_light", "PHOTON_PT_spot"):
        panel = getattr(bpy.types, name)
        if name == "PHOTON_PT_spot" and light_type != 'SPOT':
            continue
        holder = type("Holder", (), {"layout": RecordingLayout(shown)})()
        panel.draw(holder, Context(light))
    found[light_type] = shown
with open(result_path, "w") as f:
    json.dump({"version": list(bpy.app.version), "lights": found}, f)
