"""Bakes the Cornell box (walls and boxes subdivided for more sample points) with the photon maps,
renders it with the same settings, and returns every visible, flat-interior mesh vertex with
its pixel position and its PhotonLighting value; the test compares them to the image."""

import math

import bpy
import numpy as np
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

import builders
import harness

ATTRIBUTE = "PhotonLighting"


def interior_vertices(mesh):
    """Vertices off the mesh boundary whose corners all have the same normal (flat interior)."""
    boundary = set()
    edge_faces = {}
    for poly in mesh.polygons:
        for key in poly.edge_keys:
            edge_faces[key] = edge_faces.get(key, 0) + 1
    for key, count in edge_faces.items():
        if count == 1:
            boundary.update(key)
    normals = {}
    for poly in mesh.polygons:
        for v in poly.vertices:
            normals.setdefault(v, set()).add(tuple(round(c, 4) for c in poly.normal))
    return [v for v, n in normals.items() if len(n) == 1 and v not in boundary]


def pixel_ray(scene, camera, frame, x, y):
    """World direction of the camera ray through image point (x, y), y downwards."""
    width, height = scene.render.resolution_x, scene.render.resolution_y
    top_right, bottom_right, bottom_left, top_left = frame
    u, v = x / width, 1.0 - y / height
    local = bottom_left + (bottom_right - bottom_left) * u + (top_left - bottom_left) * v
    return (camera.matrix_world @ local - camera.matrix_world.translation).normalized()


def footprint_on_one_face(scene, depsgraph, camera, frame, obj, normal, px, py):
    """True when the 4 x 4 pixels the test reads around (px, py) all see `obj` with `normal`
    (the test box-filters 3 x 3 pixels and interpolates bilinearly)."""
    x0, y0 = math.floor(px - 0.5) - 1, math.floor(py - 0.5) - 1
    origin = camera.matrix_world.translation
    for y in range(y0, y0 + 4):
        for x in range(x0, x0 + 4):
            hit, _loc, n, _i, hit_obj, _m = scene.ray_cast(
                depsgraph, origin, pixel_ray(scene, camera, frame, x + 0.5, y + 0.5))
            if not hit or hit_obj.name != obj.name or n.dot(normal) < 0.999:
                return False
    return True


def main(exr_path, cuts="6", source="PHOTON_MAP"):
    scene = builders.cornell_box(width=160, height=160, samples=64)
    scene.photon.photons = 200000
    scene.photon.final_gather_rays = 16
    # The render uses the bake's source too, so the two show the same solution.
    scene.photon.integrator = source
    scene.photon.bake_source = source
    scene.photon.bake_target = 'COLOR_ATTRIBUTE'
    scene.photon.bake_samples = 32
    meshes = [o for o in scene.objects if o.type == 'MESH']
    for obj in meshes:
        builders.subdivide(obj, int(cuts))

    baked = bpy.ops.photon.bake_lighting()
    scene.render.filepath = exr_path
    bpy.ops.render.render(write_still=True)

    depsgraph = bpy.context.evaluated_depsgraph_get()
    camera = scene.camera
    frame = camera.data.view_frame(scene=scene)
    cam_pos = camera.matrix_world.translation
    width, height = scene.render.resolution_x, scene.render.resolution_y
    result = {"bake": sorted(baked), "objects": {}, "points": []}
    for obj in meshes:
        mesh = obj.data
        attribute = mesh.color_attributes.get(ATTRIBUTE)
        result["objects"][obj.name] = None if attribute is None else {
            "domain": attribute.domain, "data_type": attribute.data_type,
            "count": len(attribute.data), "loops": len(mesh.loops)}
        if attribute is None:
            continue
        colors = np.empty(len(attribute.data) * 4, np.float32)
        attribute.data.foreach_get("color", colors)
        colors = colors.reshape(-1, 4)
        loop_vertex = np.empty(len(mesh.loops), np.int32)
        mesh.loops.foreach_get("vertex_index", loop_vertex)
        for v in interior_vertices(mesh):
            world = obj.matrix_world @ mesh.vertices[v].co
            ndc = world_to_camera_view(scene, camera, world)
            if ndc.z <= 0.0:
                continue
            px, py = ndc.x * width, (1.0 - ndc.y) * height  # top row first, like the EXR read
            if not (4 <= px < width - 4 and 4 <= py < height - 4):
                continue
            direction = (world - cam_pos)
            distance = direction.length
            hit, location, _n, _i, hit_obj, _m = scene.ray_cast(
                depsgraph, cam_pos, direction.normalized(), distance=distance + 1e-3)
            if not hit or hit_obj.name != obj.name or (location - world).length > 1e-3:
                continue
            normal = (obj.matrix_world.to_3x3() @ mesh.vertices[v].normal).normalized()
            if not footprint_on_one_face(scene, depsgraph, camera, frame, obj, normal, px, py):
                continue
            corners = colors[loop_vertex == v, :3]
            result["points"].append({"object": obj.name, "pixel": [px, py],
                                     "value": corners.mean(axis=0).tolist(),
                                     "corner_spread": float(np.ptp(corners, axis=0).max())})
    return result


harness.run(main)
