"""Syncs meshes of every shading kind both through the evaluated mesh as is (the fast path) and
through a to_mesh() copy, and reports whether the native arrays agree and which path each
object took."""

import bpy
import numpy as np

import harness


def make_objects():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    objects = {}
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, calc_uvs=True)
    sphere = bpy.context.active_object
    sphere.data.polygons.foreach_set("use_smooth", [True] * len(sphere.data.polygons))
    objects["smooth_uv"] = sphere
    bpy.ops.mesh.primitive_cube_add(location=(3, 0, 0))
    cube = bpy.context.active_object
    cube.modifiers.new("Subdivision", 'SUBSURF').levels = 2
    objects["flat_subsurf"] = cube
    bpy.ops.mesh.primitive_monkey_add(location=(6, 0, 0))
    monkey = bpy.context.active_object
    flags = [i % 2 == 0 for i in range(len(monkey.data.polygons))]
    monkey.data.polygons.foreach_set("use_smooth", flags)  # a mix: split normals
    objects["mixed"] = monkey
    bpy.ops.mesh.primitive_cylinder_add(location=(9, 0, 0))
    cylinder = bpy.context.active_object
    cylinder.data.polygons.foreach_set("use_smooth", [True] * len(cylinder.data.polygons))
    cylinder.data.use_auto_smooth = True
    for name in ("A", "B"):
        cylinder.data.materials.append(bpy.data.materials.new(name))
    cylinder.data.polygons.foreach_set(
        "material_index", [i % 2 for i in range(len(cylinder.data.polygons))])
    objects["auto_smooth_two_materials"] = cylinder
    for obj in objects.values():
        obj.data.update()
    return objects


def arrays_of(mesh):
    from photon.sync import mesh as sync_mesh
    method, kwargs = sync_mesh.mesh_arrays(mesh)
    return method, {k: (None if v is None else np.asarray(v).tolist()) for k, v in kwargs.items()}


def main():
    from photon.sync import mesh as sync_mesh
    objects = make_objects()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    result = {}
    for label, obj in objects.items():
        evaluated = obj.evaluated_get(depsgraph)
        copy = evaluated.to_mesh()
        try:
            expected = arrays_of(copy)
        finally:
            evaluated.to_mesh_clear()
        direct = sync_mesh._evaluated_mesh(evaluated)
        got = arrays_of(direct) if direct is not None else expected
        result[label] = {"fast_path": direct is not None, "same": got == expected,
                         "method": got[0]}
        # The int32 view of a uint32 foreach_get equals an int32 foreach_get.
        mesh = evaluated.data
        mesh.calc_loop_triangles()
        reference = np.empty(3 * len(mesh.loop_triangles), dtype=np.int32)
        mesh.loop_triangles.foreach_get("loops", reference)
        viewed = sync_mesh._get(mesh.loop_triangles, "loops", np.int32, len(mesh.loop_triangles), 3)
        result[label]["indices_equal"] = bool(viewed.dtype == np.int32 and
                                              np.array_equal(viewed, reference))
    return result


harness.run(main)
