"""Evaluated geometry to native triangle meshes, with numpy foreach_get (no per-vertex loops)."""

import bpy
import numpy as np

# Since Blender 3.0, curve and text objects hand their evaluated mesh to render engines as a
# separate instance whose data is a Mesh; surfaces and metaballs still evaluate on the object.
# So: an object is geometry when its evaluated data is a Mesh, or it is a surface or metaball.
TO_MESH_TYPES = {'SURFACE', 'META'}
# Types that carry geometry Photon cannot render yet: reported, not silently dropped.
UNSUPPORTED_GEOMETRY_TYPES = {'VOLUME', 'POINTCLOUD', 'CURVES', 'GPENCIL'}


def is_geometry(obj):
    data = obj.data
    return data is not None and (isinstance(data, bpy.types.Mesh) or obj.type in TO_MESH_TYPES)


def mesh_arrays(mesh):
    """Returns the arrays the native Scene.add_mesh takes, or None for a mesh without faces."""
    mesh.calc_loop_triangles()
    tri_count = len(mesh.loop_triangles)
    if tri_count == 0:
        return None
    vertex_count = len(mesh.vertices)

    positions = np.empty(vertex_count * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", positions)
    triangles = np.empty(tri_count * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", triangles)
    material_slots = np.empty(tri_count, dtype=np.int32)
    mesh.loop_triangles.foreach_get("material_index", material_slots)

    # Flat-shaded meshes need no normals: the native side uses the geometric normal. Smooth,
    # auto-smooth and custom normals all come out right from the split normals.
    corner_normals = None
    smooth = np.empty(len(mesh.polygons), dtype=bool)
    mesh.polygons.foreach_get("use_smooth", smooth)
    if mesh.has_custom_normals or smooth.any():
        mesh.calc_normals_split()
        corner_normals = np.empty(tri_count * 9, dtype=np.float32)
        mesh.loop_triangles.foreach_get("split_normals", corner_normals)

    corner_uvs = None
    uv_layer = mesh.uv_layers.active
    if uv_layer is not None and len(uv_layer.data) == len(mesh.loops):
        loops = np.empty(tri_count * 3, dtype=np.int32)
        mesh.loop_triangles.foreach_get("loops", loops)
        loop_uvs = np.empty(len(mesh.loops) * 2, dtype=np.float32)
        uv_layer.data.foreach_get("uv", loop_uvs)
        corner_uvs = loop_uvs.reshape(-1, 2)[loops]

    return {
        "positions": positions,
        "triangles": triangles,
        "corner_normals": corner_normals,
        "corner_uvs": corner_uvs,
        "material_slots": material_slots,
    }


def export_object_mesh(native_scene, obj, reporter):
    """Converts an evaluated object's geometry; returns (mesh index or None, triangle count)."""
    try:
        mesh = obj.to_mesh()
    except RuntimeError as exc:
        reporter.warning(f"Object '{obj.name}': cannot convert to a mesh ({exc}); skipped")
        return None, 0
    if mesh is None:
        return None, 0
    try:
        arrays = mesh_arrays(mesh)
    finally:
        obj.to_mesh_clear()
    if arrays is None:
        return None, 0
    info = native_scene.add_mesh(obj.name, **arrays)
    if info["non_finite_vertices"]:
        reporter.warning(f"Object '{obj.name}': {info['non_finite_vertices']} vertices with "
                         f"NaN or infinite coordinates")
    if info["dropped_triangles"]:
        reporter.warning(f"Object '{obj.name}': dropped {info['dropped_triangles']} degenerate "
                         f"or invalid triangles")
    if info["triangles"] == 0:
        return None, 0
    return info["index"], info["triangles"]
