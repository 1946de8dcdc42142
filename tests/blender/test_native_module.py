"""The _photon module on its own (imported into Debian's python3, the Python Blender runs):
cancellation latency, determinism across threads and tiles, and argument validation."""

import time

import numpy as np
import pytest


def cornell_like_scene(native, width, height):
    scene = native.Scene()
    white = scene.add_material("white", [{"type": "DIFFUSE",
                                          "params": {"color": [0.7, 0.7, 0.7]}}])
    # A dense grid floor so the render takes a while.
    n = 200
    xs, ys = np.meshgrid(np.linspace(-1, 1, n + 1), np.linspace(-1, 1, n + 1))
    positions = np.stack([xs.ravel(), ys.ravel(), np.zeros(xs.size)], axis=1).astype(np.float32)
    quads = np.array([[y * (n + 1) + x, y * (n + 1) + x + 1, (y + 1) * (n + 1) + x + 1,
                       (y + 1) * (n + 1) + x] for y in range(n) for x in range(n)])
    tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]).astype(np.int32)
    mesh = scene.add_mesh("floor", positions, tris)
    scene.add_instance(mesh["index"], np.identity(4, dtype=np.float32), [white])
    light = np.identity(4, dtype=np.float32)
    light[2, 3] = 1.0
    scene.add_light("lamp", "AREA", light, [1, 1, 1], 50.0, shape="SQUARE", size_x=0.5)
    cam = np.identity(4, dtype=np.float32)
    cam[2, 3] = 3.0
    scene.set_camera("PERSP", cam, [-0.4, 0.4, -0.4 * height / width, 0.4 * height / width],
                     0.01, 100.0)
    settings = native.RenderSettings()
    settings.full_width, settings.full_height = width, height
    settings.x0, settings.y0, settings.x1, settings.y1 = 0, 0, width, height
    return scene, settings


def render(native, scene, settings):
    session = native.RenderSession(scene, settings)
    session.start()
    session.wait()
    assert session.finished and not session.cancelled
    return session.image()


@pytest.mark.serial  # a wall-time bound
def test_cancel_stops_within_half_a_second(native):
    scene, settings = cornell_like_scene(native, 1024, 1024)
    settings.samples = 4096  # minutes of work if not cancelled
    session = native.RenderSession(scene, settings)
    session.start()
    time.sleep(0.3)
    t0 = time.perf_counter()
    session.cancel()
    while not session.finished:
        session.take_tiles(0.01)
    latency = time.perf_counter() - t0
    print(f"cancel latency {latency * 1000:.1f} ms")
    assert latency < 0.5
    assert session.cancelled


def test_same_seed_same_image_for_any_threads_and_tiles(native):
    scene, settings = cornell_like_scene(native, 96, 64)
    settings.samples = 8
    images = []
    for threads, tile in ((1, 64), (2, 16), (0, 7)):
        settings.threads, settings.tile_size = threads, tile
        images.append(render(native, scene, settings))
    assert images[0].mean() > 0.01
    for other in images[1:]:
        np.testing.assert_array_equal(images[0], other)
    settings.seed = 7
    assert not np.array_equal(render(native, scene, settings), images[0])


def test_tiles_cover_the_region_exactly_once(native):
    scene, settings = cornell_like_scene(native, 100, 70)
    settings.tile_size = 32
    session = native.RenderSession(scene, settings)
    session.start()
    covered = np.zeros((70, 100), dtype=int)
    while True:
        for x, y, w, h, rgba, _passes in session.take_tiles(0.05):
            assert rgba.shape == (h, w, 4)
            covered[y:y + h, x:x + w] += 1
        if session.finished:
            for x, y, w, h, rgba, _passes in session.take_tiles(0.0):
                covered[y:y + h, x:x + w] += 1
            break
    assert (covered == 1).all()


def test_bad_arguments_raise_instead_of_crashing(native):
    scene = native.Scene()
    with pytest.raises(ValueError):
        scene.add_mesh("bad", np.zeros(7, np.float32), np.zeros(3, np.int32))
    with pytest.raises(ValueError):
        scene.add_light("l", "NOT_A_LIGHT", np.identity(4, dtype=np.float32), [1, 1, 1], 1.0)
    with pytest.raises(IndexError):
        scene.add_instance(3, np.identity(4, dtype=np.float32))
    info = scene.add_mesh("negative", np.zeros(9, np.float32), np.array([0, -1, 2], np.int32))
    assert info["dropped_triangles"] == 1 and info["triangles"] == 0
