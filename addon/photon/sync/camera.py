"""The scene camera as a native camera: frame size and border, view window, clipping, depth of
field and multiview eyes. sync/view.py places the 3D viewport's camera, with the same depth of
field in camera view."""

import math

import numpy as np

from ..report import SceneError
from .origin import rebased_matrix


def render_size(render):
    """Full frame size in pixels, as Blender computes it (integer percentage scaling)."""
    width = render.resolution_x * render.resolution_percentage // 100
    height = render.resolution_y * render.resolution_percentage // 100
    return max(width, 1), max(height, 1)


def render_region(render, width, height):
    """Pixel rectangle (x0, y0, x1, y1), y downwards, that Blender's result covers.

    Blender truncates border * size to integers for its render rectangle, with y measured
    from the bottom; the render result is that rectangle's size.
    """
    if not render.use_border:
        return 0, 0, width, height
    xmin = int(render.border_min_x * width)
    xmax = int(render.border_max_x * width)
    ymin = int(render.border_min_y * height)
    ymax = int(render.border_max_y * height)
    xmax = max(xmax, xmin + 1)
    ymax = max(ymax, ymin + 1)
    return xmin, height - ymax, xmax, height - ymin


def _check_transform(cam_obj):
    """Raises SceneError for a camera transform no image can be made from: non-finite entries
    (a NaN location, say) or a zero scale, which leaves no view direction."""
    matrix = cam_obj.matrix_world
    if not all(math.isfinite(v) for row in matrix for v in row):
        raise SceneError(f"Camera '{cam_obj.name}' has a non-finite transform (NaN or infinite "
                         f"location, rotation or scale); nothing was rendered")
    if not abs(matrix.to_3x3().determinant()) > 0.0:
        raise SceneError(f"Camera '{cam_obj.name}' has a zero scale, so it has no view "
                         f"direction; nothing was rendered")


class ViewCamera:
    """One multiview view's camera, as Blender's render pipeline places it: `camera` (the
    evaluated object; MULTIVIEW format picks a camera per view by name suffix), `matrix` (its
    eye's normalised model matrix) and `shift_x` (its eye's lens shift)."""

    def __init__(self, camera, matrix, shift_x):
        self.camera = camera
        self.matrix = matrix
        self.shift_x = shift_x


def view_camera(engine, scene, depsgraph, view):
    """The camera of multiview `view` (Stereo 3D 'left'/'right', or a MULTIVIEW view), as
    Cycles reads it: active_view_set, then camera_override, camera_model_matrix and
    camera_shift_x for that view. None when the active camera is not a camera object (the
    stereo functions read camera data): every view then renders the plain camera."""
    engine.active_view_set(view)
    cam_obj = engine.camera_override or scene.camera
    if cam_obj is None or cam_obj.type != 'CAMERA':
        return None
    cam_obj = cam_obj.evaluated_get(depsgraph)
    spherical = engine.use_spherical_stereo(cam_obj)
    matrix = engine.camera_model_matrix(cam_obj, use_spherical_stereo=spherical)
    shift_x = engine.camera_shift_x(cam_obj, use_spherical_stereo=spherical)
    return ViewCamera(cam_obj, matrix, shift_x)


def _horizontal_fit(cam, window):
    """True when the sensor width spans the frame width (Blender's BKE_camera_sensor_fit: AUTO
    fits the larger of the frame's width and height, aspect included)."""
    if cam.sensor_fit == 'AUTO':
        return window[1] - window[0] >= window[3] - window[2]
    return cam.sensor_fit == 'HORIZONTAL'


def depth_of_field(cam, depsgraph, placement):
    """(aperture radius, focus distance) of camera data `cam` placed at `placement` (its world
    matrix: a focus object's distance is measured along its view axis); (0, 10) without depth
    of field. The final render's camera and the viewport's camera view (sync/view.py) share
    it."""
    if not cam.dof.use_dof:
        return 0.0, 10.0
    fstop = max(cam.dof.aperture_fstop, 1e-5)
    if cam.type == 'ORTHO':
        aperture_radius = 1.0 / (2.0 * fstop)
    else:
        aperture_radius = (cam.lens * 1e-3) / (2.0 * fstop)
    if cam.dof.focus_object is not None:
        focus = cam.dof.focus_object.evaluated_get(depsgraph).matrix_world.translation
        view_axis = placement.to_3x3().normalized().col[2]
        focus_distance = abs(view_axis.dot(placement.translation - focus))
    else:
        focus_distance = cam.dof.focus_distance
    return float(aperture_radius), float(max(focus_distance, 1e-5))


def export_camera(native_scene, scene, depsgraph, reporter, view=None, origin=None):
    """Sets the native camera from the scene camera, or from `view` (a ViewCamera) for one
    view of a multiview render. `origin` is the world origin offset the native scene is built
    around (sync_origin; SyncStats.origin), subtracted from the camera's position."""
    if origin is None:
        origin = np.zeros(3, dtype=np.float64)
    cam_obj = scene.camera if view is None else view.camera
    if cam_obj is None:
        reporter.warning("The scene has no camera; rendering from the default view")
        native_scene.set_camera("PERSP", rebased_matrix(np.identity(4), origin),
                                [-0.5, 0.5, -0.5, 0.5], 0.1, 1000.0)
        return
    cam_obj = cam_obj.evaluated_get(depsgraph)
    _check_transform(cam_obj)
    if cam_obj.type != 'CAMERA':
        reporter.warning(f"Active camera '{cam_obj.name}' is not a camera object; "
                         f"using its transform with a 50 mm lens")
        matrix = cam_obj.matrix_world.normalized()
        native_scene.set_camera("PERSP", rebased_matrix(matrix, origin),
                                [-0.36, 0.36, -0.36, 0.36], 0.1, 1000.0)
        return
    cam = cam_obj.data
    projection = "ORTHO" if cam.type == 'ORTHO' else "PERSP"
    if cam.type == 'PANO':
        reporter.warning(f"Camera '{cam_obj.name}': panoramic cameras are not supported; "
                         f"rendering as perspective")

    # view_frame() folds in sensor fit, lens shift, aspect ratio and the orthographic scale.
    frame = cam.view_frame(scene=scene)
    xs = [v.x for v in frame]
    ys = [v.y for v in frame]
    if projection == "PERSP":
        depth = -frame[0].z
        if depth <= 0.0:
            depth = 1.0
        xs = [x / depth for x in xs]
        ys = [y / depth for y in ys]
    window = [min(xs), max(xs), min(ys), max(ys)]
    placement = cam_obj.matrix_world if view is None else view.matrix
    if view is not None and view.shift_x != cam.shift_x:
        # view_frame() holds the camera's own shift; an off-axis stereo eye adds to it. Shift
        # is a fraction of the sensor-fit side of the frame (BKE_camera_params_compute_viewplane:
        # dx = shift * viewfac), the same fraction of the window's side here.
        side = window[1] - window[0] if _horizontal_fit(cam, window) else window[3] - window[2]
        offset = (view.shift_x - cam.shift_x) * side
        window[0] += offset
        window[1] += offset

    aperture_radius, focus_distance = depth_of_field(cam, depsgraph, placement)

    # Cycles removes the camera object's scale; so do we (camera_model_matrix has none).
    matrix = placement.normalized()
    native_scene.set_camera(projection, rebased_matrix(matrix, origin), window,
                            float(cam.clip_start), float(cam.clip_end),
                            aperture_radius, focus_distance)
