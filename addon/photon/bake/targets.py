"""Which objects a lighting bake writes to, and the surface points it shades for each: one per
face corner (for the Color Attribute) and one per covered lightmap texel.

Points are (native instance, loop triangle, barycentrics) of the evaluated mesh, the same
triangles sync handed to the native scene. Results are written to the original mesh, so an
object is baked only when its evaluated mesh has the original's vertices, faces and corners
(deforming modifiers are fine; modifiers that change topology, like Subdivision, are not:
apply them first).
"""

import numpy as np

from ..native import native_module
from ..sync.mesh import loop_normals

# Corner points are shaded this fraction of the way from the corner to the triangle's centre:
# exactly at a vertex a point would lie on the neighbouring faces too (wall corners), where
# shadow rays graze them.
CORNER_PULL = 0.002
NORMAL_QUANTUM = 1.0 / 1024.0  # split normals closer than this count as the same
# Lightmap texels shaded per object at most (a 1448 x 1448 map fully covered): a larger map is
# shaded at half, quarter, ... resolution and upsampled, which keeps time and memory bounded
# (an 8192 x 8192 map would be 67M points, tens of GB of intermediate arrays).
MAX_SHADED_TEXELS = 1 << 21


def _get(collection, attribute, dtype, count, components=1):
    array = np.empty(count * components, dtype=dtype)
    collection.foreach_get(attribute, array)
    return array.reshape(count, components) if components > 1 else array


class PointSet:
    """Points of one kind for one object; `start` is set when the job concatenates them."""

    def __init__(self, triangles, barycentrics):
        self.triangles = np.ascontiguousarray(triangles, np.int32)
        self.barycentrics = np.ascontiguousarray(barycentrics, np.float32)
        self.start = 0


class Corners(PointSet):
    def __init__(self, triangles, barycentrics, point_groups, groups):
        super().__init__(triangles, barycentrics)
        self.point_groups = point_groups  # (P,) the (vertex, split normal) group of each point
        self.groups = groups              # (L,) the group of each loop
        self.loop_count = len(groups)


class Lightmap(PointSet):
    def __init__(self, triangles, barycentrics, texels, world_size, size, full_size):
        super().__init__(triangles, barycentrics)
        self.texels = texels
        self.world_size = world_size
        self.size = size            # resolution the texels are shaded at
        self.full_size = full_size  # resolution of the image (an integer multiple of size)


class Target:
    def __init__(self, obj, instance):
        self.object = obj
        self.name = obj.name
        self.mesh = obj.data
        self.instance = instance
        self.corners = None
        self.lightmap = None

    def parts(self):
        return [p for p in (self.corners, self.lightmap) if p is not None]


def corner_points(corner_loops, loop_vertex, normals):
    """One point per (vertex, split normal) group: the corners that share a vertex and a normal
    get one value (smooth and flat-but-coplanar parts are continuous, corners on two sides of a
    hard edge keep their own), so one point is shaded for all of them, in a loop triangle
    that uses the group (a quad mesh has about a quarter as many groups as corners)."""
    normals = np.nan_to_num(normals, nan=0.0, posinf=0.0, neginf=0.0)
    quantised = np.round(normals / NORMAL_QUANTUM).astype(np.int64)
    # One int64 key per loop: vertex and normal packed (normals are within [-1024, 1024]).
    keys = (loop_vertex.astype(np.int64) << 36) | ((quantised[:, 0] + 2048) << 24) \
        | ((quantised[:, 1] + 2048) << 12) | (quantised[:, 2] + 2048)
    _, groups = np.unique(keys, return_inverse=True)
    groups = groups.ravel()
    flat_groups = groups[corner_loops.ravel()]
    # One (triangle, corner) entry per group: with repeated indices, numpy's assignment keeps
    # one of the values, the same one every time (any corner of the group will do).
    entry = np.full(int(groups.max()) + 1 if len(groups) else 0, -1, np.int64)
    entry[flat_groups] = np.arange(len(flat_groups))
    point_groups = np.flatnonzero(entry >= 0)
    first = entry[point_groups]
    triangles = first // 3
    corner = first % 3
    pull = CORNER_PULL / 3.0
    bary = np.full((len(point_groups), 2), pull, np.float32)
    bary[corner == 1, 0] = 1.0 - CORNER_PULL + pull
    bary[corner == 2, 1] = 1.0 - CORNER_PULL + pull
    return Corners(triangles, bary, point_groups, groups)


def _topology_matches(mesh, evaluated):
    return (len(mesh.vertices) == len(evaluated.vertices)
            and len(mesh.polygons) == len(evaluated.polygons)
            and len(mesh.loops) == len(evaluated.loops))


def _unwrap(context, obj, size):
    """Unwraps the active UV map of `obj`: Smart UV Project (one chart per flat region, with
    margins of about three texels), or Lightmap Pack when Smart UV Project cannot run. Lightmap
    Pack gives every face its own chart, which wastes the map on finely subdivided meshes."""
    import bpy

    view_layer = context.view_layer
    previous_active = view_layer.objects.active
    override = dict(active_object=obj, object=obj, edit_object=obj, selected_objects=[obj],
                    selected_editable_objects=[obj])
    try:
        view_layer.objects.active = obj
        with context.temp_override(**override):
            bpy.ops.object.mode_set(mode='EDIT')
            try:
                bpy.ops.mesh.select_all(action='SELECT')
                bpy.ops.uv.smart_project(angle_limit=1.15192, island_margin=min(0.1, 3.0 / size),
                                         area_weight=0.0, correct_aspect=True,
                                         scale_to_bounds=False)
            finally:
                bpy.ops.object.mode_set(mode='OBJECT')
        return "Smart UV Project"
    except Exception:  # noqa: BLE001 - e.g. an object that cannot enter edit mode
        with context.temp_override(**override):
            bpy.ops.uv.lightmap_pack(PREF_CONTEXT='ALL_FACES', PREF_PACK_IN_ONE=True,
                                     PREF_NEW_UVLAYER=False, PREF_APPLY_IMAGE=False,
                                     PREF_MARGIN_DIV=min(1.0, 300.0 / size))
        return "Lightmap Pack"
    finally:
        view_layer.objects.active = previous_active


def ensure_lightmap_uv(context, obj, name, size, reporter):
    """The mesh's UV map `name`, unwrapped with Blender's own operators when it does not exist."""
    mesh = obj.data
    layer = mesh.uv_layers.get(name)
    if layer is not None:
        return layer
    previous = mesh.uv_layers.active
    previous_name = previous.name if previous is not None else None
    layer = mesh.uv_layers.new(name=name, do_init=False)
    if layer is None:
        reporter.warning(f"Object '{obj.name}': cannot add UV map '{name}' (too many UV maps); "
                         f"no lightmap")
        return None
    mesh.uv_layers.active = layer
    method = None
    try:
        method = _unwrap(context, obj, size)
    except Exception as exc:  # noqa: BLE001 - a failed unwrap must not stop the bake
        reporter.warning(f"Object '{obj.name}': cannot unwrap a lightmap UV map ({exc}); "
                         f"no lightmap")
        mesh.uv_layers.remove(mesh.uv_layers[name])
    if previous_name is not None and previous_name in mesh.uv_layers:
        mesh.uv_layers.active = mesh.uv_layers[previous_name]
    if method is not None:
        reporter.info(f"Object '{obj.name}': created UV map '{name}' with {method}")
    return mesh.uv_layers.get(name)


def shading_size(triangle_uvs, size):
    """The lightmap resolution whose covered texels (estimated from the UV area) stay within
    MAX_SHADED_TEXELS: `size` halved as often as needed."""
    e1 = triangle_uvs[:, 1] - triangle_uvs[:, 0]
    e2 = triangle_uvs[:, 2] - triangle_uvs[:, 0]
    area = np.nan_to_num(0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])).sum()
    covered = min(float(area), 1.0) * size * size
    shaded = size
    while shaded > 256 and covered * (shaded / size) ** 2 > MAX_SHADED_TEXELS:
        shaded //= 2
    return shaded, int(covered)


def lightmap_points(native, mesh, layer_name, corner_loops, world_corners, size, name,
                    reporter):
    uv = _get(mesh.uv_layers[layer_name].data, "uv", np.float32, len(mesh.loops), 2)
    triangle_uvs = np.ascontiguousarray(uv[corner_loops], np.float32)
    shaded, covered = shading_size(triangle_uvs, size)
    if shaded < size:
        reporter.info(f"Object '{name}': its {size} x {size} lightmap covers about "
                      f"{covered:,} texels; shaded at {shaded} x {shaded} (at most "
                      f"{MAX_SHADED_TEXELS:,} texels are shaded per object) and upsampled")
    texels, triangles, bary, world_size = native.rasterize_uv(
        triangle_uvs, np.ascontiguousarray(world_corners, np.float32), shaded, shaded)
    return Lightmap(triangles, bary, texels, world_size, shaded, size)


# A colour attribute holds one value per (vertex, normal) group: an object baked with fewer
# points than this loses the shadows and light changes across its faces.
COARSE_BAKE_POINTS = 64


def coarse_bake_warning(coarse):
    """One line for every object a colour-attribute bake stores too few values for
    (coarse: [(object name, points)]), or None."""
    if not coarse:
        return None
    coarse = sorted(coarse, key=lambda c: (c[1], c[0]))
    examples = ", ".join(f"'{name}' {points}" for name, points in coarse[:3])
    more = f" and {len(coarse) - 3} more" if len(coarse) > 3 else ""
    return (f"{len(coarse)} object(s) have fewer than {COARSE_BAKE_POINTS} points to hold baked "
            f"lighting ({examples}{more}): a colour attribute keeps one value per vertex, so "
            f"shadows across their faces are lost; subdivide them or set Bake Target to "
            f"Lightmap")


def collect(context, depsgraph, object_instances, props, want_attribute, want_lightmap,
            reporter, origin=None):
    """Targets for every visible mesh object with faces; warns about the others. `origin` is
    the world origin offset of the synced native scene (SyncStats.origin): lightmap corners are
    placed in its coordinates, as the positions the native bake returns are."""
    import bpy

    native = native_module()
    size = int(props.lightmap_size)
    targets = []
    coarse = []  # (name, points) of colour-attribute targets with too few points
    owners = {}  # mesh name -> object that got it (one attribute per mesh)
    names = sorted({obj.name for obj in depsgraph.objects if obj.type == 'MESH'}
                   | set(object_instances))
    for name in names:
        obj = bpy.data.objects.get(name)
        if obj is None:
            continue
        if obj.type != 'MESH':
            reporter.warning(f"Object '{name}' is a {obj.type.lower()}: baked lighting is "
                             f"stored on mesh objects only; skipped")
            continue
        if name not in object_instances:
            reporter.warning(f"Object '{name}': no faces to bake; skipped")
            continue
        mesh = obj.data
        if mesh.library is not None:
            reporter.warning(f"Object '{name}': its mesh is linked from a library and cannot "
                             f"be written; skipped")
            continue
        if mesh.name in owners:
            reporter.warning(f"Object '{name}' shares mesh '{mesh.name}' with "
                             f"'{owners[mesh.name]}', which holds the baked lighting; make the "
                             f"mesh single-user to bake both")
            continue

        evaluated_obj = obj.evaluated_get(depsgraph)
        evaluated = evaluated_obj.to_mesh()
        try:
            if evaluated is None or not _topology_matches(mesh, evaluated):
                reporter.warning(
                    f"Object '{name}': its modifiers change the mesh topology, so baked values "
                    f"cannot be stored on the original mesh; skipped (apply the modifiers to "
                    f"bake it)")
                continue
            evaluated.calc_loop_triangles()
            tri_count = len(evaluated.loop_triangles)
            loop_count = len(evaluated.loops)
            corner_loops = _get(evaluated.loop_triangles, "loops", np.int32, tri_count, 3)
            loop_vertex = _get(evaluated.loops, "vertex_index", np.int32, loop_count)
            normals = loop_normals(evaluated, loop_count).reshape(loop_count, 3)
            positions = _get(evaluated.vertices, "co", np.float32, len(evaluated.vertices), 3)
        finally:
            evaluated_obj.to_mesh_clear()
        if tri_count == 0:
            reporter.warning(f"Object '{name}': no faces to bake; skipped")
            continue
        owners[mesh.name] = name
        target = Target(obj, object_instances[name][0])
        if want_attribute:
            target.corners = corner_points(corner_loops, loop_vertex, normals)
            points = len(target.corners.point_groups)
            if not want_lightmap and points < COARSE_BAKE_POINTS:
                coarse.append((name, points))
        if want_lightmap and ensure_lightmap_uv(context, obj, props.lightmap_uv_name, size,
                                                reporter) is not None:
            matrix = np.array(obj.matrix_world, np.float32)
            # The translation rebased in double (exact for a zero origin), then float32.
            translation = np.array(obj.matrix_world, np.float64)[:3, 3]
            if origin is not None:
                translation = translation - origin
            world = (np.nan_to_num(positions) @ matrix[:3, :3].T
                     + translation.astype(np.float32))
            target.lightmap = lightmap_points(native, mesh, props.lightmap_uv_name,
                                              corner_loops, world[loop_vertex[corner_loops]],
                                              size, name, reporter)
        if target.parts():
            targets.append(target)
    warning = coarse_bake_warning(coarse)
    if warning:
        reporter.warning(warning)
    return targets
