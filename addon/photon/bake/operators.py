"""Operators and panel of the lighting bake: photon.bake_lighting (modal with Esc in the UI,
blocking when run from a script or in background mode) and photon.show_baked_lighting."""

import re
import time
import traceback

import bpy

from .. import report
from ..native import native_module
from ..ui import PhotonPanel
from . import job as bake
from . import viewport


class PHOTON_OT_bake_lighting(bpy.types.Operator):
    """Bake the scene's view-independent lighting (photon maps or radiosity) into a color
    attribute per mesh and/or lightmap images, to orbit the lit scene in the viewport"""
    bl_idname = "photon.bake_lighting"
    bl_label = "Bake Lighting"
    bl_options = {'REGISTER', 'UNDO'}

    _job = None
    _timer = None
    _started = 0.0

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def _make_job(self, context):
        self._reporter = report.Reporter(self)
        self._started = time.perf_counter()
        try:
            return bake.BakeJob(context, self._reporter)
        except bake.BakeError as exc:
            self._reporter.warning(f"Bake: {exc}")
        except Exception as exc:  # noqa: BLE001 - never let a bake take Blender down
            traceback.print_exc()
            self._reporter.error(f"Bake failed: {exc}")
        return None

    def _finish(self, job):
        try:
            result = job.finish()
        except Exception as exc:  # noqa: BLE001 - RuntimeError when the integrator cannot bake
            traceback.print_exc()
            self._reporter.error(f"Bake failed: {exc}")
            return {'CANCELLED'}
        if result is None:
            self._reporter.warning(
                f"Bake cancelled after {time.perf_counter() - self._started:.2f} s; no lighting "
                f"was written (meshes and images keep their previous values)")
            return {'CANCELLED'}
        stats = result["stats"]  # _photon.BakeStats
        written = [t.name for t in job.targets]
        elapsed = time.perf_counter() - self._started
        written_to = []
        if job.corner_count:
            written_to.append(f"{job.corner_count:,} corners "
                              f"({job.corner_count / max(elapsed, 1e-9):,.0f}/s)")
        if job.texel_count:
            written_to.append(f"{job.texel_count:,} lightmap texels")
        self._reporter.info(
            f"baked {job.point_count:,} points into {' and '.join(written_to)} on "
            f"{len(written)} object(s) in {elapsed:.2f} s ({job.point_count / max(elapsed, 1e-9):,.0f}"
            f" points/s; prepare {stats.prepare_seconds:.2f} s, locate "
            f"{stats.locate_seconds:.2f} s, shared work {stats.share_seconds:.2f} s, "
            f"shading {stats.bake_seconds:.2f} s, {stats.threads} threads)")
        cache = stats.integrator.bake_irradiance_cache
        if cache is not None:
            print(f"Photon: bake: irradiance cache of {cache.records:,.0f} records in "
                  f"{cache.seconds:.2f} s", flush=True)
        return {'FINISHED'}

    def execute(self, context):
        # Blocking (scripts, background mode): Ctrl-C cancels the bake through a SIGINT
        # handler installed for its duration (Blender's own only flags renders).
        try:
            native = native_module()
        except Exception:  # noqa: BLE001 - _make_job reports the missing module
            native = None
        if native is not None:
            native.watch_sigint(None)
        try:
            job = self._make_job(context)
            if job is None:
                return {'CANCELLED'}
            native.watch_sigint(job.session)
            if native.sigint_received():  # Ctrl-C while the scene was synced
                job.session.cancel()
            job.start()
            wm = context.window_manager
            wm.progress_begin(0, 100)
            last_print, last_stage = 0.0, None
            try:
                while not job.finished:
                    time.sleep(0.02)
                    wm.progress_update(int(100 * job.progress))
                    # Read the status on every poll (it times the shading rate from its first
                    # reading); print it when the stage changes, else once a second.
                    status = job.status
                    stage = re.split(r"\d", status, maxsplit=1)[0]
                    if stage != last_stage or time.perf_counter() - last_print > 1.0:
                        last_print, last_stage = time.perf_counter(), stage
                        print(f"Photon: bake: {status} {100 * job.progress:.0f}%", flush=True)
            except KeyboardInterrupt:
                job.cancel()
            finally:
                wm.progress_end()
            return self._finish(job)
        finally:
            if native is not None:
                native.unwatch_sigint()

    def invoke(self, context, event):
        if bpy.app.background or context.window is None:
            return self.execute(context)
        job = self._make_job(context)
        if job is None:
            return {'CANCELLED'}
        self._job = job
        job.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        wm.progress_begin(0, 100)
        return {'RUNNING_MODAL'}

    def _cleanup(self, context):
        wm = context.window_manager
        if self._timer is not None:
            wm.event_timer_remove(self._timer)
            self._timer = None
        wm.progress_end()
        if context.workspace is not None:
            context.workspace.status_text_set(None)

    def modal(self, context, event):
        job = self._job
        if event.type == 'ESC':
            job.cancel()
            self._cleanup(context)
            return self._finish(job)
        if event.type != 'TIMER':
            return {'PASS_THROUGH'}
        context.window_manager.progress_update(int(100 * job.progress))
        if context.workspace is not None:
            context.workspace.status_text_set(
                f"Photon bake: {job.status} {100 * job.progress:.0f}% (Esc to cancel)")
        if not job.finished:
            return {'PASS_THROUGH'}
        self._cleanup(context)
        return self._finish(job)


class PHOTON_OT_show_baked_lighting(bpy.types.Operator):
    """Show the baked lighting in every 3D viewport (or restore the previous shading)"""
    bl_idname = "photon.show_baked_lighting"
    bl_label = "Show Baked Lighting"
    bl_options = {'REGISTER'}

    mode: bpy.props.EnumProperty(
        name="Mode",
        items=[
            ("ATTRIBUTE", "Color Attribute",
             "Solid shading, flat lighting, colour from the PhotonLighting attribute"),
            ("LIGHTMAP", "Lightmaps",
             "Solid shading, flat lighting, colour from each object's lightmap texture"),
            ("RESTORE", "Restore", "Back to the shading used before"),
        ],
        default="ATTRIBUTE",
    )

    def execute(self, context):
        reporter = report.Reporter(self)
        try:
            if self.mode == "RESTORE":
                count = viewport.restore(context)
                reporter.info(f"restored the shading of {count} 3D viewport(s)")
            else:
                count = viewport.show(context, self.mode, reporter)
                reporter.info(f"showing baked lighting ({self.mode.lower()}) in {count} 3D "
                              f"viewport(s)")
        except Exception as exc:  # noqa: BLE001
            traceback.print_exc()
            reporter.error(f"Cannot switch the viewport: {exc}")
            return {'CANCELLED'}
        return {'FINISHED'}


class PHOTON_PT_bake(PhotonPanel, bpy.types.Panel):
    bl_label = "Bake Lighting"
    bl_parent_id = "PHOTON_PT_render"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        props = context.scene.photon
        layout.prop(props, "bake_source")
        layout.prop(props, "bake_target")
        layout.prop(props, "bake_samples")
        layout.prop(props, "bake_brighter_side")
        if props.bake_target in {"LIGHTMAP", "BOTH"}:
            col = layout.column(align=True)
            col.prop(props, "lightmap_size")
            col.prop(props, "lightmap_uv_name")
            col = layout.column(align=True)
            col.prop(props, "lightmap_filter_radius")
            col.prop(props, "lightmap_dilate")
        layout.operator("photon.bake_lighting", icon="RENDER_STILL")
        row = layout.row(align=True)
        row.operator("photon.show_baked_lighting", text="Show Baked",
                     icon="SHADING_SOLID").mode = "ATTRIBUTE"
        row.operator("photon.show_baked_lighting", text="Lightmaps",
                     icon="TEXTURE").mode = "LIGHTMAP"
        row.operator("photon.show_baked_lighting", text="", icon="LOOP_BACK").mode = "RESTORE"


classes = (PHOTON_OT_bake_lighting, PHOTON_OT_show_baked_lighting, PHOTON_PT_bake)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
