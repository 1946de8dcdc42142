"""The final render (F12, -f, -a) of one view layer: syncs its depsgraph, runs the native
RenderSession off the GIL for each view (a stereo eye, a multiview camera), streams the quick
preview and the finished tiles into the render result (passes.py) while Blender's progress bar
and stats line move (progress.py), cancels on Esc and reports (render_report.py). With
Persistent Data, unchanged meshes and their BVHs are kept between frames."""

import time

import bpy
import numpy as np

from . import (data_passes, passes, prepared_state, render_report, report, sync,
               texture_cache)
from . import progress as render_progress
from .native import native_module
from .render_settings import integrator_capabilities, make_settings
from .sync import cache as sync_cache
from .sync import camera as sync_camera
from .sync.cancel import SyncCancelled

POLL_SECONDS = 0.05  # tile poll interval; bounds Esc latency together with the per-row check
SYNC_STAGE = "Syncing scene"  # the stats line's stage while the depsgraph is read
NOTHING_RENDERED = "no image was rendered"

# The render in progress as scripts may watch it from Blender's main thread (a timer): the
# session's status, tiles finished of the total, whether the quick preview was shown and the
# progress bar's fraction. Empty between renders.
RENDER_STATUS = {}


class PersistentData:
    """Persistent Data: Blender keeps the RenderEngine object (which holds this) between the
    frames of an animation; these caches keep unchanged meshes (their arrays and their BVHs)
    between them."""

    def __init__(self):
        self.mesh_cache = None
        self.blas_cache = None
        self.frame = None

    def caches(self, native, scene):
        """(MeshCache, BlasCache) under Render > Performance > Persistent Data, else (None,
        None), which also frees what earlier frames kept."""
        if not scene.render.use_persistent_data or not hasattr(native, "BlasCache"):
            self.mesh_cache = self.blas_cache = self.frame = None
            return None, None
        if self.mesh_cache is None:
            self.mesh_cache = sync_cache.MeshCache()
            self.blas_cache = native.BlasCache()
        if scene.frame_current != self.frame:
            # BVHs the previous frame did not use go (every view layer of a frame shares them).
            self.blas_cache.begin_frame()
            self.frame = scene.frame_current
        return self.mesh_cache, self.blas_cache


def render(engine, depsgraph, persistent):
    """Renders the view layer of `depsgraph` into `engine`'s result (`persistent`: the
    engine's PersistentData)."""
    FinalRender(engine, depsgraph).run(persistent)


class FinalRender:
    """One render() call: Blender calls render() once per view layer to render, each time with
    that layer's depsgraph (its collections and objects); the layer's passes and tiles go into
    the result's layer of that name."""

    def __init__(self, engine, depsgraph):
        self.engine = engine
        self.depsgraph = depsgraph
        self.native = native_module()
        self.reporter = report.Reporter(engine)
        self.t_start = time.perf_counter()
        self.layer = depsgraph.view_layer.name  # the view layer being rendered
        self.light_passes = ()  # the names of its enabled Photon light passes
        self.native_scene = None
        self.sync_stats = None
        self.blas_cache = None  # the BlasCache of Persistent Data, or None
        self.stage = SYNC_STAGE  # the stage the stats line shows

    def run(self, persistent):
        engine, native, reporter = self.engine, self.native, self.reporter
        depsgraph = self.depsgraph
        scene = depsgraph.scene
        view_layer = depsgraph.view_layer
        self.light_passes = passes.add_light_passes(engine, view_layer)
        data_passes.warn_unsupported(reporter, native, scene, view_layer)
        views = self._views(scene)

        if scene.render.use_motion_blur:
            # Photon samples one instant per frame: say so rather than ignore the setting.
            reporter.warning("motion blur is not rendered by Photon (Render Properties > "
                             "Motion Blur is on); the frame is rendered without blur at its "
                             "current time")
        engine.update_stats("", f"Photon | {SYNC_STAGE}")
        mesh_cache, self.blas_cache = persistent.caches(native, scene)
        try:
            self.native_scene, self.sync_stats = sync.sync_scene(
                native, depsgraph, reporter, mesh_cache=mesh_cache,
                test_break=engine.test_break)
        except SyncCancelled as cancelled:
            self._report_cancel(SYNC_STAGE, cancelled.at, NOTHING_RENDERED)
            return
        try:
            for view in views:
                if view:
                    # Each multiview view (a stereo eye) from its own camera, as Cycles does.
                    camera = sync_camera.view_camera(engine, scene, depsgraph, view)
                    sync_camera.export_camera(self.native_scene, scene, depsgraph, reporter,
                                              camera, origin=self.sync_stats.origin)
                if not self._render_view(view):
                    break
        finally:
            if mesh_cache is not None:
                # The kept meshes it borrowed, for next frame.
                mesh_cache.reclaim(self.native_scene)
            # Packed and generated images were written for this render only.
            self.sync_stats.release()

    def _report_cancel(self, stage, t_cancel, outcome):
        """The warning of a render Esc stopped during `stage`: how long it took to stop after
        test_break() was first seen true (at perf_counter `t_cancel`), and what is left."""
        self.reporter.warning(f"render cancelled (Esc) during '{stage}', stopped "
                              f"{time.perf_counter() - t_cancel:.3f} s later: {outcome}")

    def _views(self, scene):
        """Names of the views to render: [""] (all of the result's views, one) without
        multiview, else the views of the render result (Stereo 3D: left and right; MULTIVIEW:
        the enabled views), read from a probe result as Cycles does."""
        if not scene.render.use_multiview:
            return [""]
        probe = self.engine.begin_result(0, 0, 1, 1, layer=self.layer)
        try:
            names = [view.name for view in probe.views]
        finally:
            self.engine.end_result(probe, cancel=True, do_merge_results=False)
        return names or [""]

    def _render_view(self, view):
        """Renders one view into the result; returns False when the render was cancelled."""
        engine, native, reporter = self.engine, self.native, self.reporter
        sync_stats = self.sync_stats
        scene = self.depsgraph.scene
        if engine.test_break():  # Esc after the sync's last poll, or between two views
            self._report_cancel(self.stage, time.perf_counter(), NOTHING_RENDERED)
            return False

        width, height = sync_camera.render_size(scene.render)
        region = sync_camera.render_region(scene.render, width, height)
        settings = make_settings(native, scene, width, height, region)
        region_w, region_h = region[2] - region[0], region[3] - region[1]
        settings.light_passes = bool(self.light_passes)
        settings.data_passes = data_passes.settings(native, scene, self.depsgraph.view_layer,
                                                    sync_stats.origin)
        writer = passes.TileWriter(engine, self.layer, view)
        passes.add_cryptomatte_metadata(engine, sync_stats, self.layer)

        session = native.RenderSession(self.native_scene, settings,
                                       blas_cache=self.blas_cache)
        # A user watching the render sees the whole frame (direct light) before the slow
        # stages; in background mode nobody does and it would only cost time.
        session.set_quick_preview(not bpy.app.background)
        # A render farm's bands of one frame share its preparation (prepared_state.py).
        prepared_files = prepared_state.from_environment(scene.frame_current)
        if prepared_files:
            session.set_prepared_state(**prepared_files)
        capabilities = integrator_capabilities(native, scene)
        prepares = capabilities["prepares"]
        bar = render_progress.RenderProgress(prepares)
        session.start()
        tiles_total = ((region_w + settings.tile_size - 1) // settings.tile_size) * (
            (region_h + settings.tile_size - 1) // settings.tile_size)
        if capabilities.get("iterative"):
            tiles_total = 1  # SPPM: the whole region, written again after each iteration
        tiles_done = 0
        cancelled_during = None  # the stage Esc cancelled, or None
        RENDER_STATUS.clear()
        RENDER_STATUS.update(status="Starting", tiles_done=0, tiles_total=tiles_total,
                             progress=0.0, preview_shown=False)
        try:
            while True:
                preview = session.take_preview()
                if preview is not None:
                    writer.write(0, 0, region_w, region_h, preview, preview=True)
                    RENDER_STATUS["preview_shown"] = True
                for x, y, w, h, rgba, tile_passes in session.take_tiles(POLL_SECONDS):
                    writer.write(x, region_h - (y + h), w, h, rgba, tile_passes)
                    tiles_done += 1
                # Esc (or Ctrl-C in background mode, which Blender turns into test_break())
                # cancels whatever stage runs; test_break() then stays set, so it is read until
                # the first time it is true.
                if cancelled_during is None and engine.test_break():
                    cancelled_during = session.status
                    t_cancel = time.perf_counter()
                    session.cancel()
                snapshot = session.snapshot()
                fraction, time_left = bar.update(snapshot["status"], snapshot["preparing"],
                                                 snapshot["progress"], time.perf_counter())
                engine.update_progress(fraction)
                RENDER_STATUS.update(status=snapshot["status"], tiles_done=tiles_done,
                                     tiles_total=tiles_total, progress=fraction)
                self.stage = snapshot["status"]
                engine.update_stats("", render_progress.stats_line(
                    snapshot["status"], sync_stats, min(tiles_done, tiles_total), tiles_total,
                    self.t_start, time_left))
                if session.finished:
                    for x, y, w, h, rgba, tile_passes in session.take_tiles(0.0):
                        writer.write(x, region_h - (y + h), w, h, rgba, tile_passes)
                        tiles_done += 1
                    break
        finally:
            session.cancel()
            session.wait()
            RENDER_STATUS.clear()
        cancelled = cancelled_during is not None
        if prepared_files and prepared_files["prepare_only"] and not tiles_done:
            # A result no tile was written to crashes Blender when it saves the image: an
            # empty (zero) frame is written instead.
            writer.write(0, 0, region_w, region_h,
                         np.zeros((region_h, region_w, 4), dtype=np.float32), preview=True)
        if cancelled:
            self._report_cancel(cancelled_during, t_cancel,
                                f"the image keeps what was finished ({tiles_done} tiles or "
                                f"parts of tiles of {tiles_total})")

        for message in texture_cache.explain(session.warnings,
                                              sync_stats.texture_redirect):
            reporter.warning(message)
        if writer.missing:
            reporter.warning(f"passes not written by Photon, left at zero: "
                             f"{', '.join(sorted(writer.missing))}")
        stats = session.stats
        if stats.non_finite_samples:
            reporter.warning(f"{stats.non_finite_samples} samples were NaN or infinite "
                             f"and were dropped")
        elapsed = time.perf_counter() - self.t_start
        state = "cancelled" if cancelled else "rendered"
        if prepared_files and prepared_files["prepare_only"] and not cancelled:
            state = "prepared (no pixels: PHOTON_PREPARE_ONLY)"
        reporter.info(render_report.frame_line(state, scene, region_w, region_h, settings, stats,
                                               sync_stats, elapsed, self.layer, view))
        result = engine.get_result()
        for key, value in render_report.metadata_fields(self.layer, settings, stats, sync_stats,
                                                        elapsed):
            result.stamp_data_add_field(key, value)
        if prepared_files:
            prepared_state.report(reporter, prepared_files, stats)
        for line in render_report.prepare_lines(stats.integrator):
            reporter.info(line)
        if stats.iterations.iterations:
            reporter.info(render_report.iterations_line(settings.integrator.name,
                                                        stats.iterations))
        line = render_report.persistent_data_line(sync_stats, stats)
        if line is not None:
            reporter.info(line)
        # Free native memory now rather than when Python collects: -a renders many frames.
        del session
        return not cancelled
