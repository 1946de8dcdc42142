"""The render and bake statistics are typed objects (RenderStats, PrepareStats and its groups,
BakeStats) whose fields the integrators fill: a photon-map render fills the photon-map and
irradiance-cache groups, a radiosity render the radiosity group, a ray-traced render none."""

import numpy as np
import pytest


def box_scene(native, size=32):
    """A box of five diffuse walls (open towards -y) lit by a small area lamp under its
    ceiling, seen from the open side."""
    scene = native.Scene()
    white = scene.add_material("white", [{"type": "DIFFUSE",
                                          "params": {"color": [0.7, 0.7, 0.7]}}])
    positions = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                          [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], np.float32)
    faces = [[0, 1, 2, 3], [4, 7, 6, 5], [3, 2, 6, 7], [0, 3, 7, 4], [1, 5, 6, 2]]
    tris = np.array([t for a, b, c, d in faces for t in ([a, b, c], [a, c, d])], np.int32)
    mesh = scene.add_mesh("box", positions.ravel(), tris.ravel())
    scene.add_instance(mesh["index"], np.identity(4, dtype=np.float32), [white])
    lamp = np.identity(4, dtype=np.float32)
    lamp[2, 3] = 0.9  # an area lamp emits along its -z: down
    scene.add_light("lamp", "AREA", lamp, [1, 1, 1], 50.0, shape="SQUARE", size_x=0.4)
    cam = np.array([[1, 0, 0, 0], [0, 0, -1, -4], [0, 1, 0, 0], [0, 0, 0, 1]], np.float32)
    scene.set_camera("PERSP", cam, [-0.3, 0.3, -0.3, 0.3], 0.01, 100.0)
    settings = native.RenderSettings()
    settings.full_width = settings.full_height = size
    settings.x0, settings.y0, settings.x1, settings.y1 = 0, 0, size, size
    settings.samples = 2
    return scene, settings, mesh


def render_stats(native, integrator, **overrides):
    scene, settings, _ = box_scene(native)
    settings.integrator = integrator
    for name, value in overrides.items():
        setattr(settings, name, value)
    session = native.RenderSession(scene, settings)
    session.start()
    session.wait()
    assert session.finished and not session.cancelled, session.warnings
    assert session.image()[..., :3].mean() > 0.0
    return session.stats


def test_ray_trace_render_has_render_stats_and_no_prepare_groups(native):
    stats = render_stats(native, native.Integrator.RAY_TRACE)
    assert isinstance(stats, native.RenderStats)
    assert stats.threads > 0 and stats.render_seconds > 0.0 and stats.camera_samples > 0
    assert stats.unique_triangles == 10 and stats.lights == 1
    prepared = stats.integrator
    assert isinstance(prepared, native.PrepareStats)
    assert prepared.photon_map is None and prepared.irradiance_cache is None
    assert prepared.radiosity is None and prepared.bake_irradiance_cache is None
    with pytest.raises(AttributeError):
        stats.threads = 3  # read-only


def test_photon_map_render_fills_the_photon_map_and_irradiance_cache(native):
    stats = render_stats(native, native.Integrator.PHOTON_MAP, photons=20000,
                         caustic_photons=1000)
    pm = stats.integrator.photon_map
    assert isinstance(pm, native.PhotonMapStats)
    assert pm.photons_emitted >= 20000 and isinstance(pm.photons_emitted, int)
    assert 0 < pm.global_photons_stored and pm.photon_rays > 0
    assert pm.caustic_photons_stored == 0  # no specular surface to focus light
    assert pm.radiance_points > 0 and pm.photon_map_bytes > 0
    assert pm.global_gather_radius > 0.0 and pm.caustic_gather_radius > 0.0
    assert pm.radiance_cell_size > 0.0
    assert pm.photon_trace_seconds > 0.0 and pm.photon_map_build_seconds >= 0.0
    cache = stats.integrator.irradiance_cache
    assert isinstance(cache, native.IrradianceCacheStats)
    assert cache.records > 0 and cache.gather_rays > 0 and cache.bytes > 0
    assert cache.candidates >= cache.records and cache.seconds > 0.0
    assert stats.integrator.radiosity is None


def test_radiosity_render_fills_the_radiosity_group(native):
    stats = render_stats(native, native.Integrator.RADIOSITY, radiosity_rays=200000)
    r = stats.integrator.radiosity
    assert isinstance(r, native.RadiosityStats)
    assert r.patches > 0 and r.elements >= r.patches and r.vertices > 0
    assert r.patch_size > 0.0 and r.area == pytest.approx(20.0, rel=1e-3)  # five 2 x 2 walls
    assert r.rays > 0 and r.rays_per_second > 0.0 and r.solve_seconds > 0.0
    assert r.shooting_iterations + r.averaged_iterations > 0
    assert 0.0 < r.emitted_power <= 50.0  # at most the lamp's 50 W
    assert 0.0 < r.absorbed_power <= r.emitted_power
    assert stats.integrator.photon_map is None


def test_photon_map_bake_stats_are_typed(native):
    scene, settings, mesh = box_scene(native)
    settings.integrator = native.Integrator.PHOTON_MAP
    settings.photons = 20000
    n = 64
    instances = np.zeros(n, np.int32)
    triangles = (np.arange(n) % 10).astype(np.int32)
    bary = np.full((n, 2), 1.0 / 3.0, np.float32)
    result = native.bake(scene, settings, instances, triangles, bary.ravel())
    stats = result["stats"]
    assert isinstance(stats, native.BakeStats)
    assert stats.threads > 0 and stats.bake_seconds > 0.0 and stats.prepare_seconds > 0.0
    assert stats.integrator.photon_map.global_photons_stored > 0
    cache = stats.integrator.bake_irradiance_cache
    assert cache is not None and cache.records > 0 and cache.seconds > 0.0
