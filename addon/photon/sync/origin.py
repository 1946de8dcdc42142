"""Rebasing: the native scene is built around a world origin offset chosen here, in double
precision, so a scene far from Blender's origin keeps its precision in 32-bit floats.

A float32 coordinate x resolves |x| * 2^-24: 1 m at 1e7 m, where a scene of a few metres bands
and loses its contact shadows. Blender's own matrices are float32, but their values are exact
in double; subtracting an offset in double before the conversion to float32 leaves the native
scene near the origin with its detail intact (the camera-relative / origin-rebasing scheme of
large-world engines). Every world-space quantity sync sends goes through `rebased_*` here:
instance matrices, light and camera matrices, hair ribbon points, bake lightmap corners.

The offset is the centre of the geometry's bounding box rounded to a power-of-two grid at least
the box's extent, so the offset and every `x - offset` of Blender's float32 values are exact.
A scene whose centre lies within REBASE_RATIO extents of the origin gets offset exactly 0: it is
sent exactly as before (bit-identical images), since floats place it well enough already.
"""

import math

import numpy as np

# The centre must lie over this many scene extents from the origin before the scene is rebased:
# there float32 has lost 3 bits of the extent's resolution and the ray offset, relative to
# |p| (ray_offset.h), is over 8x what it is for the same scene at the origin.
REBASE_RATIO = 8.0


def choose_origin(lo, hi):
    """The world origin offset (float64 (3,)) for geometry within [lo, hi] (float64 (3,) each,
    or None for no geometry): zero for a scene near the origin."""
    origin = np.zeros(3, dtype=np.float64)
    if lo is None or not (np.isfinite(lo).all() and np.isfinite(hi).all()):
        return origin
    extent = float(np.linalg.norm(hi - lo))
    centre = 0.5 * (lo + hi)
    distance = float(np.abs(centre).max())
    if not distance > REBASE_RATIO * extent:
        return origin
    # A power of two at least the extent (and at least a float32 step at `distance`, for a
    # scene of zero size): centre / grid rounds to an integer, exact times the grid in double.
    size = max(extent, distance * 2.0 ** -24)
    grid = 2.0 ** math.ceil(math.log2(size))
    return np.round(centre / grid) * grid + 0.0  # + 0.0: no -0 in the info line


class SceneBounds:
    """World bounding box of the synced geometry, in double precision."""

    def __init__(self):
        self.lo = None
        self.hi = None

    def add(self, lo, hi):
        if lo is None or hi is None:
            return
        lo = np.asarray(lo, dtype=np.float64)
        hi = np.asarray(hi, dtype=np.float64)
        if not (np.isfinite(lo).all() and np.isfinite(hi).all()):
            return
        self.lo = lo if self.lo is None else np.minimum(self.lo, lo)
        self.hi = hi if self.hi is None else np.maximum(self.hi, hi)

    def add_points(self, points):
        points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        points = points[np.isfinite(points).all(axis=1)]
        if len(points):
            self.add(points.min(axis=0), points.max(axis=0))

    def add_instances(self, local_lo, local_hi, matrices):
        """Adds the boxes of a mesh with object-space bounds [local_lo, local_hi] placed by
        `matrices` (N, 4, 4): each box's centre transformed, its half size by |rotation|."""
        matrices = np.asarray(matrices, dtype=np.float64)
        matrices = matrices[np.isfinite(matrices).all(axis=(1, 2))]
        if local_lo is None or len(matrices) == 0:
            return
        centre = 0.5 * (local_lo + local_hi)
        half = 0.5 * (local_hi - local_lo)
        centres = matrices[:, :3, :3] @ centre + matrices[:, :3, 3]
        halves = np.abs(matrices[:, :3, :3]) @ half
        self.add((centres - halves).min(axis=0), (centres + halves).max(axis=0))

    def origin(self):
        return choose_origin(self.lo, self.hi)


def local_bounds(positions):
    """(lo, hi) float64 of finite object-space positions (flat or (N, 3)), or (None, None)."""
    points = np.asarray(positions).reshape(-1, 3)
    finite = np.isfinite(points).all(axis=1)
    if not finite.all():  # the usual all-finite mesh skips a copy of its vertices
        points = points[finite]
    if len(points) == 0:
        return None, None
    return points.min(axis=0).astype(np.float64), points.max(axis=0).astype(np.float64)


def rebased_matrix(matrix, origin):
    """A world 4x4 matrix (Blender Matrix or array) moved by -origin, as float32. With origin 0
    it is the float32 matrix sync sent before rebasing, bit for bit."""
    matrix = np.array(matrix, dtype=np.float64)
    matrix[:3, 3] -= origin
    return matrix.astype(np.float32)


def rebased_matrices(matrices, origin):
    """(N, 4, 4) world matrices moved by -origin, as float32."""
    matrices = np.array(matrices, dtype=np.float64)
    matrices[:, :3, 3] -= origin
    return matrices.astype(np.float32)
