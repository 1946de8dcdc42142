"""The PHOTON RenderEngine: what Blender calls, delegated. Final renders go to final.py,
material/light/world thumbnails to preview.py, Rendered viewport shading to viewport.py and pass
registration to passes.py; this class only holds their per-engine state (Persistent Data's
caches, the viewport's render) and keeps exceptions from reaching Blender."""

import traceback

import bpy

from . import final, passes, preview, report, viewport
from .native import native_module


class PhotonRenderEngine(bpy.types.RenderEngine):
    bl_idname = "PHOTON"
    bl_label = "Photon"
    # Material, light and world thumbnails render with Photon (preview.py).
    bl_use_preview = True
    # Material Preview shading draws with EEVEE, as for Cycles; Rendered shading is Photon's.
    bl_use_eevee_viewport = True
    bl_use_postprocess = True
    # Keep Blender's shader nodes visible so artists author Principled materials for Photon.
    bl_use_shading_nodes_custom = False

    # Persistent Data: Blender keeps this engine object between the frames of an animation;
    # final.PersistentData keeps unchanged meshes (their arrays and their BVHs) between them.
    _persistent = None
    _viewport = None  # viewport.ViewportRender of this engine's 3D viewport

    def __init__(self, *args, **kwargs):
        # Blender 4.4+ creates the RenderEngine's own data in bpy_struct.__init__, from the
        # arguments it passes; 3.4 passes none.
        super().__init__(*args, **kwargs)

    def __del__(self):
        # Blender frees the engine when the viewport leaves Rendered shading or closes. At
        # Blender's exit the underlying data may already be gone (ReferenceError).
        try:
            viewport = self._viewport
        except ReferenceError:
            viewport = None
        if viewport is not None:
            viewport.free()
        parent_del = getattr(super(), "__del__", None)
        if parent_del is not None:
            parent_del()

    def view_update(self, context, depsgraph):
        if self._viewport is None:
            self._viewport = viewport.ViewportRender(native_module())
        if self._viewport.update(depsgraph):
            self.tag_redraw()

    def view_draw(self, context, depsgraph):
        if self._viewport is None:
            self._viewport = viewport.ViewportRender(native_module())
        self._viewport.draw(self, context, depsgraph)

    def update_render_passes(self, scene=None, renderlayer=None):
        passes.register(self, scene, renderlayer)

    def render(self, depsgraph):
        # An exception escaping render() makes Blender write an empty file and crash in
        # background mode: everything is caught and reported instead.
        try:
            if self.is_preview:  # a material/light/world thumbnail
                preview.render(self, depsgraph)
                return
            if self._persistent is None:
                self._persistent = final.PersistentData()
            final.render(self, depsgraph, self._persistent)
        except report.SceneError as exc:  # the scene's own fault: its message, no traceback
            message = f"Photon: {exc}"
            print(message, flush=True)
            self.report({'ERROR'}, message)
            self.error_set(message)
        except Exception as exc:  # noqa: BLE001 - the engine must never propagate
            traceback.print_exc()
            message = f"Photon: render failed: {exc}"
            self.report({'ERROR'}, message)
            self.error_set(message)


def register():
    bpy.utils.register_class(PhotonRenderEngine)


def unregister():
    bpy.utils.unregister_class(PhotonRenderEngine)
