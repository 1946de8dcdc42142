"""Material, light and world thumbnails (RenderEngine.is_preview): Blender's preview scene
rendered with Photon on the native ProgressiveSession, quickly: the viewport's sample count and
few photons."""

from . import render_settings, report, sync
from .native import native_module
from .passes import TileWriter
from .sync import camera as sync_camera
from .sync.cancel import SyncCancelled

# Material/light/world thumbnails: a few photons are plenty at 128 px.
PREVIEW_PHOTONS = 20000
PREVIEW_CAUSTIC_PHOTONS = 10000

# Preview thumbnails rendered to the end (tests).
previews_rendered = 0


def _settings(native, scene, width, height):
    """The viewport's render settings, tracing fewer photons."""
    settings = render_settings.viewport_settings(native, scene, width, height,
                                                 (0, 0, width, height))
    settings.photons = min(settings.photons, PREVIEW_PHOTONS)
    settings.caustic_photons = min(settings.caustic_photons, PREVIEW_CAUSTIC_PHOTONS)
    settings.photon_time = 0.0
    return settings


def render(engine, depsgraph):
    """Renders Blender's preview scene progressively into the result."""
    native = native_module()
    scene = depsgraph.scene
    reporter = report.Reporter(None)
    width, height = sync_camera.render_size(scene.render)
    try:
        # Blender cancels a thumbnail's job when another one replaces it (test_break).
        native_scene, stats = sync.sync_scene(native, depsgraph, reporter,
                                              test_break=engine.test_break)
    except SyncCancelled:
        return
    try:
        settings = _settings(native, scene, width, height)
        session = native.ProgressiveSession(native_scene, settings)
        session.start()
        # The whole image into the result; other passes left black.
        writer = TileWriter(engine)
        shown = None
        try:
            while True:
                if engine.test_break():
                    break
                samples = session.wait_for_samples(settings.samples, 0.05)
                image = session.image()
                if image is not None and image[0].shape[:2] != (height, width):
                    image = None  # a coarse first look: the thumbnail waits for a full pass
                if image is not None and image[1:3] != shown:
                    writer.write(0, 0, width, height, image[0], preview=True)
                    shown = image[1:3]
                if samples >= settings.samples or session.finished:
                    global previews_rendered
                    previews_rendered += 1
                    break
        finally:
            session.cancel()
            session.wait()
    finally:
        stats.release()
