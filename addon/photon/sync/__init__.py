"""Blender's evaluated depsgraph into the native scene: scene.py walks the depsgraph and calls
one module per kind of data (mesh, hair, lights, camera, materials through their node graphs,
textures, mattes, view layers). Blender types stop here."""

from .scene import SyncStats, sync_scene  # noqa: F401
