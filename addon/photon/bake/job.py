"""Lighting bake: the view-independent lighting of the scene, computed once by the native
integrator (photon maps or radiosity) at surface points, written into Blender data for real-time
viewing: a per-corner Color Attribute `PhotonLighting` on each mesh, and optionally a per-object
UV lightmap image (photon-mapped light turned into textures, filtered in 2D).

A BakeJob syncs the scene exactly as a render does, lists the points to shade (one per face
corner, one per covered lightmap texel), runs one native BakeSession for all of them (so photon
tracing or the radiosity solve happens once) and writes the results back.
"""

import time

import numpy as np

from .. import report, sync, texture_cache
from ..native import native_module
from ..render_settings import make_settings
from . import targets as bake_targets

ATTRIBUTE = "PhotonLighting"
LIGHTMAP_PROPERTY = "photon_lightmap"  # object custom property: name of its lightmap image


def format_seconds(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 60} min {seconds % 60:02d} s" if seconds >= 60 else f"{seconds} s"


class BakeError(Exception):
    """The bake cannot run at all (no native module, no integrator, nothing to bake)."""


def bake_settings(native, scene):
    """RenderSettings for a bake: the render settings, with the bake's source and samples."""
    props = scene.photon
    settings = make_settings(native, scene, 64, 64, (0, 0, 64, 64))
    integrator = getattr(native.Integrator, props.bake_source, None)
    if integrator is None:
        raise BakeError(f"this build of Photon has no {props.bake_source} integrator to bake from")
    capabilities = native.integrator_capabilities(integrator)
    if not capabilities["bake"]:
        raise BakeError(capabilities["no_bake_reason"])
    settings.integrator = integrator
    settings.samples = max(1, int(props.bake_samples))
    return settings


class BakeJob:
    def __init__(self, context, reporter=None):
        self.reporter = reporter or report.Reporter()
        self.native = native = native_module()
        self.scene = scene = context.scene
        props = scene.photon
        depsgraph = context.evaluated_depsgraph_get()
        self.want_attribute = props.bake_target in {'COLOR_ATTRIBUTE', 'BOTH'}
        self.want_lightmap = props.bake_target in {'LIGHTMAP', 'BOTH'}
        settings = bake_settings(native, scene)

        object_instances = {}
        self.native_scene, self.sync_stats = sync.sync_scene(
            native, depsgraph, self.reporter, object_instances)
        self.targets = bake_targets.collect(
            context, depsgraph, object_instances, props, self.want_attribute,
            self.want_lightmap, self.reporter, origin=self.sync_stats.origin)
        if not self.targets:
            raise BakeError("no mesh object with faces to bake into")

        instances, triangles, barycentrics = [], [], []
        offset = 0
        for target in self.targets:
            for part in target.parts():
                part.start = offset
                offset += len(part.triangles)
                instances.append(np.full(len(part.triangles), target.instance, np.int32))
                triangles.append(part.triangles)
                barycentrics.append(part.barycentrics)
        self.point_count = offset
        self.corner_count = sum(t.corners.loop_count for t in self.targets if t.corners)
        self.texel_count = sum(len(t.lightmap.texels) for t in self.targets if t.lightmap)
        self.session = native.BakeSession(
            self.native_scene, settings, np.concatenate(instances), np.concatenate(triangles),
            np.concatenate(barycentrics), brighter_side=bool(props.bake_brighter_side))

    def start(self):
        self._shading_since = None  # (time, points done) when shading was first seen
        self.session.start()

    @property
    def finished(self):
        return self.session.finished

    @property
    def progress(self):
        return self.session.progress

    @property
    def status(self):
        """The native phase; while shading: points done / total, rate and time left."""
        session = self.session
        if session.preparing or session.finished:
            return f"{session.status} ({self.point_count:,} points)"
        now = time.perf_counter()
        done = min(int(session.progress * self.point_count), self.point_count)
        if self._shading_since is None:
            self._shading_since = (now, done)
        since, done_then = self._shading_since
        elapsed = now - since
        text = f"Baking {done:,} / {self.point_count:,} points"
        if elapsed > 0.2 and done > done_then:
            rate = (done - done_then) / elapsed
            text += (f", {rate:,.0f} points/s, about "
                     f"{format_seconds((self.point_count - done) / rate)} left")
        return text

    def cancel(self):
        self.session.cancel()
        self.session.wait()
        self.sync_stats.release()  # temporary files of packed images

    def finish(self):
        """Writes the results into Blender data; returns the native result dict, or None when
        the bake was cancelled (nothing is written then)."""
        self.session.wait()
        self.sync_stats.release()  # temporary files of packed images
        result = self.session.result()  # raises RuntimeError when the integrator cannot bake
        if result["cancelled"]:
            return None
        for message in texture_cache.explain(result["warnings"],
                                              self.sync_stats.texture_redirect):
            self.reporter.warning(message)
        for target in self.targets:
            if target.corners is not None:
                write_attribute(target, result, self.reporter)
            if target.lightmap is not None:
                write_lightmap(self.native, target, result, self.scene.photon, self.reporter)
        return result


def _slice(result, part):
    stop = part.start + len(part.triangles)
    return {key: result[key][part.start:stop] for key in ("radiance", "position", "normal",
                                                         "status")}


def write_attribute(target, result, reporter):
    """Per-corner radiance into the mesh's FLOAT_COLOR corner attribute: every corner takes the
    value of the point shaded for its (vertex, split normal) group (bake_targets.corner_points)."""
    corners = target.corners
    values = _slice(result, corners)
    ok = values["status"] == 0
    group_count = int(corners.groups.max()) + 1 if corners.loop_count else 0
    group_values = np.zeros((group_count, 3), np.float32)
    group_values[corners.point_groups[ok]] = values["radiance"][ok]
    if not ok.all():
        failed = np.zeros(group_count, bool)
        failed[corners.point_groups[~ok]] = True
        reporter.warning(f"Object '{target.name}': {int(failed[corners.groups].sum())} of "
                         f"{corners.loop_count} corners could not be baked (see above); they "
                         f"are black")
    rgba = np.ones((corners.loop_count, 4), np.float32)
    rgba[:, :3] = group_values[corners.groups]

    mesh = target.mesh
    existing = mesh.attributes.get(ATTRIBUTE)
    if existing is not None and (existing.domain != 'CORNER' or existing.data_type != 'FLOAT_COLOR'):
        mesh.attributes.remove(existing)
        existing = None
    attribute = existing or mesh.color_attributes.new(ATTRIBUTE, 'FLOAT_COLOR', 'CORNER')
    attribute.data.foreach_set("color", rgba.ravel())
    mesh.update()


def write_lightmap(native, target, result, props, reporter):
    """Texel radiance -> surface-aware 2D filter and dilation -> a packed float image."""
    import bpy

    lightmap = target.lightmap
    size = lightmap.size
    values = _slice(result, lightmap)
    ok = values["status"] == 0
    texel = lightmap.texels[ok]
    count = size * size
    image_values = np.zeros((count, 3), np.float32)
    covered = np.zeros(count, np.uint8)
    positions = np.zeros((count, 3), np.float32)
    normals = np.zeros((count, 3), np.float32)
    world_size = np.zeros(count, np.float32)
    image_values[texel] = values["radiance"][ok]
    covered[texel] = 1
    positions[texel] = values["position"][ok]
    normals[texel] = values["normal"][ok]
    world_size[texel] = lightmap.world_size[ok]
    factor = lightmap.full_size // size
    # Gutters in image texels: at the shading resolution, plus one ring so that bilinear
    # upsampling at chart borders reads filled texels only.
    dilate = int(props.lightmap_dilate)
    dilate = -(-dilate // factor) + (1 if factor > 1 else 0)
    filtered, _coverage = native.filter_lightmap(
        image_values, covered, positions, normals, world_size, size, size,
        radius=int(props.lightmap_filter_radius), dilate=dilate)
    del image_values, positions, normals, world_size
    rgba = native.upsample_lightmap(filtered, factor)
    del filtered

    full = lightmap.full_size
    name = f"{ATTRIBUTE}_{target.name}"
    image = bpy.data.images.get(name)
    if image is not None and (tuple(image.size) != (full, full) or not image.is_float):
        bpy.data.images.remove(image)
        image = None
    if image is None:
        image = bpy.data.images.new(name, full, full, alpha=False, float_buffer=True)
    # Blender 4.0 renamed the scene-linear space "Linear" to "Linear Rec.709".
    spaces = image.colorspace_settings.bl_rna.properties["name"].enum_items.keys()
    image.colorspace_settings.name = "Linear Rec.709" if "Linear Rec.709" in spaces else "Linear"
    image.pixels.foreach_set(rgba.ravel())
    del rgba
    # Packed into the .blend as float EXR, so the lightmap travels with the file.
    image.file_format = 'OPEN_EXR'
    image.pack()
    target.object[LIGHTMAP_PROPERTY] = image.name
    if not covered.any():
        reporter.warning(f"Object '{target.name}': no lightmap texel centre fell inside its UV "
                         f"layout '{props.lightmap_uv_name}'; the lightmap is black")
