"""Evaluated geometry to native triangle meshes, with numpy foreach_get (no per-vertex loops)."""

import bpy
import numpy as np

from .origin import local_bounds

# Since Blender 3.0 the evaluated geometry of curves, text, surfaces and metaballs reaches render
# engines as a separate instance whose data is a Mesh (the object's own entry keeps its Curve or
# MetaBall data). So an object is geometry exactly when its evaluated data is a Mesh.
def is_geometry(obj):
    return isinstance(obj.data, bpy.types.Mesh)


# Types that carry geometry Photon cannot render yet: reported, not silently dropped (Curves
# objects, the new hair type, are rendered as ribbons by sync_hair).
UNSUPPORTED_GEOMETRY_TYPES = {'VOLUME', 'POINTCLOUD', 'GPENCIL'}


def _get(collection, attribute, dtype, count, components=1):
    if dtype is np.int32:
        # Blender 3.4 stores mesh indices as unsigned ints: foreach_get into a uint32 buffer
        # takes its raw-array path (one memcpy), an int32 buffer the per-item path, ~5x slower
        # on a 1M-triangle mesh. Indices fit in 31 bits, so the int32 view reads the same
        # values (a corrupt one beyond 2^31 turns negative, which the native side rejects too).
        array = np.empty(count * components, dtype=np.uint32)
        collection.foreach_get(attribute, array)
        return array.view(np.int32)
    array = np.empty(count * components, dtype=dtype)
    collection.foreach_get(attribute, array)
    return array


def _shading(mesh):
    """(per-polygon smooth flags, split normals needed). Shading normals: none for all-flat
    meshes (the geometric normal is exact), Blender's split (per-loop) normals for auto smooth
    and custom normals, else computed natively from the polygons (vertex normals where smooth).
    Blender 4.1 replaced Auto Smooth by sharp edges (and a modifier that marks them): its mesh
    says itself whether its normals are per corner."""
    smooth = _get(mesh.polygons, "use_smooth", bool, len(mesh.polygons))
    if hasattr(mesh, "normals_domain"):
        split = mesh.normals_domain == 'CORNER'
    else:
        split = mesh.has_custom_normals or (smooth.any() and mesh.use_auto_smooth)
    return smooth, bool(split)


def loop_normals(mesh, loop_count):
    """Blender's per-corner (split) normals, float32 (loop_count, 3) flattened. Blender 4.1+
    keeps them computed on demand (Mesh.corner_normals); 3.4 computes them into the loops."""
    if hasattr(mesh, "corner_normals"):
        return _get(mesh.corner_normals, "vector", np.float32, loop_count, 3)
    mesh.calc_normals_split()
    return _get(mesh.loops, "normal", np.float32, loop_count, 3)


def _evaluated_mesh(obj):
    """The object's evaluated Mesh when it can be read as is, else None (use to_mesh()).

    A mesh object's evaluated data already holds its final geometry (modifiers applied):
    reading it directly saves to_mesh()'s full copy (a third of the sync time of a
    1M-triangle mesh), as Cycles' object_to_mesh does. The copy is still made in edit mode
    (the evaluated data may then be a wrapper without loop layers) and when split normals
    must be computed, so the depsgraph's data is never written beyond its triangulation cache.
    """
    if obj.type != 'MESH':
        return None
    mesh = obj.data
    if not isinstance(mesh, bpy.types.Mesh) or mesh.is_editmode:
        return None
    # 3.4 writes split normals into the mesh it computes them for; 4.1+ caches them itself.
    if _shading(mesh)[1] and not hasattr(mesh, "corner_normals"):
        return None
    return mesh


# Generic attribute types shader programs read: (foreach_get property, components, dtype).
_ATTRIBUTE_TYPES = {'FLOAT': ("value", 1, np.float32), 'INT': ("value", 1, np.int32),
                    'BOOLEAN': ("value", 1, bool), 'FLOAT2': ("vector", 2, np.float32),
                    'FLOAT_VECTOR': ("vector", 3, np.float32),
                    'FLOAT_COLOR': ("color", 4, np.float32),
                    # Blender stores byte colours sRGB-encoded; "color" reads them linear, as
                    # Cycles decodes them.
                    'BYTE_COLOR': ("color", 4, np.float32)}


def _render_color(mesh):
    """The colour attribute marked for render (the camera icon), else the active one."""
    colors = getattr(mesh, "color_attributes", None)
    if colors is None or len(colors) == 0:
        return None
    index = getattr(colors, "render_color_index", -1)
    if 0 <= index < len(colors):
        return colors[index]
    return colors.active_color


def _attribute_source(mesh, name):
    """(domain, data collection, property, components, dtype) of the attribute `name` of
    `mesh` (a UV map, a colour or generic attribute), or a string saying why it cannot be read,
    or None when the mesh has none of that name."""
    from .shader_program import RENDER_COLOR
    if name == RENDER_COLOR:
        attribute = _render_color(mesh)
    else:
        uv = mesh.uv_layers.get(name)
        if uv is not None:
            return 'CORNER', uv.data, "uv", 2, np.float32
        attribute = mesh.attributes.get(name)
    if attribute is None:
        return None
    kind = _ATTRIBUTE_TYPES.get(attribute.data_type)
    if kind is None:
        return f"its type {attribute.data_type} is not supported"
    if attribute.domain not in ('POINT', 'CORNER', 'FACE'):
        return f"its domain {attribute.domain} is not supported"
    return (attribute.domain, attribute.data) + kind


def attribute_arrays(mesh, names):
    """([(name, float32 array (3 x triangles, components))], [names the mesh lacks],
    [(name, reason) not readable]): the named attributes of `mesh` (loop triangles computed)
    expanded to the corners of its triangles, with numpy gathers."""
    tri_count = len(mesh.loop_triangles)
    corner_index = {}

    def corners(domain):
        if domain not in corner_index:
            if domain == 'CORNER':
                index = _get(mesh.loop_triangles, "loops", np.int32, tri_count, 3)
            elif domain == 'POINT':
                index = _get(mesh.loop_triangles, "vertices", np.int32, tri_count, 3)
            else:
                index = np.repeat(_get(mesh.loop_triangles, "polygon_index", np.int32,
                                       tri_count), 3)
            corner_index[domain] = index
        return corner_index[domain]

    arrays, missing, unreadable = [], [], []
    for name in sorted(names):
        source = _attribute_source(mesh, name)
        if source is None:
            missing.append(name)
            continue
        if isinstance(source, str):
            unreadable.append((name, source))
            continue
        domain, data, prop, components, dtype = source
        values = np.empty(len(data) * components, dtype=dtype)
        data.foreach_get(prop, values)
        values = values.astype(np.float32, copy=False).reshape(-1, components)
        arrays.append((name, np.ascontiguousarray(values[corners(domain)])))
    return arrays, missing, unreadable


def mesh_arrays(mesh, attributes=()):
    """Returns (method name, keyword arguments) for the native Scene, or None without faces.
    `attributes`: names of attributes shader programs read (kwargs "attributes" then holds
    attribute_arrays()).

    Chooses the cheapest foreach_get route (measured on a 1M-triangle grid, Blender 3.4):
    triangle "vertices" costs about as much as triangle "loops", so when UVs or split normals
    need the loops anyway, vertices come from loops -> vertex_index and the per-corner gathers
    happen in C++.
    """
    method, kwargs = _mesh_arrays(mesh)
    if method is None:
        return None
    # Generated coordinates: Blender's texture space (the bounds unless the artist set one).
    kwargs["texspace"] = (tuple(mesh.texspace_location), tuple(mesh.texspace_size))
    if attributes:
        kwargs["attributes"] = attribute_arrays(mesh, attributes)
    return method, kwargs


def _mesh_arrays(mesh):
    mesh.calc_loop_triangles()
    tri_count = len(mesh.loop_triangles)
    if tri_count == 0:
        return None, None
    vertex_count = len(mesh.vertices)
    loop_count = len(mesh.loops)
    positions = _get(mesh.vertices, "co", np.float32, vertex_count, 3)

    material_slots = None
    if len(mesh.materials) > 1:
        material_slots = _get(mesh.loop_triangles, "material_index", np.int32, tri_count)

    poly_smooth, split = _shading(mesh)
    # Smooth polygons without split normals: the vertex normals are computed natively from the
    # polygons, not read from Blender, whose threads sum them in no fixed order (the same mesh
    # then differs in the last bits from one render to the next). Blender's split normals
    # (Auto Smooth, custom normals) are summed fan by fan in a fixed order and are read as is.
    smooth = not split and bool(poly_smooth.any())

    # Image textures without a UV Map node read the layer marked for render (the camera icon
    # in Object Data > UV Maps), as in Cycles; it is usually also the active one.
    uv_layer = next((layer for layer in mesh.uv_layers if layer.active_render),
                    mesh.uv_layers.active)
    has_uvs = uv_layer is not None and len(uv_layer.data) == loop_count
    if not has_uvs and not split and not smooth:
        triangles = _get(mesh.loop_triangles, "vertices", np.int32, tri_count, 3)
        return "add_mesh", {"positions": positions, "triangles": triangles,
                            "material_slots": material_slots}

    corner_loops = _get(mesh.loop_triangles, "loops", np.int32, tri_count, 3)
    loop_vertices = _get(mesh.loops, "vertex_index", np.int32, loop_count)
    kwargs = {"positions": positions, "corner_loops": corner_loops,
              "loop_vertices": loop_vertices, "material_slots": material_slots}
    if split:
        kwargs["loop_normals"] = loop_normals(mesh, loop_count)
    elif smooth:
        poly_count = len(mesh.polygons)
        kwargs["poly_loop_starts"] = _get(mesh.polygons, "loop_start", np.int32, poly_count)
        kwargs["poly_loop_totals"] = _get(mesh.polygons, "loop_total", np.int32, poly_count)
        if not poly_smooth.all():
            kwargs["poly_smooth"] = poly_smooth.view(np.uint8)
    if has_uvs:
        kwargs["loop_uvs"] = _get(uv_layer.data, "uv", np.float32, loop_count, 2)
    return "add_loop_mesh", kwargs


def export_object_mesh(native_scene, obj, reporter, attributes=(), on_missing=None):
    """Converts an evaluated object's geometry with the named `attributes` its materials read
    (on_missing(names) hears of those it lacks); returns (mesh index or None, triangle count,
    (lo, hi) object-space bounds of its vertices in float64)."""
    arrays = object_mesh_arrays(obj, reporter, attributes)
    if arrays is None:
        return None, 0, (None, None)
    return add_mesh_arrays(native_scene, obj.name, arrays, reporter, on_missing)


def object_mesh_arrays(obj, reporter, attributes=()):
    """mesh_arrays() of an evaluated object's geometry, or None (no faces, no mesh)."""
    mesh = _evaluated_mesh(obj)
    if mesh is not None:
        return mesh_arrays(mesh, attributes)
    try:
        mesh = obj.to_mesh()
    except RuntimeError as exc:
        reporter.warning(f"Object '{obj.name}': cannot convert to a mesh ({exc}); skipped")
        return None
    if mesh is None:
        return None
    try:
        return mesh_arrays(mesh, attributes)
    finally:
        obj.to_mesh_clear()


def add_mesh_arrays(native_scene, name, arrays, reporter, on_missing=None):
    """Adds mesh_arrays() output to the native scene; returns as export_object_mesh."""
    method, kwargs = arrays
    kwargs = dict(kwargs)
    texspace = kwargs.pop("texspace", None)
    attributes = kwargs.pop("attributes", None)
    info = getattr(native_scene, method)(name, **kwargs)
    if texspace is not None and info["triangles"]:
        native_scene.set_mesh_texspace(info["index"], list(texspace[0]), list(texspace[1]))
    add_attributes(native_scene, name, info, attributes, reporter, on_missing)
    return mesh_result(name, info, local_bounds(kwargs["positions"]), reporter)


def add_attributes(native_scene, name, info, attributes, reporter, on_missing=None):
    """Adds attribute_arrays() output to the native mesh `info` describes and reports what
    could not be read."""
    if attributes is None:
        return
    arrays, missing, unreadable = attributes
    for attribute, reason in unreadable:
        reporter.warning(f"Object '{name}': attribute '{attribute}' cannot be read by shaders "
                         f"({reason}); it reads as 0")
    if missing and on_missing is not None:
        on_missing(missing)
    if not info["triangles"]:
        return
    for attribute, values in arrays:
        native_scene.add_mesh_attribute(info["index"], attribute, values)


def mesh_result(name, info, bounds, reporter):
    """Reports what the native cleanup dropped (`info` from add_mesh / add_loop_mesh); returns
    (mesh index or None, triangle count, `bounds`)."""
    if info["non_finite_vertices"]:
        reporter.warning(f"Object '{name}': {info['non_finite_vertices']} vertices with "
                         f"NaN or infinite coordinates")
    if info["dropped_triangles"]:
        reporter.warning(f"Object '{name}': dropped {info['dropped_triangles']} degenerate "
                         f"or invalid triangles")
    if info["triangles"] == 0:
        return None, 0, (None, None)
    return info["index"], info["triangles"], bounds
