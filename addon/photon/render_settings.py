"""The scene's settings as the native RenderSettings: scene.photon's schema parameters by name,
the Film (Cycles' own settings when Cycles is enabled), and the viewport's variant of them; and
what the chosen integrator can do. Final renders, the viewport, thumbnails and bakes all start
from make_settings."""

from . import schema

# The viewport final-gathers at every sample (no irradiance cache: its records are placed for
# the scene camera's pixels, and a moving view would keep missing them) with at most this many
# rays per sample; over the viewport's samples the pixel averages as many rays as a final
# render's cached gathers, so the image converges to the same brightness.
VIEWPORT_FINAL_GATHER_RAYS = 4


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


def viewport_settings(native, scene, width, height, region):
    """Render settings of a viewport render (and of thumbnails, which trace fewer photons on
    top): the scene's, at the viewport sample count, final gathering at every sample."""
    settings = make_settings(native, scene, width, height, region)
    settings.samples = max(1, int(scene.photon.preview_samples))
    settings.irradiance_cache = False
    settings.final_gather_rays = min(settings.final_gather_rays, VIEWPORT_FINAL_GATHER_RAYS)
    return settings


def integrator_capabilities(native, scene):
    """What the scene's integrator can do (bake, stop_early, ...), as the native factory says."""
    return native.integrator_capabilities(getattr(native.Integrator, scene.photon.integrator))
