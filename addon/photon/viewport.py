"""Rendered shading in the 3D viewport, on the native ProgressiveSession
(session/progressive_session.h).

view_update sorts `depsgraph.updates` (Cycles' viewport does the same): objects that only
moved (a transform update of a plain mesh object) are re-placed in the synced scene's BVH top
level (native ViewportScene.move_instances; no mesh, BVH, texture or light is rebuilt), and the
session restarts on it, tracing photons again; anything else (geometry, materials, lights, the
world, objects shown or hidden, instancers) syncs the scene again, with meshes unchanged since
the last sync replayed from a MeshCache and their BVHs kept in a BlasCache. view_draw reads the
view from `context.region_data` (sync/view.py), re-aims the running session when it changed (no
sync, no rebuild), and draws its latest pass as a float texture through Blender's display
transform. All native work runs on the session's threads, off the GIL.
"""

import time
import traceback

import bpy
import gpu
import numpy as np
from gpu_extras.presets import draw_texture_2d

from . import render_settings, report, schema, sync, texture_cache
from .sync import cache as sync_cache
from .sync.origin import REBASE_RATIO, rebased_matrix
from .sync.view import viewport_view

# While a pass is on its way, a redraw waits this long for it instead of spinning the UI.
DRAW_WAIT_SECONDS = 0.01
# After a restart (an edit, a new view), a redraw waits up to this long for the session's
# coarse first image (a few ms of rendering) rather than show the old image for another
# redraw, which under load comes a tenth of a second or more later.
FIRST_IMAGE_WAIT_SECONDS = 0.05

# Seconds from the last edit (a view_update that synced) to the first image of the session it
# started, for the benchmark in tests/blender/test_viewport_gui.py; None before the first.
last_edit_to_image_seconds = None
# The last view_draw's state (samples shown, converged), for tests and benchmarks.
last_draw = {}
# How the viewport took edits in (tests, benchmarks): "full" syncs of the whole scene,
# "transform" updates that only moved instances and "material" updates that only converted
# edited materials again; "last" is the latest one's kind.
sync_counts = {"full": 0, "transform": 0, "material": 0, "last": None}


def tag_rendered_viewports():
    """Redraws every 3D viewport in Rendered shading (their view_draw notices new settings)."""
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == 'VIEW_3D' and area.spaces[0].shading.type == 'RENDERED':
                area.tag_redraw()


def _settings_key(scene):
    """What a session was started with besides the view: a change restarts the session."""
    values = tuple(getattr(scene.photon, p["name"]) for p in schema.params())
    return values + (bool(scene.render.film_transparent),)


class ViewportRender:
    """One viewport's render: the synced native scene, its progressive session and the texture
    of its latest pass. Lives on the RenderEngine instance Blender keeps for that viewport."""

    def __init__(self, native):
        self.native = native
        self.reporter = report.Reporter(None)  # prints each distinct warning once
        self.mesh_cache = sync_cache.MeshCache()
        self.blas_cache = native.BlasCache()
        self.camera_scene = native.Scene()  # holds the viewport camera handed to set_view
        self.native_scene = None
        self.sync_stats = None
        self.session = None
        self.needs_sync = True
        self.settings_key = None
        self.view_key = None
        self.texture = None
        # (view serial, samples, quick, rows) uploaded: a coarse first image has fewer rows
        self.texture_key = (None, None, None, None)
        self.view_serial = None   # of the session's current view
        self.texture_rect = None  # (x, y, width, height) in region pixels, from the bottom
        self.edit_time = None     # perf_counter() of the sync the session started from
        self.error = None
        self.viewport_scene = None  # native ViewportScene: the synced scene and its BVH
        self.instances = {}       # object name -> its native instance indices
        self.movable = set()      # objects whose moves only re-place their instances
        self.object_names = None  # the depsgraph's objects at the last sync (shown/hidden)
        self.pending_moves = set()  # objects moved since the session started
        self.pending_materials = set()  # name_full of materials edited since then

    # -- view_update --
    def update(self, depsgraph):
        """view_update: sorts the edits. Objects that only moved are queued for draw() to
        re-place; anything else marks a full re-sync. True when the viewport must redraw (an
        edit, or new render settings, which draw() notices by their key): a script's change
        sends no notifier that would redraw it."""
        if self.native_scene is None:
            self.needs_sync = True
            return True
        moved, materials, trees = set(), set(), 0
        for update in depsgraph.updates:
            data = update.id
            if isinstance(data, bpy.types.Material):
                materials.add(data.name_full)
                continue
            if isinstance(data, bpy.types.ShaderNodeTree) and data.is_embedded_data:
                trees += 1  # a material's or the world's own tree: its owner is updated too
                continue
            if isinstance(data, bpy.types.Object) and data.type == 'CAMERA':
                continue  # view_draw reads the camera
            if isinstance(data, bpy.types.Camera):
                continue
            if isinstance(data, bpy.types.Scene):
                # Hiding or showing an object updates only the scene (checked in Blender
                # 3.4.1), as do render settings (draw() compares their key).
                if self._objects_changed(depsgraph):
                    return self._mark_sync()
                continue
            if isinstance(data, bpy.types.Object) and self._moved_only(update, data):
                moved.add(data.name)
                continue
            return self._mark_sync()
        if trees and not materials and not moved:
            return self._mark_sync()  # a node tree edit whose owner is not known
        if moved or materials:
            self.pending_moves |= moved
            self.pending_materials |= materials
            self.edit_time = time.perf_counter()  # for the edit-to-image benchmark
            return True
        return _settings_key(depsgraph.scene) != self.settings_key

    def _mark_sync(self):
        self.needs_sync = True
        self.pending_moves.clear()
        self.pending_materials.clear()
        self.edit_time = time.perf_counter()  # for the edit-to-image benchmark
        return True

    def _objects_changed(self, depsgraph):
        return frozenset(o.name for o in depsgraph.objects) != self.object_names

    def _moved_only(self, update, obj):
        """True for an update that only moved a plain mesh object: a transform update (a
        parent's move updates its children too), no geometry or shading update (ray
        visibility, pass index and such are shading updates), of an object whose own
        instances are all it puts in the scene."""
        return (update.is_updated_transform and not update.is_updated_geometry
                and not update.is_updated_shading and obj.name in self.movable)

    def _stop(self):
        if self.session is not None:
            self.session.cancel()
            self.session.wait()
            redirect = self.sync_stats.texture_redirect if self.sync_stats else None
            for message in texture_cache.explain(self.session.warnings, redirect):
                self.reporter.warning(message)
            self.session = None

    def _drop_scene(self):
        """Ends the session and gives the synced scene's meshes back to the MeshCache (they
        are moved into the scene, not copied: the scene cannot render afterwards)."""
        self._stop()
        self.viewport_scene = None  # its BVH points into the meshes
        self.pending_moves.clear()
        self.pending_materials.clear()
        if self.native_scene is not None:
            self.mesh_cache.reclaim(self.native_scene)
            self.native_scene = None
        if self.sync_stats is not None:
            self.sync_stats.release()
            self.sync_stats = None

    def _sync(self, depsgraph):
        self._drop_scene()
        if self.edit_time is None:
            self.edit_time = time.perf_counter()
        self.blas_cache.begin_frame()  # BVHs of meshes the last sync no longer had go
        self.instances = {}
        self.native_scene, self.sync_stats = sync.sync_scene(
            self.native, depsgraph, self.reporter, object_instances=self.instances,
            mesh_cache=self.mesh_cache)
        self.viewport_scene = self.native.ViewportScene(self.native_scene, self.blas_cache)
        self.movable = _movable_objects(depsgraph, self.instances)
        self.object_names = frozenset(o.name for o in depsgraph.objects)
        self.needs_sync = False
        self.pending_moves.clear()
        self.pending_materials.clear()
        sync_counts["full"] += 1
        sync_counts["last"] = "full"

    def _move(self, depsgraph):
        """Re-places the instances of the objects that moved since the session started, in
        the synced scene and its BVH's top level, as a full sync would place them. False when
        that cannot be sure to give what a full sync would (the caller syncs then)."""
        names, self.pending_moves = self.pending_moves, set()
        origin = self.sync_stats.origin
        if origin.any():
            return False  # a move may change the rebased scene's origin: sync again
        indices, matrices = [], []
        for name in sorted(names):
            obj = depsgraph.objects.get(name)
            if obj is None or name not in self.instances:
                return False
            matrix = rebased_matrix(obj.matrix_world, origin)
            for index in self.instances[name]:
                indices.append(index)
                matrices.append(matrix)
        self._stop()
        self.viewport_scene.move_instances(indices, np.stack(matrices))
        # The scene moved far from its size off the origin would be rebased by a full sync
        # (sync/origin.choose_origin); with margin, as the BVH's float bounds are checked here.
        bounds = self.viewport_scene.bounds
        if bounds is not None:
            lo, hi = np.array(bounds[0], np.float64), np.array(bounds[1], np.float64)
            extent = float(np.linalg.norm(hi - lo))
            if not float(np.abs(0.5 * (lo + hi)).max()) <= 0.5 * REBASE_RATIO * extent:
                return False
        sync_counts["transform"] += 1
        sync_counts["last"] = "transform"
        return True

    def _edit_materials(self, depsgraph):
        """Converts the materials edited since the session started again and replaces them in
        the synced scene, whose BVH, lamps and textures stay (emissive triangles are refreshed).
        False when an edit needs a full sync (the caller syncs then)."""
        names, self.pending_materials = self.pending_materials, set()
        table = self.sync_stats.material_table
        crypto = self.sync_stats.cryptomatte
        edits = []
        for name in sorted(names):
            material = next((m for m in bpy.data.materials if m.name_full == name), None)
            if material is None or table is None:
                return False
            converted = table.reconvert(material.evaluated_get(depsgraph))
            if converted is None:
                return False
            edits.append(converted)
        self._stop()
        for index, name, closures, program, pass_index in edits:
            crypto_id = (crypto.id("CryptoMaterial", name)
                         if crypto is not None and crypto.any() else 0.0)
            try:
                self.viewport_scene.replace_material(index, name, closures, program, pass_index,
                                                     crypto_id)
            except ValueError:  # its nodes do not compile: a full sync reports and falls back
                return False
        sync_counts["material"] += 1
        sync_counts["last"] = "material"
        return True

    def _start(self, scene, view):
        (args, width, height, border) = view
        settings = render_settings.viewport_settings(self.native, scene, width, height, border)
        self.session = self.native.ProgressiveSession(self.viewport_scene, settings)
        self.camera_scene.set_camera(*args)
        self.view_serial = self.session.set_view(self.camera_scene, width, height, list(border))
        self.session.start()
        # A new session counts views and samples from the start again: whatever it shows first
        # replaces the texture (which stays up meanwhile).
        self.texture_key = (None, None, None, None)
        self.settings_key = _settings_key(scene)

    # -- view_draw --
    def draw(self, engine, context, depsgraph):
        scene = depsgraph.scene
        try:
            if self.needs_sync or self.native_scene is None:
                self._sync(depsgraph)
            elif ((self.pending_moves and not self._move(depsgraph))
                  or (self.pending_materials and not self._edit_materials(depsgraph))):
                self._sync(depsgraph)
            key, view = viewport_view(context, depsgraph, self.sync_stats.origin)
            if self.session is None or _settings_key(scene) != self.settings_key:
                self._stop()
                self._start(scene, view)
                self.view_key = key
            elif key != self.view_key:
                args, width, height, border = view
                self.camera_scene.set_camera(*args)
                self.view_serial = self.session.set_view(self.camera_scene, width, height,
                                                         list(border))
                self.view_key = key
            self.error = None
        except Exception as exc:  # noqa: BLE001 - a failed viewport must not take Blender down
            self._drop_scene()
            self.needs_sync = True
            self.error = f"Photon: {exc}"
            if not isinstance(exc, report.SceneError):
                traceback.print_exc()
            engine.update_stats("", self.error)
            return

        image = self.session.image()
        if image is None or image[3] != self.view_serial:
            self.session.wait_for_image(FIRST_IMAGE_WAIT_SECONDS)
        # Read before the image: a session converged by then has published its last pass.
        converged = self.session.converged
        image = self.session.image()
        if not converged and (image is None or image[3] != self.view_serial
                              or _image_key(image) == self.texture_key):
            # Nothing new yet: wait a moment for the next pass rather than spin the UI. (The
            # previous view's image stays up until the new view's first pass.)
            self.session.wait_for_samples(max(self.session.samples_done, 0) + 1,
                                          DRAW_WAIT_SECONDS)
            image = self.session.image()
        if image is not None:
            self._upload(image, view)
        if self.texture is not None:
            gpu.state.blend_set('ALPHA_PREMULT')
            engine.bind_display_space_shader(scene)
            draw_texture_2d(self.texture, self.texture_rect[:2], *self.texture_rect[2:])
            engine.unbind_display_space_shader()
            gpu.state.blend_set('NONE')
        engine.update_stats("", self._status())
        last_draw.update(samples=self.texture_key[1], quick=self.texture_key[2],
                         current=self.texture_key[0] == self.view_serial,
                         converged=converged, status=self.session.status)
        if not converged:
            engine.tag_redraw()

    def _upload(self, image, view):
        pixels, samples, quick, serial = image
        key = _image_key(image)
        if key == self.texture_key:
            return
        height, width = pixels.shape[:2]  # a coarse first image is smaller: drawn scaled up
        _, region_w, region_h, border = view
        flat = np.ascontiguousarray(pixels[::-1], dtype=np.float32).ravel()  # rows bottom-up
        buffer = gpu.types.Buffer('FLOAT', flat.size, flat)
        self.texture = gpu.types.GPUTexture((width, height), format='RGBA16F', data=buffer)
        x0, y0, x1, y1 = border
        self.texture_rect = (x0, region_h - y1, x1 - x0, y1 - y0)
        self.texture_key = key
        if self.edit_time is not None:
            global last_edit_to_image_seconds
            last_edit_to_image_seconds = time.perf_counter() - self.edit_time
            self.edit_time = None

    def _status(self):
        session = self.session
        done, target = session.samples_done, session.target_samples
        if session.preparing or done == 0:
            return f"Photon | {session.status}"
        return f"Photon | Sample {done}/{target}"

    def free(self):
        self._drop_scene()


def _image_key(image):
    """(view serial, samples, quick, rows) of a session image: what tells two apart (quick is
    0, or 1 and 2 for the two first looks, which have the same size and sample count)."""
    pixels, samples, quick, serial = image
    return serial, samples, quick, pixels.shape[0]


def _movable_objects(depsgraph, instances):
    """Names of the objects whose moves only re-place their own native instances: plain mesh
    objects that neither instance anything (collections, particles, geometry-node instances,
    hair) nor are instanced by another object (whose copies a move would carry along)."""
    generated = set()
    for inst in depsgraph.object_instances:
        # Instance items die when iteration moves on: names only.
        if inst.is_instance:
            generated.add(inst.object.name)
            if inst.parent is not None:
                generated.add(inst.parent.name)
    movable = set()
    for name in instances:
        obj = depsgraph.objects.get(name)
        if (obj is None or obj.type != 'MESH' or name in generated or obj.is_instancer
                or len(obj.particle_systems) or any(m.type == 'NODES' for m in obj.modifiers)):
            continue
        movable.add(name)
    return movable
