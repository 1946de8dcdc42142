"""The PHOTON RenderEngine: syncs the depsgraph, runs the native render off the GIL and streams
finished tiles into Blender's render result."""

import time
import traceback

import bpy
import numpy as np

from . import report, sync, sync_camera

POLL_SECONDS = 0.05  # tile poll interval; bounds Esc latency together with the per-row check


def native_module():
    from . import _photon, NATIVE_IMPORT_ERROR
    if _photon is None:
        raise RuntimeError(f"the native module _photon failed to load: {NATIVE_IMPORT_ERROR}")
    return _photon


def make_settings(native, scene, full_width, full_height, region):
    props = scene.photon
    settings = native.RenderSettings()
    settings.full_width = full_width
    settings.full_height = full_height
    settings.x0, settings.y0, settings.x1, settings.y1 = region
    settings.samples = max(1, int(props.samples))
    settings.max_depth = max(0, int(props.max_depth))
    settings.seed = max(0, int(props.seed))
    settings.threads = max(0, int(props.threads))
    settings.tile_size = max(8, int(props.tile_size))
    settings.transparent_background = bool(scene.render.film_transparent)
    settings.integrator = getattr(native.Integrator, props.integrator)
    return settings


class PhotonRenderEngine(bpy.types.RenderEngine):
    bl_idname = "PHOTON"
    bl_label = "Photon"
    bl_use_preview = False
    bl_use_postprocess = True
    # Keep Blender's shader nodes visible so artists author Principled materials for Photon.
    bl_use_shading_nodes_custom = False

    def render(self, depsgraph):
        # An exception escaping render() makes Blender write an empty file and crash in
        # background mode: everything is caught and reported instead.
        try:
            self._render(depsgraph)
        except Exception as exc:  # noqa: BLE001 - the engine must never propagate
            traceback.print_exc()
            message = f"Photon: render failed: {exc}"
            self.report({'ERROR'}, message)
            self.error_set(message)

    def _render(self, depsgraph):
        native = native_module()
        scene = depsgraph.scene
        reporter = report.Reporter(self)
        t_start = time.perf_counter()

        self.update_stats("", "Photon | Syncing scene")
        native_scene, sync_stats = sync.sync_scene(native, depsgraph, reporter)
        if self.test_break():
            return

        width, height = sync_camera.render_size(scene.render)
        region = sync_camera.render_region(scene.render, width, height)
        settings = make_settings(native, scene, width, height, region)
        region_w, region_h = region[2] - region[0], region[3] - region[1]

        session = native.RenderSession(native_scene, settings)
        session.start()
        tiles_total = ((region_w + settings.tile_size - 1) // settings.tile_size) * (
            (region_h + settings.tile_size - 1) // settings.tile_size)
        tiles_done = 0
        cancelled = False
        try:
            while True:
                for x, y, w, h, rgba in session.take_tiles(POLL_SECONDS):
                    self._write_tile(x, region_h - (y + h), w, h, rgba)
                    tiles_done += 1
                if not cancelled and self.test_break():
                    session.cancel()
                    cancelled = True
                self.update_progress(session.progress)
                self.update_stats("", self._stats_line(session, sync_stats, tiles_done,
                                                       tiles_total, t_start))
                if session.finished:
                    for x, y, w, h, rgba in session.take_tiles(0.0):
                        self._write_tile(x, region_h - (y + h), w, h, rgba)
                        tiles_done += 1
                    break
        finally:
            session.cancel()
            session.wait()

        for message in session.warnings:
            reporter.warning(message)
        stats = session.stats
        if stats["non_finite_samples"]:
            reporter.warning(f"{stats['non_finite_samples']} samples were NaN or infinite "
                             f"and were dropped")
        elapsed = time.perf_counter() - t_start
        state = "cancelled" if cancelled else "rendered"
        reporter.info(
            f"{state} frame {scene.frame_current} {region_w}x{region_h} "
            f"({settings.samples} spp, {stats['threads']} threads): sync {sync_stats.seconds:.3f} s "
            f"({sync_stats.triangles} triangles, {sync_stats.instances} instances, "
            f"{sync_stats.lights} lights), BVH {stats['build_seconds']:.3f} s, "
            f"render {stats['render_seconds']:.3f} s, total {elapsed:.3f} s")
        # Free native memory now rather than when Python collects: -a renders many frames.
        del session, native_scene

    def _write_tile(self, x, y_bottom, w, h, rgba):
        # Native tiles are top row first; Blender's result rows go bottom-up.
        pixels = np.ascontiguousarray(rgba[::-1], dtype=np.float32)
        result = self.begin_result(x, y_bottom, w, h)
        passes = result.layers[0].passes
        if len(passes) == 1:
            passes.foreach_set("rect", pixels.ravel())
        else:
            # Other passes registered on the view layer get zeros until Photon writes them.
            parts = []
            for render_pass in passes:
                if render_pass.name == "Combined":
                    parts.append(pixels.ravel())
                else:
                    parts.append(np.zeros(w * h * render_pass.channels, dtype=np.float32))
            passes.foreach_set("rect", np.concatenate(parts))
        self.end_result(result)

    @staticmethod
    def _stats_line(session, sync_stats, tiles_done, tiles_total, t_start):
        return (f"Photon | {session.status} | Tiles {tiles_done}/{tiles_total} | "
                f"Triangles {sync_stats.triangles:,} | Instances {sync_stats.instances:,} | "
                f"Lights {sync_stats.lights} | Time {time.perf_counter() - t_start:.1f} s")


def register():
    bpy.utils.register_class(PhotonRenderEngine)


def unregister():
    bpy.utils.unregister_class(PhotonRenderEngine)
