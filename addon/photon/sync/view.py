"""A 3D viewport's view as a native camera: its projection window and clipping from the view's
OpenGL matrices, its render border, and in camera view the scene camera's depth of field
(shared with the scene camera, sync/camera.py). viewport.py re-aims its session with it."""

import math

import numpy as np
from bpy_extras import view3d_utils

from .camera import depth_of_field
from .origin import rebased_matrix


def _projection_window(window_matrix, perspective):
    """(window [min_x, max_x, min_y, max_y], clip_start, clip_end) of an OpenGL projection
    matrix: the image-plane window at distance 1 (perspective) or in scene units (ortho)."""
    p = np.array(window_matrix, dtype=np.float64)
    if perspective:
        # x_ndc = p00 * (x / -z) - p02 (glFrustum), so x / -z = (x_ndc + p02) / p00.
        window = [(-1.0 + p[0, 2]) / p[0, 0], (1.0 + p[0, 2]) / p[0, 0],
                  (-1.0 + p[1, 2]) / p[1, 1], (1.0 + p[1, 2]) / p[1, 1]]
        near, far = p[2, 3] / (p[2, 2] - 1.0), p[2, 3] / (p[2, 2] + 1.0)
    else:
        # x_ndc = p00 * x + p03 (glOrtho).
        window = [(-1.0 - p[0, 3]) / p[0, 0], (1.0 - p[0, 3]) / p[0, 0],
                  (-1.0 - p[1, 3]) / p[1, 1], (1.0 - p[1, 3]) / p[1, 1]]
        near, far = (p[2, 3] + 1.0) / p[2, 2], (p[2, 3] - 1.0) / p[2, 2]
    return window, near, far


def _camera_dof(scene, depsgraph, camera_matrix):
    """(aperture radius, focus distance) of the scene camera's depth of field seen from the
    viewport's camera view, as the final render uses it."""
    cam_obj = scene.camera
    if cam_obj is None or cam_obj.type != 'CAMERA':
        return 0.0, 10.0
    return depth_of_field(cam_obj.data, depsgraph, camera_matrix)


def _border(context, scene, width, height):
    """Rendered pixel rectangle (x0, y0, x1, y1), y downwards, of the region: the viewport's
    render border, or in camera view the scene's render border within the camera frame."""
    space, rv3d = context.space_data, context.region_data
    if rv3d.view_perspective == 'CAMERA':
        if not scene.render.use_border or scene.camera is None:
            return 0, 0, width, height
        cam_obj = scene.camera
        corners = [cam_obj.matrix_world @ v for v in cam_obj.data.view_frame(scene=scene)]
        points = [view3d_utils.location_3d_to_region_2d(context.region, rv3d, c)
                  for c in corners]
        if any(p is None for p in points):
            return 0, 0, width, height
        xs, ys = [p.x for p in points], [p.y for p in points]
        fx0, fx1, fy0, fy1 = min(xs), max(xs), min(ys), max(ys)
        bx0 = fx0 + scene.render.border_min_x * (fx1 - fx0)
        bx1 = fx0 + scene.render.border_max_x * (fx1 - fx0)
        by0 = fy0 + scene.render.border_min_y * (fy1 - fy0)
        by1 = fy0 + scene.render.border_max_y * (fy1 - fy0)
    elif space.use_render_border:
        bx0, bx1 = space.render_border_min_x * width, space.render_border_max_x * width
        by0, by1 = space.render_border_min_y * height, space.render_border_max_y * height
    else:
        return 0, 0, width, height
    x0 = min(max(int(math.floor(bx0)), 0), width - 1)
    x1 = min(max(int(math.ceil(bx1)), x0 + 1), width)
    y0 = min(max(int(math.floor(by0)), 0), height - 1)  # from the bottom
    y1 = min(max(int(math.ceil(by1)), y0 + 1), height)
    return x0, height - y1, x1, height - y0


def viewport_view(context, depsgraph, origin):
    """The native camera arguments and frame of a 3D viewport region: a key that changes
    whenever the image would, and (set_camera args, width, height, region)."""
    region, rv3d = context.region, context.region_data
    scene = depsgraph.scene
    width, height = max(region.width, 1), max(region.height, 1)
    perspective = rv3d.is_perspective
    window, near, far = _projection_window(rv3d.window_matrix, perspective)
    camera_matrix = rv3d.view_matrix.inverted()
    if not perspective:
        # Blender's orthographic views clip from -far/2 to far/2 around the view point
        # (negative near clip, as Cycles' viewport camera has); the native camera clips from
        # 0, so its origin moves back along the view axis, which an orthographic image does
        # not see.
        back = camera_matrix.to_3x3().normalized().col[2] * (-near)
        camera_matrix = camera_matrix.copy()
        camera_matrix.translation += back
        near, far = 0.0, far - near
    aperture, focus = 0.0, 10.0
    if rv3d.view_perspective == 'CAMERA':
        aperture, focus = _camera_dof(scene, depsgraph, camera_matrix)
    matrix = rebased_matrix(camera_matrix, origin)
    args = ("PERSP" if perspective else "ORTHO", matrix, [float(w) for w in window],
            float(max(near, 0.0)), float(far), aperture, focus)
    border = _border(context, scene, width, height)
    key = (args[0], matrix.tobytes(), tuple(args[2]), args[3], args[4], aperture, focus,
           width, height, border)
    return key, (args, width, height, border)
