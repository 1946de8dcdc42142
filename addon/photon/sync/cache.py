"""Persistent Data (Render Properties > Performance): finished native meshes kept between the
frames of an animation, so meshes whose data did not change skip Blender's foreach_get reads and
the native gather and cleanup (their BVHs are kept natively, by BlasCache).

Blender keeps the engine and its depsgraph between frames when `render.use_persistent_data` is
on (checked in Blender 3.4.1: render() runs on the same engine object with the same depsgraph,
and `depsgraph.updates` then lists only what changed since the previous frame: an object moved
is `is_updated_transform` only; a shape key or an animated modifier makes its object
`is_updated_geometry`). A cached mesh is replayed only when neither its object's geometry nor
its mesh data block was updated AND its fingerprint (element counts and a hash of the vertex
positions) is unchanged, so a missed update cannot serve stale geometry. A replayed mesh is the
native mesh the same arrays made (moved into each frame's scene and back out after its render),
so the frame is the same bit for bit.
"""

import hashlib

import bpy
import numpy as np

from . import mesh as sync_mesh
from .origin import local_bounds


def _fingerprint(mesh):
    """Counts and a hash of the vertex positions of an evaluated mesh (a few ms per 1M
    triangles): the guard against an edit the depsgraph did not report."""
    count = len(mesh.vertices)
    positions = np.empty(count * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", positions)
    digest = hashlib.blake2b(positions, digest_size=16).digest()
    return (count, len(mesh.loops), len(mesh.polygons), len(mesh.materials), digest)


# The entry of a mesh whose data changed since the previous frame (animated geometry): not kept
# (its memory would be held for nothing if it changes again) until a frame finds it unchanged.
_CHANGED = "changed"


class MeshCache:
    """Per-engine cache: begin(depsgraph) before a sync, export() in place of
    sync_mesh.export_object_mesh, end() after it, and reclaim(scene) once the scene's renders
    are over."""

    def __init__(self):
        # (object name, data name, data pointer) -> (fingerprint, native KeptMesh, add_mesh
        # info, object-space bounds), or _CHANGED
        self._entries = {}
        self._owner = None  # (depsgraph pointer, view layer name) the entries came from
        self._used = set()
        self._lent = []     # KeptMeshes in the scene of the current sync
        self.reused = 0     # meshes of the current sync replayed from the cache
        self.exported = 0   # meshes of the current sync read from Blender

    def begin(self, depsgraph):
        owner = (depsgraph.as_pointer(), depsgraph.view_layer.name)
        if owner != self._owner:
            # Another depsgraph or view layer: its updates say nothing about these entries.
            self._entries.clear()
            self._owner = owner
        changed_objects, changed_data = set(), set()
        for update in depsgraph.updates:
            data = update.id
            if isinstance(data, bpy.types.Object):
                if update.is_updated_geometry:
                    changed_objects.add(data.name)
            elif isinstance(data, bpy.types.Mesh):
                changed_data.add(data.name)  # any update of the data block: normals, UVs ...
        entries = {}
        for key, entry in self._entries.items():
            if key[0] in changed_objects or key[1] in changed_data:
                entries[key] = _CHANGED
            elif entry is not _CHANGED:
                # (A _CHANGED mesh that did not change again is dropped: this frame keeps it.)
                entries[key] = entry
        self._entries = entries
        self._used = set()
        self._lent = []
        self.reused = self.exported = 0

    def export(self, native_scene, obj, reporter, attributes=(), on_missing=None):
        """As sync_mesh.export_object_mesh, from the cache when the mesh did not change."""
        data = obj.data
        key = (obj.name, data.name, data.as_pointer())
        entry = self._entries.get(key)
        # The attributes read are part of what must not have changed.
        fingerprint = (None if entry is _CHANGED else
                       _fingerprint(data) + (tuple(sorted(attributes)),))
        # A kept mesh still lent to an earlier scene (its render never handed it back) is read
        # again.
        if (entry is not None and entry is not _CHANGED and entry[0] == fingerprint
                and not entry[1].lent):
            _, kept, info, bounds = entry
            self.reused += 1
            # The native mesh as the first sync left it: the same a fresh sync would make.
            info = dict(info, index=native_scene.add_kept_mesh(kept))
            self._lent.append(kept)
        else:
            arrays = sync_mesh.object_mesh_arrays(obj, reporter, attributes)
            if arrays is None:
                self._entries.pop(key, None)
                return None, 0, (None, None)
            method, kwargs = arrays
            kwargs = dict(kwargs)
            texspace = kwargs.pop("texspace", None)
            attribute_arrays = kwargs.pop("attributes", None)
            info = getattr(native_scene, method)(obj.name, **kwargs)
            if texspace is not None and info["triangles"]:
                native_scene.set_mesh_texspace(info["index"], list(texspace[0]),
                                               list(texspace[1]))
            sync_mesh.add_attributes(native_scene, obj.name, info, attribute_arrays, reporter,
                                     on_missing)
            bounds = local_bounds(kwargs["positions"])
            if entry is not _CHANGED:
                kept = native_scene.keep_mesh(info["index"])
                self._entries[key] = (fingerprint, kept, info, bounds)
                self._lent.append(kept)
            self.exported += 1
        self._used.add(key)
        return sync_mesh.mesh_result(obj.name, info, bounds, reporter)

    def end(self):
        """Drops meshes this sync did not use (deleted or hidden objects): memory stays that of
        one frame."""
        self._entries = {key: entry for key, entry in self._entries.items()
                         if key in self._used}
        self._used = set()

    def reclaim(self, native_scene):
        """Takes the kept meshes back from `native_scene` once no render uses it (they are moved
        into a frame's scene, not copied)."""
        for kept in self._lent:
            native_scene.return_kept_mesh(kept)
        self._lent = []

    def __len__(self):
        return len(self._entries)
