"""The PHOTON RenderEngine: syncs the depsgraph, runs the native render off the GIL and streams
finished tiles into Blender's render result."""

import time
import traceback

import bpy
import numpy as np

from . import data_passes, prepared_state, properties, report, schema, sync, viewport
from . import progress as render_progress
from .sync import cache as sync_cache
from .sync import camera as sync_camera

POLL_SECONDS = 0.05  # tile poll interval; bounds Esc latency together with the per-row check

# The render in progress as scripts may watch it from Blender's main thread (a timer): the
# session's status, tiles finished of the total, whether the quick preview was shown and the
# progress bar's fraction. Empty between renders.
RENDER_STATUS = {}


def native_module():
    from . import _photon, NATIVE_IMPORT_ERROR
    if _photon is None:
        raise RuntimeError(NATIVE_IMPORT_ERROR)
    return _photon


def uses_cycles_film(scene):
    """Whether Photon's Film follows Cycles' own settings (scene.cycles: film_exposure,
    pixel_filter_type, filter_width), as it does whenever Cycles is enabled (the default in
    Blender 3.4), so one .blend renders alike in both engines."""
    cycles = getattr(scene, "cycles", None)
    return cycles is not None and hasattr(cycles, "pixel_filter_type")


def film_settings(scene):
    """(filter type, filter width, exposure) of the render. Cycles renders Box at width 1
    whatever its (then hidden) width says; Photon's Box width is its own scene.photon.filter_width
    (default 1, as Cycles; 0.01 samples pixel centres). Without Cycles, all three are
    scene.photon's."""
    props = scene.photon
    if not uses_cycles_film(scene):
        return props.filter_type, props.filter_width, props.exposure
    cycles = scene.cycles
    kind = cycles.pixel_filter_type
    width = props.filter_width if kind == "BOX" else cycles.filter_width
    return kind, width, cycles.film_exposure


def make_settings(native, scene, full_width, full_height, region):
    props = scene.photon
    settings = native.RenderSettings()
    settings.full_width = full_width
    settings.full_height = full_height
    settings.x0, settings.y0, settings.x1, settings.y1 = region
    settings.transparent_background = bool(scene.render.film_transparent)
    # Every schema parameter by name; out-of-range values are clamped (with a warning) natively.
    for p in schema.params():
        setattr(settings, p["name"], schema.native_value(p, getattr(props, p["name"])))
    kind, width, exposure = film_settings(scene)
    settings.filter_type, settings.filter_width, settings.exposure = kind, width, exposure
    return settings


def integrator_capabilities(native, scene):
    """What the scene's integrator can do (bake, stop_early, ...), as the native factory says."""
    return native.integrator_capabilities(getattr(native.Integrator, scene.photon.integrator))


def sppm_report(sppm):
    """The report line of an SPPM render (RenderStats.sppm)."""
    return (f"sppm: {sppm.iterations} iterations, {sppm.photons_emitted:,} photons emitted "
            f"in {sppm.photon_seconds:.3f} s, camera passes {sppm.camera_seconds:.3f} s; "
            f"{sppm.bytes_per_pixel} bytes per pixel, photons of one iteration "
            f"{sppm.peak_photon_bytes / 1e6:.1f} MB at most")


def prepare_report(prepared):
    """Report lines for a PrepareStats (photon maps, irradiance cache, radiosity): one per
    stage that ran."""
    lines = []
    pm = prepared.photon_map
    if pm is not None:
        lines.append(
            f"photons: {pm.photons_emitted:,} global and "
            f"{pm.caustic_photons_emitted:,} caustic emitted, "
            f"{pm.global_photons_stored:,} and "
            f"{pm.caustic_photons_stored:,} stored in "
            f"{pm.photon_trace_seconds:.3f} s; maps built in "
            f"{pm.photon_map_build_seconds:.3f} s, radiance precomputed in "
            f"{pm.radiance_precompute_seconds:.3f} s "
            f"({pm.photon_map_bytes / 1e6:.1f} MB)")
    cache = prepared.irradiance_cache
    if cache is not None:
        lines.append(
            f"irradiance cache: {cache.records:,} records, "
            f"{cache.gather_rays:,} gather rays in "
            f"{cache.seconds:.3f} s")
    r = prepared.radiosity
    if r is not None:
        lines.append(
            f"radiosity: {r.patches:,} patches (size {r.patch_size:.4g}, "
            f"{r.elements:,} elements, {r.clusters:,} clusters, meshed in "
            f"{r.mesh_seconds:.3f} s, displayed in {r.field_seconds:.3f} s), "
            f"{r.rays:,} rays in {r.solve_seconds:.3f} s "
            f"({r.rays_per_second / 1e6:.2f} M rays/s), "
            f"{r.shooting_iterations} shooting + "
            f"{r.averaged_iterations} averaged iterations; power: "
            f"emitted {r.emitted_power:.4g} W, absorbed "
            f"{r.absorbed_power + r.absorbed_specular_power:.4g}"
            f" W, escaped {r.escaped_power:.4g} W, unshot "
            f"{r.unshot_power:.4g} W")
    return lines


class PhotonRenderEngine(bpy.types.RenderEngine):
    bl_idname = "PHOTON"
    bl_label = "Photon"
    # Material, light and world thumbnails render with Photon (viewport.render_preview).
    bl_use_preview = True
    # Material Preview shading draws with EEVEE, as for Cycles; Rendered shading is Photon's.
    bl_use_eevee_viewport = True
    bl_use_postprocess = True
    # Keep Blender's shader nodes visible so artists author Principled materials for Photon.
    bl_use_shading_nodes_custom = False
    _passes = ()
    _missing_passes = set()  # enabled passes of the result Photon did not write
    _layer = ""  # the view layer being rendered
    _view = ""   # the multiview view being rendered ("": every view of a mono render)
    # Persistent Data: Blender keeps this engine object between the frames of an animation;
    # these caches keep unchanged meshes (their arrays and their BVHs) between them.
    _mesh_cache = None
    _blas_cache = None
    _cache_frame = None
    _session_blas_cache = None  # the BlasCache of the render in progress, or None

    _viewport = None  # viewport.ViewportRender of this engine's 3D viewport

    def __del__(self):
        # Blender frees the engine when the viewport leaves Rendered shading or closes.
        if self._viewport is not None:
            self._viewport.free()

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
        # Registering makes the passes exist in the compositor's Render Layers node.
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", "COLOR")
        for name, _index in properties.enabled_passes(renderlayer):
            self.register_pass(scene, renderlayer, name, 3, "RGB", "COLOR")
        try:
            native = native_module()
        except RuntimeError:
            return  # render() reports the failed import
        data_passes.register(self, native, scene, renderlayer)

    def render(self, depsgraph):
        # An exception escaping render() makes Blender write an empty file and crash in
        # background mode: everything is caught and reported instead.
        try:
            if self.is_preview:  # a material/light/world thumbnail
                viewport.render_preview(self, depsgraph)
                return
            self._render(depsgraph)
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

    def _render(self, depsgraph):
        # Blender calls render() once per view layer to render, each time with that layer's
        # depsgraph (its collections and objects); the layer's passes and tiles go into the
        # result's layer of that name.
        native = native_module()
        scene = depsgraph.scene
        reporter = report.Reporter(self)
        t_start = time.perf_counter()
        view_layer = depsgraph.view_layer
        self._layer = view_layer.name
        self._passes = properties.enabled_passes(view_layer)
        for name, _index in self._passes:
            self.add_pass(name, 3, "RGB", layer=self._layer)
        data_passes.warn_unsupported(reporter, view_layer)
        views = self._views(scene)

        if scene.render.use_motion_blur:
            # Photon samples one instant per frame: say so rather than ignore the setting.
            reporter.warning("motion blur is not rendered by Photon (Render Properties > "
                             "Motion Blur is on); the frame is rendered without blur at its "
                             "current time")
        self.update_stats("", "Photon | Syncing scene")
        mesh_cache, self._session_blas_cache = self._persistent_caches(native, scene)
        native_scene, sync_stats = sync.sync_scene(native, depsgraph, reporter,
                                                   mesh_cache=mesh_cache)
        try:
            for view in views:
                if view:
                    # Each multiview view (a stereo eye) from its own camera, as Cycles does.
                    camera = sync_camera.view_camera(self, scene, depsgraph, view)
                    sync_camera.export_camera(native_scene, scene, depsgraph, reporter, camera,
                                              origin=sync_stats.origin)
                if not self._render_scene(native, depsgraph, reporter, native_scene, sync_stats,
                                          t_start, view):
                    break
        finally:
            if mesh_cache is not None:
                mesh_cache.reclaim(native_scene)  # the kept meshes it borrowed, for next frame
            # Packed and generated images were written for this render only.
            sync_stats.release()

    def _persistent_caches(self, native, scene):
        """(MeshCache, BlasCache) under Render > Performance > Persistent Data, else (None,
        None), which also frees what earlier frames kept."""
        if not scene.render.use_persistent_data or not hasattr(native, "BlasCache"):
            self._mesh_cache = self._blas_cache = self._cache_frame = None
            return None, None
        if self._mesh_cache is None:
            self._mesh_cache = sync_cache.MeshCache()
            self._blas_cache = native.BlasCache()
        if scene.frame_current != self._cache_frame:
            # BVHs the previous frame did not use go (every view layer of a frame shares them).
            self._blas_cache.begin_frame()
            self._cache_frame = scene.frame_current
        return self._mesh_cache, self._blas_cache

    def _views(self, scene):
        """Names of the views to render: [""] (all of the result's views, one) without
        multiview, else the views of the render result (Stereo 3D: left and right; MULTIVIEW:
        the enabled views), read from a probe result as Cycles does."""
        if not scene.render.use_multiview:
            return [""]
        probe = self.begin_result(0, 0, 1, 1, layer=self._layer)
        try:
            names = [view.name for view in probe.views]
        finally:
            self.end_result(probe, cancel=True, do_merge_results=False)
        return names or [""]

    @staticmethod
    def _texture_stats(stats):
        """'textures 1.234 s (3, 2 cached), ' or '' for a scene without image textures."""
        if not stats.textures:
            return ""
        return (f"textures {stats.texture_seconds:.3f} s ({stats.textures}, "
                f"{stats.textures_reused} cached), ")

    def _render_scene(self, native, depsgraph, reporter, native_scene, sync_stats, t_start,
                      view=""):
        """Renders one view into the result; returns False when the render was cancelled."""
        scene = depsgraph.scene
        self._view = view
        if self.test_break():
            return False

        width, height = sync_camera.render_size(scene.render)
        region = sync_camera.render_region(scene.render, width, height)
        settings = make_settings(native, scene, width, height, region)
        region_w, region_h = region[2] - region[0], region[3] - region[1]
        settings.light_passes = bool(self._passes)
        settings.data_passes = data_passes.settings(native, scene, depsgraph.view_layer,
                                                    sync_stats.origin)
        self._missing_passes = set()
        metadata = self._cryptomatte_metadata(sync_stats, self._layer)
        if metadata:
            final = self.get_result()  # the render's own result (not a tile's), as Cycles does
            for key, value in metadata:
                final.stamp_data_add_field(key, value)

        session = native.RenderSession(native_scene, settings,
                                       blas_cache=self._session_blas_cache)
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
                    self._write_tile(0, 0, region_w, region_h, preview, preview=True)
                    RENDER_STATUS["preview_shown"] = True
                for x, y, w, h, rgba, passes, data in session.take_tiles(POLL_SECONDS):
                    self._write_tile(x, region_h - (y + h), w, h, rgba, passes, data)
                    tiles_done += 1
                # Esc (or Ctrl-C in background mode, which Blender turns into test_break())
                # cancels whatever stage runs; test_break() then stays set, so it is read until
                # the first time it is true.
                if cancelled_during is None and self.test_break():
                    cancelled_during = session.status
                    t_cancel = time.perf_counter()
                    session.cancel()
                snapshot = session.snapshot()
                fraction, time_left = bar.update(snapshot["status"], snapshot["preparing"],
                                                 snapshot["progress"], time.perf_counter())
                self.update_progress(fraction)
                RENDER_STATUS.update(status=snapshot["status"], tiles_done=tiles_done,
                                     tiles_total=tiles_total, progress=fraction)
                self.update_stats("", self._stats_line(snapshot["status"], sync_stats,
                                                       min(tiles_done, tiles_total),
                                                       tiles_total, t_start,
                                                       time_left))
                if session.finished:
                    for x, y, w, h, rgba, passes, data in session.take_tiles(0.0):
                        self._write_tile(x, region_h - (y + h), w, h, rgba, passes, data)
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
            self._write_tile(0, 0, region_w, region_h,
                             np.zeros((region_h, region_w, 4), dtype=np.float32), preview=True)
        if cancelled:
            reporter.warning(f"render cancelled (Esc) during '{cancelled_during}', stopped "
                             f"{time.perf_counter() - t_cancel:.3f} s later: the image keeps "
                             f"what was finished ({tiles_done} tiles or parts of tiles of "
                             f"{tiles_total})")

        for message in session.warnings:
            reporter.warning(message)
        if self._missing_passes:
            reporter.warning(f"passes not written by Photon, left at zero: "
                             f"{', '.join(sorted(self._missing_passes))}")
        stats = session.stats
        if stats.non_finite_samples:
            reporter.warning(f"{stats.non_finite_samples} samples were NaN or infinite "
                             f"and were dropped")
        elapsed = time.perf_counter() - t_start
        state = "cancelled" if cancelled else "rendered"
        if prepared_files and prepared_files["prepare_only"] and not cancelled:
            state = "prepared (no pixels: PHOTON_PREPARE_ONLY)"
        reporter.info(
            f"{state} frame {scene.frame_current} {region_w}x{region_h} "
            f"({self._samples_label(settings, stats)}, {stats.threads} threads): sync {sync_stats.seconds:.3f} s "
            f"({sync_stats.triangles} triangles, {sync_stats.instances} instances, "
            f"{sync_stats.lights} lights), {self._texture_stats(stats)}"
            f"BVH {stats.build_seconds:.3f} s, "
            f"render {stats.render_seconds:.3f} s, total {elapsed:.3f} s"
            f"{self._layer_view_label(scene, view)}")
        if prepared_files:
            prepared_state.report(reporter, prepared_files, stats)
        for line in prepare_report(stats.integrator):
            reporter.info(line)
        if stats.sppm.iterations:
            reporter.info(sppm_report(stats.sppm))
        if sync_stats.meshes_reused is not None:
            meshes = sync_stats.meshes_reused + sync_stats.meshes_exported
            reporter.info(f"persistent data: reused {sync_stats.meshes_reused} of {meshes} "
                          f"meshes, {stats.bvh_reused} of {stats.bvh_count} BVHs")
        # Free native memory now rather than when Python collects: -a renders many frames.
        del session, native_scene
        return not cancelled

    @staticmethod
    def _cryptomatte_metadata(sync_stats, layer):
        """[(key, value)] of the Cryptomatte layers' names, hashing and manifests, which the
        result's metadata holds as Cycles writes it (Blender's Cryptomatte node reads it)."""
        crypto = sync_stats.cryptomatte
        if crypto is None or not crypto.any():
            return []
        return crypto.layer_metadata(layer)

    def _layer_view_label(self, scene, view):
        """', view layer 'X', view left' when a frame has several layers or views, else ''."""
        label = ""
        if sum(1 for layer in scene.view_layers if layer.use) > 1:
            label += f", view layer '{self._layer}'"
        if view:
            label += f", view {view}"
        return label

    def _write_tile(self, x, y_bottom, w, h, rgba, light_passes=None, data=None,
                    preview=False):
        """Writes a tile (or, with `preview`, the quick preview: Combined only, the other
        passes zero until their tiles come)."""
        # Native tiles are top row first; Blender's result rows go bottom-up.
        pixels = np.ascontiguousarray(rgba[::-1], dtype=np.float32)
        result = self.begin_result(x, y_bottom, w, h, layer=self._layer, view=self._view)
        passes = result.layers[0].passes
        if len(passes) == 1:
            passes.foreach_set("rect", pixels.ravel())
        else:
            ours = dict(self._passes)
            parts = []
            for render_pass in passes:
                if render_pass.name == "Combined":
                    parts.append(pixels.ravel())
                elif (render_pass.name in ours and light_passes is not None
                      and render_pass.channels == 3):
                    parts.append(np.ascontiguousarray(
                        light_passes[ours[render_pass.name]][::-1], dtype=np.float32).ravel())
                elif (data is not None and render_pass.name in data
                      and data[render_pass.name].shape[2] == render_pass.channels):
                    parts.append(np.ascontiguousarray(data[render_pass.name][::-1],
                                                      dtype=np.float32).ravel())
                else:
                    # Passes Photon does not produce (enabled on the view layer): Blender's
                    # default, zero, and one warning after the render.
                    if not preview:
                        self._missing_passes.add(render_pass.name)
                    parts.append(np.zeros(w * h * render_pass.channels, dtype=np.float32))
            passes.foreach_set("rect", np.concatenate(parts))
        self.end_result(result)

    @staticmethod
    def _samples_label(settings, stats):
        """'64 spp', or 'N SPPM iterations' / 'N VCM iterations' for the iterative ones."""
        if stats.sppm.iterations:
            return f"{stats.sppm.iterations} {settings.integrator} iterations"
        return f"{settings.samples} spp"

    @staticmethod
    def _stats_line(status, sync_stats, tiles_done, tiles_total, t_start, time_left=""):
        left = f" | {time_left}" if time_left else ""
        return (f"Photon | {status} | Tiles {tiles_done}/{tiles_total} | "
                f"Triangles {sync_stats.triangles:,} | Instances {sync_stats.instances:,} | "
                f"Lights {sync_stats.lights} | Time {time.perf_counter() - t_start:.1f} s{left}")


def register():
    bpy.utils.register_class(PhotonRenderEngine)


def unregister():
    bpy.utils.unregister_class(PhotonRenderEngine)
