"""A dense mesh in the Cornell box for bake speed and cancellation tests: the box's walls and
lamp, and a bumpy grid of `triangles` triangles (smooth shaded) as the floor. Bakes its colour
attribute with the photon maps; arguments: triangles [bake_samples]."""

import time

import bpy
import numpy as np

import builders
import harness

ATTRIBUTE = "PhotonLighting"


def bumpy_grid(name, triangles, material):
    """(k + 1)^2 vertices, k^2 quads (2 k^2 triangles) over the box floor, built with
    foreach_set (from_pydata would take minutes at this size)."""
    k = max(2, int(round((triangles / 2) ** 0.5)))
    x, y = np.meshgrid(np.linspace(-0.99, 0.99, k + 1), np.linspace(-0.99, 0.99, k + 1))
    z = 0.02 + 0.015 * np.sin(9.0 * x) * np.cos(7.0 * y)
    co = np.stack([x, y, z], axis=-1).reshape(-1, 3).astype(np.float32)
    i, j = np.meshgrid(np.arange(k), np.arange(k))
    v0 = (j * (k + 1) + i).ravel()
    quads = np.stack([v0, v0 + 1, v0 + k + 2, v0 + k + 1], axis=1).astype(np.int32)
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(co))
    mesh.vertices.foreach_set("co", co.ravel())
    mesh.loops.add(quads.size)
    mesh.loops.foreach_set("vertex_index", quads.ravel())
    mesh.polygons.add(len(quads))
    mesh.polygons.foreach_set("loop_start", np.arange(0, quads.size, 4, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(quads), 4, np.int32))
    mesh.polygons.foreach_set("use_smooth", np.ones(len(quads), bool))
    mesh.update(calc_edges=True)
    mesh.validate()
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def main(triangles="500000", bake_samples="16"):
    scene = builders.cornell_box(width=64, height=64, samples=16)
    for name in ("TallBox", "ShortBox"):
        bpy.data.objects.remove(bpy.data.objects[name])
    scene.photon.photons = 100000
    scene.photon.bake_source = 'PHOTON_MAP'
    scene.photon.bake_target = 'COLOR_ATTRIBUTE'
    scene.photon.bake_samples = int(bake_samples)
    grid = bumpy_grid("Terrain", int(triangles), bpy.data.materials["White"])
    grid.data.calc_loop_triangles()
    corners = len(grid.data.loops) + sum(len(o.data.loops) for o in scene.objects
                                         if o.type == 'MESH' and o is not grid)
    print(f"bake_scale: {len(grid.data.loop_triangles)} triangles, {corners} corners",
          flush=True)
    t0 = time.perf_counter()
    baked = bpy.ops.photon.bake_lighting()
    seconds = time.perf_counter() - t0
    attribute = grid.data.color_attributes.get(ATTRIBUTE)
    result = {"bake": sorted(baked), "seconds": seconds, "corners": corners,
              "triangles": len(grid.data.loop_triangles), "has_attribute": attribute is not None}
    if attribute is not None:
        colors = np.empty(len(attribute.data) * 4, np.float32)
        attribute.data.foreach_get("color", colors)
        colors = colors.reshape(-1, 4)[:, :3]
        result.update(finite=bool(np.isfinite(colors).all()), mean=float(colors.mean()),
                      lit_fraction=float((colors.sum(axis=1) > 0).mean()))
    print(f"bake_scale: {corners / seconds:,.0f} corners/s", flush=True)
    return result


harness.run(main)
