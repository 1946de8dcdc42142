"""Applies `name=value` edits to the open scene (the rest of Blender's command line renders):
scene.photon settings and resolution as limits_settings.py does, plus lights and the world:
  area_power=W     the area light 'CeilingLight' emits W watts (0 removes it)
  sun_strength=S   adds a sun 'Sun' of strength S W/m^2 shining down through the open front
  world_strength=S the world's Background strength (NaN allowed)
  passes=1         enables the Photon light passes
  half=1           EXR output in half floats (Blender's default depth is 32)"""

import math

import bpy

import harness


def add_sun(strength):
    data = bpy.data.lights.new("Sun", 'SUN')
    data.energy = strength
    data.angle = 0.0
    obj = bpy.data.objects.new("Sun", data)
    bpy.context.scene.collection.objects.link(obj)
    # From the camera's side, tilted so it lights the floor and the boxes through the open front.
    obj.rotation_euler = (math.radians(50.0), 0.0, 0.0)


def main():
    scene = bpy.context.scene
    for arg in harness.script_args():
        name, value = arg.split("=", 1)
        if name == "resolution":
            scene.render.resolution_x = scene.render.resolution_y = int(value)
            scene.render.resolution_percentage = 100
        elif name == "area_power":
            if float(value) == 0.0:
                bpy.data.objects.remove(bpy.data.objects["CeilingLight"])
            else:
                bpy.data.lights["CeilingLight"].energy = float(value)
        elif name == "sun_strength":
            add_sun(float(value))
        elif name == "world_strength":
            background = scene.world.node_tree.nodes["Background"]
            background.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1.0)
            background.inputs["Strength"].default_value = float(value)
            print(f"light_limits: world strength = "
                  f"{background.inputs['Strength'].default_value}", flush=True)
        elif name == "half":
            scene.render.image_settings.color_depth = '16' if value == "1" else '32'
        elif name == "passes":
            for pass_name in ("use_pass_direct", "use_pass_indirect", "use_pass_caustics",
                              "use_pass_photon_map"):
                setattr(bpy.context.view_layer.photon, pass_name, value == "1")
        else:
            setattr(scene.photon, name, type(getattr(scene.photon, name))(float(value)))


main()
