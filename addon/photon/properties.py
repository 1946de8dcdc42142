"""Render settings stored on the scene as scene.photon."""

import bpy
from bpy.props import EnumProperty, IntProperty, PointerProperty


class PhotonRenderSettings(bpy.types.PropertyGroup):
    integrator: EnumProperty(
        name="Integrator",
        description="Rendering algorithm",
        items=[
            ("RAY_TRACE", "Ray Tracing",
             "Whitted ray tracing: direct light, perfect mirrors and glass"),
        ],
        default="RAY_TRACE",
    )
    samples: IntProperty(
        name="Samples", description="Camera samples per pixel",
        default=16, min=1, soft_max=4096, max=1 << 20)
    max_depth: IntProperty(
        name="Max Depth", description="Maximum number of mirror and glass bounces",
        default=8, min=0, soft_max=64, max=1024)
    seed: IntProperty(
        name="Seed", description="Random seed; the same seed renders the same image",
        default=0, min=0)
    threads: IntProperty(
        name="Threads", description="Render threads (0 = all cores)",
        default=0, min=0, soft_max=256)
    tile_size: IntProperty(
        name="Tile Size", description="Width and height of the render tiles in pixels",
        default=64, min=8, max=4096, subtype="PIXEL")


def register():
    bpy.utils.register_class(PhotonRenderSettings)
    bpy.types.Scene.photon = PointerProperty(type=PhotonRenderSettings)


def unregister():
    del bpy.types.Scene.photon
    bpy.utils.unregister_class(PhotonRenderSettings)
