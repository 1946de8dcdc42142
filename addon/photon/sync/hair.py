"""Hair (particle hair systems and Curves objects) as camera-facing ribbons of triangles.

Each strand is a polyline of points with a radius; each segment becomes a quad of two triangles
spanning the strand's width at its ends, turned to face the camera (the side vector is
tangent x view direction), as ribbon-based hair renderers draw thin strands. The ribbons go
through the ordinary mesh path with the particle system's (or Curves object's) material.

Strand thickness follows Cycles 3.4 (intern/cycles/blender/curves.cpp): radius = radius_scale
* 0.5 * width, width interpolated from root to tip by the hair shape, zero at the tip when
"Close Tip" is on.
"""

import numpy as np

# Points read with ParticleSystem.co_hair (one call per point, about 2 us each in Blender 3.4):
# above this many the strands are thinned evenly, with a warning, to bound the sync time.
MAX_HAIR_POINTS = 2_000_000
# How far the ribbons' edge normals lean towards the side (a tube's edge would be 90 degrees;
# interpolating normals that far apart across a flat ribbon passes through zero length).
ROUND_EDGE_DEGREES = 60.0
# Radius of a Curves object's points without a "radius" attribute (Cycles 3.4's default).
DEFAULT_CURVES_RADIUS = 0.005
# Hair points read between two polls of the render's cancel (sync/cancel.py): ~0.1 s of co_hair.
POINTS_PER_POLL = 40_000


class HairView:
    """Where ribbons face: towards `position` (perspective) or against `forward` (orthographic)."""

    def __init__(self, scene, depsgraph):
        self.position = np.zeros(3, dtype=np.float64)
        self.forward = None
        cam = scene.camera
        if cam is None:
            return
        matrix = np.asarray(cam.evaluated_get(depsgraph).matrix_world, dtype=np.float64)
        if not np.isfinite(matrix).all():
            return
        self.position = matrix[:3, 3].copy()
        if cam.type == 'CAMERA' and cam.data.type == 'ORTHO':
            forward = -matrix[:3, 2]
            norm = np.linalg.norm(forward)
            if norm > 0.0:
                self.forward = forward / norm


def _shape_radius(shape, root, tip, t):
    """Cycles' shaperadius(): radius along the strand at fraction t in [0, 1]."""
    radius = 1.0 - t
    shape = min(max(shape, -1.0), 1.0 - 1e-6)  # at 1 Cycles divides by zero (radius 0 but root)
    if shape < 0.0:
        radius = np.power(radius, 1.0 + shape)
    elif shape > 0.0:
        radius = np.power(radius, 1.0 / (1.0 - shape))
    return radius * (root - tip) + tip


def ribbons(points, radii, counts, view, anchor=None):
    """Triangles of camera-facing ribbons along strands.

    points: (N, 3) world positions, strands stored one after another; radii: (N,); counts:
    points per strand. `anchor` (float64 (3,), optional) is subtracted from the points and the
    view in double precision before they become float32: the ribbons are then placed by an
    instance translated by the anchor, so hair far from the origin keeps its detail. Returns
    (positions (2N, 3) float32, triangles (T, 3) int32, corner normals (3T, 3) float32) with degenerate and non-finite triangles already removed (a zero
    tip radius makes one triangle of the last quad a sliver), so the native mesh cleanup has
    nothing to report.

    Shading normals round the flat ribbon like the cylinder it stands for: at its edges they
    lean ROUND_EDGE_DEGREES from the facing direction towards the side, and interpolated
    across the ribbon they sweep between the two, so a strand is lit like a tube, brighter on
    its side towards the light.
    """
    view_position = view.position
    if anchor is not None:
        points = np.asarray(points, dtype=np.float64) - anchor
        view_position = view_position - anchor
    points = np.asarray(points, dtype=np.float32)
    radii = np.asarray(radii, dtype=np.float32)
    counts = np.asarray(counts, dtype=np.int64)
    n = len(points)
    ends = np.cumsum(counts)
    nonempty = counts > 0
    is_first = np.zeros(n, dtype=bool)
    is_last = np.zeros(n, dtype=bool)
    is_first[(ends - counts)[nonempty]] = True
    is_last[(ends - 1)[nonempty]] = True
    index = np.arange(n)
    following = np.where(is_last, index, np.minimum(index + 1, n - 1))
    previous = np.where(is_first, index, np.maximum(index - 1, 0))
    tangent = points[following] - points[previous]

    if view.forward is not None:
        to_view = -view.forward.astype(np.float32)
    else:
        to_view = view_position.astype(np.float32) - points
    side = np.cross(tangent, to_view)
    length = np.sqrt(np.einsum('ij,ij->i', side, side))
    # A strand pointing straight at the camera has no facing side: any perpendicular will do.
    weak = ~(length > 1e-6 * np.sqrt(np.einsum('ij,ij->i', tangent, tangent)))
    if weak.any():
        side[weak] = np.cross(tangent[weak], np.array([0.0, 0.0, 1.0], dtype=np.float32))
        length[weak] = np.sqrt(np.einsum('ij,ij->i', side[weak], side[weak]))
    with np.errstate(invalid='ignore', divide='ignore', over='ignore'):
        side_unit = side / length[:, None]
        # Facing direction: the view direction's part across the strand.
        facing = np.cross(side_unit, tangent)
        facing /= np.sqrt(np.einsum('ij,ij->i', facing, facing))[:, None]
        side = side_unit * radii[:, None]
    side[~np.isfinite(side).all(axis=1)] = 0.0

    lean = np.radians(ROUND_EDGE_DEGREES)
    normals = np.empty((2 * n, 3), dtype=np.float32)
    normals[0::2] = np.cos(lean) * facing - np.sin(lean) * side_unit
    normals[1::2] = np.cos(lean) * facing + np.sin(lean) * side_unit
    # Where a strand has no width or direction the geometric normal is used (zero normal).
    normals[~np.isfinite(normals).all(axis=1)] = 0.0

    positions = np.empty((2 * n, 3), dtype=np.float32)
    np.subtract(points, side, out=positions[0::2])  # left edge of the ribbon
    np.add(points, side, out=positions[1::2])       # right edge

    seg = index[~is_last].astype(np.int32)  # segment seg -> seg + 1 inside one strand
    left0, right0 = 2 * seg, 2 * seg + 1
    triangles = np.concatenate([np.stack([left0, right0, right0 + 2], axis=1),
                                np.stack([left0, right0 + 2, left0 + 2], axis=1)])
    # Same relative test as the native mesh cleanup (scene.cpp): slivers at closed tips and
    # strands with repeated points are removed here rather than reported as bad geometry.
    p0 = positions[triangles[:, 0]]
    e1 = positions[triangles[:, 1]] - p0
    e2 = positions[triangles[:, 2]] - p0
    normal = np.cross(e1, e2)
    with np.errstate(invalid='ignore', over='ignore'):
        area2 = np.sqrt(np.einsum('ij,ij->i', normal, normal))
        scale = np.maximum(np.einsum('ij,ij->i', e1, e1), np.einsum('ij,ij->i', e2, e2))
        keep = np.isfinite(area2) & (area2 > 1e-12 * scale) & (area2 > 0.0)
    finite = np.isfinite(positions).all(axis=1)
    keep &= finite[triangles[:, 0]] & finite[triangles[:, 1]] & finite[triangles[:, 2]]
    triangles = triangles[keep]
    return positions, triangles, normals[triangles].reshape(-1, 3)


def _hair_modifiers(obj, render_mode):
    """(particle system, settings) of the object's enabled hair systems drawn as paths."""
    for modifier in obj.modifiers:
        if modifier.type != 'PARTICLE_SYSTEM':
            continue
        if not (modifier.show_render if render_mode else modifier.show_viewport):
            continue
        psys = modifier.particle_system
        settings = psys.settings if psys is not None else None
        if settings is None or settings.type != 'HAIR' or settings.render_type != 'PATH':
            continue
        yield psys, settings


def has_hair(obj, render_mode):
    return obj.type == 'MESH' and any(True for _ in _hair_modifiers(obj, render_mode))


def _particle_strands(obj, psys, settings, render_mode, reporter, poll):
    """(points (S*K, 3), radii, counts) of a hair system's rendered strands, or None; poll()
    is called every POINTS_PER_POLL points read."""
    parents = len(psys.particles)
    children = len(psys.child_particles)
    # As Cycles: with children, only the children are rendered.
    first = parents if (settings.child_type != 'NONE' and children > 0) else 0
    strands = parents + children - first
    steps = settings.render_step if render_mode else settings.display_step
    keys = (1 << max(0, min(int(steps), 10))) + 1
    if settings.kink == 'SPIRAL':
        keys += max(0, int(settings.kink_extra_steps))
    if strands <= 0:
        return None
    chosen = np.arange(first, parents + children)
    if strands * keys > MAX_HAIR_POINTS:
        keep = max(1, MAX_HAIR_POINTS // keys)
        chosen = chosen[np.linspace(0, strands - 1, keep).astype(np.int64)]
        reporter.warning(f"Object '{obj.name}': hair '{psys.name}' has {strands:,} strands; "
                         f"rendering {len(chosen):,} of them, evenly spread "
                         f"(Photon reads at most {MAX_HAIR_POINTS:,} hair points)")
    points = np.array(_co_hair(obj, psys, chosen.tolist(), keys, poll),
                      dtype=np.float64).reshape(len(chosen), keys, 3)
    t = np.linspace(0.0, 1.0, keys)
    scale = float(settings.radius_scale) * 0.5
    radius = _shape_radius(float(settings.shape), scale * float(settings.root_radius),
                           scale * float(settings.tip_radius), t)
    if settings.use_close_tip:
        radius[-1] = 0.0
    radius = np.maximum(radius, 0.0)
    # co_hair gives (0, 0, 0) past the end of a strand's path cache (or for a system with no
    # cache): such trailing points are not part of the strand.
    present = (points != 0.0).any(axis=2)
    counts = np.where(present.any(axis=1), keys - np.argmax(present[:, ::-1], axis=1), 0)
    if (counts < keys).any():
        keep = np.arange(keys)[None, :] < counts[:, None]
        return points[keep], np.broadcast_to(radius, points.shape[:2])[keep], counts
    return points.reshape(-1, 3), np.tile(radius, len(chosen)), counts


def _co_hair(obj, psys, particles, keys, poll):
    """Flat list of the coordinates of `keys` points of each of `particles`, polling between
    runs of strands (two million points take five seconds)."""
    # A flat list comprehension is the cheapest route from co_hair's Vectors (about 2.5 us a
    # point in 3.4; assigning each Vector into a numpy row costs 4 us more).
    co_hair = psys.co_hair
    steps = range(keys)
    per_poll = max(1, POINTS_PER_POLL // keys)
    coords = []
    for start in range(0, len(particles), per_poll):
        coords += [c for particle in particles[start:start + per_poll] for step in steps
                   for c in co_hair(obj, particle_no=particle, step=step)]
        poll()
    return coords


def _non_finite(points, counts):
    """(points, strands): how many of the (N, 3) points, stored strand after strand with
    `counts` points each, have a NaN or infinite coordinate, and in how many strands."""
    bad = ~np.isfinite(points).all(axis=1)
    points_bad = int(np.count_nonzero(bad))
    if not points_bad:
        return 0, 0
    counts = np.asarray(counts, dtype=np.int64)
    starts = (np.cumsum(counts) - counts)[counts > 0]
    strands_bad = int(np.count_nonzero(np.add.reduceat(bad.astype(np.int64), starts)))
    return points_bad, strands_bad


def _warn_non_finite(reporter, name, found):
    """One warning per object for its hair points with NaN or infinite coordinates (`found`:
    _non_finite's (points, strands)), which ribbons() leaves out with the segments touching
    them; the rest of the hair renders."""
    points, strands = found
    if points:
        reporter.warning(f"Object '{name}': {points} hair point{'s' if points != 1 else ''} "
                         f"in {strands} strand{'s' if strands != 1 else ''} with NaN or "
                         f"infinite coordinates; the strand segments at them were dropped")


def _transformed(points, radii, matrix):
    """Points and radii moved by a 4x4 matrix (radii by its mean axis scale)."""
    matrix = np.asarray(matrix, dtype=np.float64)
    points = np.asarray(points, dtype=np.float64) @ matrix[:3, :3].T + matrix[:3, 3]
    scale = float(np.cbrt(abs(np.linalg.det(matrix[:3, :3]))))
    radii = np.maximum(np.nan_to_num(np.asarray(radii, dtype=np.float64) * scale), 0.0)
    return points, radii


def _anchor(place, points):
    return np.zeros(3, dtype=np.float64) if place is None else place(points)


def relocation(instance_matrix, object_matrix):
    """The matrix taking the object's hair (where co_hair puts it: at the object) to one of its
    instances, or False when the object's transform cannot be inverted (a zero scale, NaN)."""
    object_matrix = np.asarray(object_matrix, dtype=np.float64)
    instance_matrix = np.asarray(instance_matrix, dtype=np.float64)
    if not (np.isfinite(object_matrix).all() and np.isfinite(instance_matrix).all()
            and abs(np.linalg.det(object_matrix[:3, :3])) > 1e-30):
        return False
    return instance_matrix @ np.linalg.inv(object_matrix)


def particle_hair(native_scene, obj, render_mode, view, slots, reporter, relocate=None,
                  cache=None, place=None, poll=None):
    """Adds one ribbon mesh per hair system of `obj`: [(mesh index, triangles, slot list,
    anchor)]: each mesh holds its ribbons relative to its anchor (float64 (3,)), which the
    instance placing it adds back. `place(points)` gives the anchor of world points (zero
    without it).

    `slots` are the object's native material indices; each system renders with the slot its
    settings name (Particle Settings > Render > Material). co_hair gives the strands where the
    object itself stands; for an instance of the object (a collection instance, say),
    `relocate` is the 4x4 matrix from there to the instance. `cache` (a dict) keeps the
    strands read for an object, so each of its instances reads them once. `poll()` is called
    while strands are read (it raises to cancel the sync)."""
    out = []
    non_finite = np.zeros(2, dtype=np.int64)  # (points, strands)
    for psys, settings in _hair_modifiers(obj, render_mode):
        key = (obj.name, psys.name)
        if cache is not None and key in cache:
            strands = cache[key]
        else:
            strands = _particle_strands(obj, psys, settings, render_mode, reporter,
                                        poll or _no_poll)
            if cache is not None:
                cache[key] = strands
        if strands is None:
            continue
        points, radii, counts = strands
        if relocate is not None:
            points, radii = _transformed(points, radii, relocate)
        non_finite += _non_finite(points, counts)
        anchor = _anchor(place, points)
        positions, triangles, normals = ribbons(points, radii, counts, view, anchor)
        if len(triangles) == 0:
            continue
        info = native_scene.add_mesh(f"{obj.name} hair {psys.name}", positions, triangles,
                                     corner_normals=normals)
        if info["triangles"] == 0:
            continue
        slot = min(max(int(settings.material) - 1, 0), len(slots) - 1)
        out.append((info["index"], info["triangles"], [slots[slot]], anchor))
    _warn_non_finite(reporter, obj.name, tuple(int(n) for n in non_finite))
    return out


def _no_poll():
    pass


def curves_hair(native_scene, obj, matrix, view, slots, reporter, place=None):
    """Adds a Curves object's strands as ribbons: (mesh index, triangles, slot list, anchor)
    or None; the anchor is as particle_hair's."""
    curves = obj.data
    point_count = len(curves.points)
    curve_count = len(curves.curves)
    if point_count == 0 or curve_count == 0:
        return None
    positions = np.empty(point_count * 3, dtype=np.float32)
    curves.position_data.foreach_get("vector", positions)
    offsets = np.empty(curve_count + 1, dtype=np.int32)
    curves.curve_offset_data.foreach_get("value", offsets)
    counts = np.diff(offsets.astype(np.int64))
    if (counts < 0).any() or offsets[0] != 0 or offsets[-1] != point_count:
        reporter.warning(f"Object '{obj.name}': curves with invalid point offsets; skipped")
        return None
    radius_attribute = curves.attributes.get("radius")
    if (radius_attribute is not None and radius_attribute.data_type == 'FLOAT'
            and radius_attribute.domain == 'POINT'):
        radii = np.empty(point_count, dtype=np.float32)
        radius_attribute.data.foreach_get("value", radii)
    else:
        radii = np.full(point_count, DEFAULT_CURVES_RADIUS, dtype=np.float32)
    # Radii live in object space: scaled by the transform's mean axis scale.
    points, radii = _transformed(positions.reshape(-1, 3), radii, matrix)
    _warn_non_finite(reporter, obj.name, _non_finite(points, counts))
    anchor = _anchor(place, points)
    ribbon_positions, triangles, normals = ribbons(points, radii, counts, view, anchor)
    if len(triangles) == 0:
        return None
    info = native_scene.add_mesh(f"{obj.name} curves", ribbon_positions, triangles,
                                 corner_normals=normals)
    if info["triangles"] == 0:
        return None
    return info["index"], info["triangles"], [slots[0]], anchor
