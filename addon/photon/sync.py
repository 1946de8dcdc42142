"""Builds a native scene from Blender's evaluated depsgraph (Blender types stop here)."""

import time

import numpy as np

from . import sync_camera, sync_lights, sync_materials, sync_mesh


class SyncStats:
    def __init__(self):
        self.meshes = 0
        self.instances = 0
        self.triangles = 0
        self.lights = 0
        self.seconds = 0.0
        self._release = []

    def release(self):
        """Frees what the render needed until its end (textures written to a temp folder)."""
        for release in self._release:
            release()
        self._release = []


def sync_scene(native, depsgraph, reporter, object_instances=None):
    """Returns (native Scene, SyncStats); call stats.release() once the render has ended.

    When `object_instances` is a dict it is filled with object name -> list of native instance
    indices (Scene.instances) of the object's own geometry, not of instances it generates
    (particles, collection instances); lighting bakes use it to address surface points.
    """
    stats = SyncStats()
    try:
        return _sync(native, depsgraph, reporter, stats, object_instances), stats
    except BaseException:
        stats.release()
        raise


def _sync(native, depsgraph, reporter, stats, object_instances):
    t0 = time.perf_counter()
    scene = depsgraph.scene
    native_scene = native.Scene()
    materials = sync_materials.MaterialTable(native_scene, reporter,
                                             getattr(native, "TexturePixels", None))
    stats._release.append(materials.release)

    mesh_index = {}        # data identity -> native mesh index (None: no triangles)
    pending = {}           # (mesh index, slot tuple, visibility) -> [(4x4 matrix, owner or None)]
    unsupported = {}       # object type -> object names

    for inst in depsgraph.object_instances:
        # Instance items die when iteration moves on: use them only inside this body.
        obj = inst.object
        obj_type = obj.type
        if obj_type == 'LIGHT':
            if sync_lights.export_light(native, native_scene, obj, inst.matrix_world, reporter):
                stats.lights += 1
            continue
        if obj_type in sync_mesh.UNSUPPORTED_GEOMETRY_TYPES:
            unsupported.setdefault(obj_type, set()).add(obj.name)
            continue
        if not sync_mesh.is_geometry(obj):
            continue
        if not inst.is_instance and not inst.show_self:
            continue
        # The evaluated data block identifies shared geometry: every instance of one mesh
        # (particles, geometry nodes, linked duplicates) maps to one native mesh and one BVH.
        key = obj.data.as_pointer()
        if key not in mesh_index:
            index, triangles = sync_mesh.export_object_mesh(native_scene, obj, reporter)
            mesh_index[key] = index
            if index is not None:
                stats.meshes += 1
                stats.triangles += triangles
        index = mesh_index[key]
        if index is None:
            continue
        slots = tuple(materials.slot_indices(obj))
        visibility = sync_lights.visibility_bits(native, obj)
        owner = None if inst.is_instance else obj.name
        pending.setdefault((index, slots, visibility), []).append(
            (np.asarray(inst.matrix_world, dtype=np.float32), owner))

    for (index, slots, visibility), entries in pending.items():
        first = native_scene.instance_count
        stats.instances += native_scene.add_instances(
            index, np.stack([matrix for matrix, _ in entries]), list(slots), visibility)
        if object_instances is not None:
            for offset, (_, owner) in enumerate(entries):
                if owner is not None:
                    object_instances.setdefault(owner, []).append(first + offset)

    for obj_type, names in sorted(unsupported.items()):
        shown = ", ".join(sorted(names)[:5]) + (" ..." if len(names) > 5 else "")
        reporter.warning(f"{obj_type.title()} objects are not supported yet and were skipped: "
                         f"{shown}")

    sync_camera.export_camera(native_scene, scene, depsgraph, reporter)
    world = sync_materials.world_color(scene.world, reporter,
                                       getattr(native, "MAX_EMISSION", None))
    native_scene.set_world(world)

    if stats.triangles == 0:
        reporter.warning("The scene has no renderable geometry")
    if stats.lights == 0 and max(world) <= 0.0:
        reporter.warning("The scene has no lights and a black world: only emissive surfaces will show")
    stats.seconds = time.perf_counter() - t0
    return native_scene
