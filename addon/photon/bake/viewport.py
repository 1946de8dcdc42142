"""Switches 3D viewports to show baked lighting, and back.

Colour attribute: Solid shading, Color = Attribute (the mesh's active colour attribute, set to
PhotonLighting), Lighting = Flat, so what is drawn is the baked radiance (through the scene's
view transform). Lightmaps: Solid shading, Color = Texture, Lighting = Flat; Workbench draws the
image of each material's active Image Texture node with the mesh's active UV map, so every
material of a baked object gets an unconnected "PhotonLightmap" node (renders are unchanged)
made active, and the lightmap UV map is made active (the previous one is restored by RESTORE).

The previous shading of every 3D view is kept on the scene (in all screens, so it works in
background mode too) and RESTORE puts it back.
"""

import json

import bpy

from .job import ATTRIBUTE, LIGHTMAP_PROPERTY

BACKUP = "photon_viewport_backup"      # scene property: JSON {view key: shading}
PREVIOUS_UV = "photon_previous_active_uv"  # mesh property: active UV map before LIGHTMAP
NODE_NAME = "PhotonLightmap"


def _views():
    for screen in bpy.data.screens:
        for index, area in enumerate(screen.areas):
            if area.type != 'VIEW_3D':
                continue
            for space in area.spaces:
                if space.type == 'VIEW_3D':
                    yield f"{screen.name}:{index}", space.shading


def _activate_attributes(scene):
    baked = 0
    for obj in scene.objects:
        if obj.type != 'MESH':
            continue
        attribute = obj.data.color_attributes.get(ATTRIBUTE)
        if attribute is not None:
            obj.data.color_attributes.active_color = attribute
            baked += 1
    return baked


def _activate_lightmaps(scene, reporter):
    baked = 0
    material_owner = {}
    uv_name = scene.photon.lightmap_uv_name
    for obj in scene.objects:
        image = bpy.data.images.get(obj.get(LIGHTMAP_PROPERTY, "")) if obj.type == 'MESH' else None
        if image is None:
            continue
        mesh = obj.data
        layer = mesh.uv_layers.get(uv_name)
        if layer is None:
            reporter.warning(f"Object '{obj.name}': UV map '{uv_name}' is gone; lightmap not shown")
            continue
        if mesh.uv_layers.active is not None and mesh.uv_layers.active.name != uv_name:
            mesh[PREVIOUS_UV] = mesh.uv_layers.active.name
        mesh.uv_layers.active = layer
        materials = [slot.material for slot in obj.material_slots if slot.material is not None]
        if not materials:
            reporter.warning(f"Object '{obj.name}' has no material: Workbench shows textures "
                             f"through materials, so its lightmap is not shown")
            continue
        for material in materials:
            owner = material_owner.setdefault(material.name, obj.name)
            if owner != obj.name:
                reporter.warning(f"Material '{material.name}' is shared by '{owner}' and "
                                 f"'{obj.name}': it shows the lightmap of '{owner}' only")
                continue
            if not material.use_nodes:
                material.use_nodes = True
            nodes = material.node_tree.nodes
            node = nodes.get(NODE_NAME)
            if node is None or node.bl_idname != "ShaderNodeTexImage":
                node = nodes.new("ShaderNodeTexImage")
                node.name = node.label = NODE_NAME
                node.location = (-600, -400)
            node.image = image
            node.interpolation = 'Linear'
            nodes.active = node
        baked += 1
    return baked


def show(context, mode, reporter):
    """Returns the number of 3D views switched."""
    scene = context.scene
    baked = _activate_lightmaps(scene, reporter) if mode == "LIGHTMAP" else \
        _activate_attributes(scene)
    if baked == 0:
        what = "lightmaps" if mode == "LIGHTMAP" else f"'{ATTRIBUTE}' color attributes"
        reporter.warning(f"No object has baked {what} yet: run Bake Lighting first")
    backup = json.loads(scene.get(BACKUP, "{}"))
    count = 0
    for key, shading in _views():
        backup.setdefault(key, {"type": shading.type, "light": shading.light,
                                "color_type": shading.color_type})
        shading.type = 'SOLID'
        shading.light = 'FLAT'
        shading.color_type = 'TEXTURE' if mode == "LIGHTMAP" else 'VERTEX'
        count += 1
    scene[BACKUP] = json.dumps(backup)
    return count


def restore(context):
    scene = context.scene
    backup = json.loads(scene.get(BACKUP, "{}"))
    count = 0
    for key, shading in _views():
        saved = backup.get(key)
        if saved is None:
            continue
        shading.type = saved["type"]
        shading.light = saved["light"]
        shading.color_type = saved["color_type"]
        count += 1
    if BACKUP in scene:
        del scene[BACKUP]
    for obj in scene.objects:
        mesh = obj.data if obj.type == 'MESH' else None
        if mesh is not None and PREVIOUS_UV in mesh:
            layer = mesh.uv_layers.get(mesh[PREVIOUS_UV])
            if layer is not None:
                mesh.uv_layers.active = layer
            del mesh[PREVIOUS_UV]
    return count
