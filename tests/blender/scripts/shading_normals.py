"""Syncs meshes of every shading kind into a native scene and reports, per mesh, how far the
native shading normals are from Blender's own loop normals and a hash of their bits (the test
runs this in two Blender processes: equal meshes must give equal bits)."""

import hashlib

import bpy
import numpy as np

import builders
import harness


def make_objects():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    objects = {}
    # Built from explicit data: Blender's UV sphere operator orders loops differently from
    # one process to the next.
    sphere = builders.uv_sphere("Sphere", (0, 0, 0), 1.0, segments=96, rings=48)
    sphere.data.uv_layers.new(name="UVMap")
    objects["smooth_uv"] = sphere
    bpy.ops.mesh.primitive_monkey_add(location=(3, 0, 0))
    monkey = bpy.context.active_object
    monkey.data.polygons.foreach_set("use_smooth", [True] * len(monkey.data.polygons))
    monkey.modifiers.new("Subdivision", 'SUBSURF').levels = 2
    objects["smooth_subsurf_no_uv"] = monkey
    bpy.ops.mesh.primitive_monkey_add(location=(6, 0, 0))
    mixed = bpy.context.active_object
    mixed.data.polygons.foreach_set("use_smooth",
                                    [i % 3 != 0 for i in range(len(mixed.data.polygons))])
    objects["mixed"] = mixed
    bpy.ops.mesh.primitive_cylinder_add(vertices=12, location=(9, 0, 0))
    cylinder = bpy.context.active_object  # n-gon caps, quads around
    cylinder.data.polygons.foreach_set("use_smooth", [True] * len(cylinder.data.polygons))
    objects["smooth_ngons"] = cylinder
    bpy.ops.mesh.primitive_cylinder_add(location=(12, 0, 0))
    auto = bpy.context.active_object
    auto.data.polygons.foreach_set("use_smooth", [True] * len(auto.data.polygons))
    builders.set_auto_smooth(auto.data)
    objects["auto_smooth"] = auto
    for obj in objects.values():
        obj.data.update()
    return objects


def blender_loop_normals(obj, depsgraph):
    """Blender's normal of each loop (face corner)."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        normals = np.empty(3 * len(mesh.loops), dtype=np.float32)
        if hasattr(mesh, "corner_normals"):  # Blender 4.1+
            mesh.corner_normals.foreach_get("vector", normals)
        else:
            mesh.calc_normals_split()
            mesh.loops.foreach_get("normal", normals)
        return normals.reshape(-1, 3)
    finally:
        evaluated.to_mesh_clear()


def main():
    from photon import _photon, report
    from photon.sync import mesh as sync_mesh
    objects = make_objects()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    native = _photon.Scene()
    reporter = report.Reporter()
    result = {}
    for label, obj in objects.items():
        arrays = sync_mesh.object_mesh_arrays(obj.evaluated_get(depsgraph), reporter)
        index, triangles, _ = sync_mesh.add_mesh_arrays(native, label, arrays, reporter)
        ours = native.mesh_corner_normals(index)
        # Compared corner by corner through the loops the sync triangulated with.
        theirs = blender_loop_normals(obj, depsgraph)[arrays[1]["corner_loops"]]
        cosine = np.sum(ours * theirs, axis=1) / np.maximum(
            np.linalg.norm(ours, axis=1) * np.linalg.norm(theirs, axis=1), 1e-30)
        result[label] = {
            "triangles": triangles, "rows": len(ours), "expected_rows": len(theirs),
            "min_cosine": float(cosine.min()) if len(cosine) else None,
            "hash": hashlib.sha256(np.ascontiguousarray(ours).tobytes()).hexdigest(),
            "input_hash": hashlib.sha256(b"".join(
                np.ascontiguousarray(arrays[1][key]).tobytes()
                for key in ("positions", "loop_vertices", "corner_loops"))).hexdigest()}
    result["warnings"] = reporter.warnings
    return result


harness.run(main)
