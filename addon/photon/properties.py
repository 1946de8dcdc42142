"""Render settings stored on the scene as scene.photon."""

import bpy
from bpy.props import (BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty,
                       StringProperty)


class PhotonRenderSettings(bpy.types.PropertyGroup):
    integrator: EnumProperty(
        name="Integrator",
        description="Rendering algorithm",
        items=[
            ("PHOTON_MAP", "Photon Mapping",
             "Global illumination and caustics from global and caustic photon maps, with "
             "final gathering"),
            ("RAY_TRACE", "Ray Tracing",
             "Whitted ray tracing: direct light, perfect mirrors and glass"),
            ("RADIOSITY", "Radiosity",
             "Diffuse global illumination solved once on a mesh of patches (stochastic "
             "Jacobi radiosity) and viewed from anywhere; mirrors and glass are ray traced"),
        ],
        default="PHOTON_MAP",
    )
    samples: IntProperty(
        name="Samples", description="Camera samples per pixel",
        default=64, min=1, soft_max=4096, max=1 << 20)
    max_depth: IntProperty(
        name="Max Depth", description="Maximum number of mirror and glass bounces",
        default=8, min=0, soft_max=64, max=1024)
    seed: IntProperty(
        name="Seed", description="Random seed; the same seed renders the same image",
        default=0, min=0)
    photons: IntProperty(
        name="Photons", description="Photons emitted for the global photon map (indirect light)",
        default=200000, min=0, soft_max=10000000, max=100000000)
    caustic_photons: IntProperty(
        name="Caustic Photons",
        description="Photons aimed at mirrors and glass for the caustic photon map",
        default=100000, min=0, soft_max=10000000, max=100000000)
    gather_count: IntProperty(
        name="Gather Count",
        description="Nearest photons used in a global photon map estimate",
        default=100, min=1, soft_max=500, max=1000)
    gather_radius: FloatProperty(
        name="Gather Radius",
        description="Largest distance searched for photons (0 = automatic from the scene size)",
        default=0.0, min=0.0, soft_max=10.0, subtype="DISTANCE", unit="LENGTH")
    caustic_gather_count: IntProperty(
        name="Caustic Gather Count",
        description="Nearest photons used in a caustic estimate",
        default=50, min=1, soft_max=500, max=1000)
    final_gather_rays: IntProperty(
        name="Final Gather Rays",
        description="Rays gathering indirect light per camera sample "
                    "(0 = read the global photon map directly: fast, blotchy preview)",
        default=16, min=0, soft_max=256, max=4096)
    irradiance_cache: BoolProperty(
        name="Irradiance Cache",
        description="Compute the final gather carefully (64 times Final Gather Rays) at sparse "
                    "points the camera sees before rendering, and interpolate between them "
                    "(Ward 1988): smooth indirect light at a fraction of the cost. Points the "
                    "cache does not cover are gathered per sample",
        default=True)
    photon_time: FloatProperty(
        name="Photon Time",
        description="Trace photons for this many seconds instead of a fixed count "
                    "(0 = use the counts). Esc during photon tracing renders with the "
                    "photons traced so far",
        default=0.0, min=0.0, soft_max=600.0, max=86400.0, subtype="TIME_ABSOLUTE", unit="TIME")
    memory_limit: FloatProperty(
        name="Memory Limit",
        description="Fraction of the memory available when a render starts that the photon "
                    "maps may use at their peak (estimated before tracing); larger photon "
                    "counts are scaled down to fit, with a warning",
        default=0.75, min=0.01, max=1.0, subtype="FACTOR")
    radiosity_patch_size: FloatProperty(
        name="Patch Size",
        description="Edge length of the radiosity patches: larger triangles are split into "
                    "patches of this size, much smaller ones are grouped into one patch per "
                    "cell of this size; smaller patches show sharper shadows but need more rays "
                    "(0 = automatic: about 20000 patches, fewer if the rays are too few for "
                    "them, at least 256 rays per patch)",
        default=0.0, min=0.0, soft_max=1.0, max=1e6, subtype="DISTANCE", unit="LENGTH")
    radiosity_rays: IntProperty(
        name="Rays",
        description="Rays the radiosity solve traces in total, in thousands; the solve time is "
                    "about proportional, and the noise falls as 1 / sqrt(rays). Use more rays "
                    "for more (smaller) patches",
        default=8000, min=10, soft_max=200000, max=10000000)
    radiosity_threshold: FloatProperty(
        name="Unshot Threshold",
        description="Light is shot on from patch to patch until the power not yet shot is "
                    "below this fraction of the emitted power",
        default=0.01, min=0.0001, max=1.0, soft_max=0.1, precision=4)
    radiosity_iterations: IntProperty(
        name="Averaged Iterations",
        description="Jacobi iterations after shooting, each re-estimating the whole solution "
                    "with fresh rays, averaged to reduce noise (0 = shooting only)",
        default=4, min=0, soft_max=16, max=100)
    threads: IntProperty(
        name="Threads",
        description="Render threads (0 = all cores); more than 4 per core are not used",
        default=0, min=0, soft_max=256, max=4096)
    tile_size: IntProperty(
        name="Tile Size", description="Width and height of the render tiles in pixels",
        default=64, min=8, max=4096, subtype="PIXEL")

    # Lighting bake (photon.bake_lighting): view-independent lighting into Blender data.
    bake_source: EnumProperty(
        name="Source",
        description="Which view-independent lighting solution is baked",
        items=[
            ("PHOTON_MAP", "Photon Maps",
             "Direct light, caustic map and final-gathered global map at each point, times "
             "the diffuse albedo (uses the Photon Mapping settings)"),
            ("RADIOSITY", "Radiosity", "The radiosity solution (uses the Radiosity settings)"),
        ],
        default="PHOTON_MAP",
    )
    bake_target: EnumProperty(
        name="Target",
        description="Where the baked lighting is written",
        items=[
            ("COLOR_ATTRIBUTE", "Color Attribute",
             "Per face corner into the color attribute 'PhotonLighting' of each mesh"),
            ("LIGHTMAP", "Lightmap", "Into a UV lightmap image per object"),
            ("BOTH", "Both", "Color attribute and lightmaps"),
        ],
        default="COLOR_ATTRIBUTE",
    )
    bake_samples: IntProperty(
        name="Bake Samples",
        description="Samples per baked point for direct light and final gathering",
        default=16, min=1, soft_max=256, max=4096)
    bake_brighter_side: BoolProperty(
        name="Brighter Side",
        description="Shade both sides of each surface and keep the brighter one (a room "
                    "modelled with outward normals still bakes its lit inside). Off: the side "
                    "the normals face",
        default=True)
    lightmap_size: IntProperty(
        name="Lightmap Size", description="Width and height of each object's lightmap",
        default=256, min=16, soft_max=2048, max=8192, subtype="PIXEL")
    lightmap_uv_name: StringProperty(
        name="Lightmap UV Map",
        description="UV map holding the lightmap layout; created with Smart UV Project when a "
                    "mesh does not have it",
        default="Lightmap")
    lightmap_filter_radius: IntProperty(
        name="Filter Radius",
        description="Half-width in texels of the 2D filter applied to lightmaps (0 = none)",
        default=1, min=0, max=8)
    lightmap_dilate: IntProperty(
        name="Dilate",
        description="Texels filled around every UV island so texture filtering does not read "
                    "empty gutters",
        default=4, min=0, max=64, subtype="PIXEL")


class PhotonViewLayerSettings(bpy.types.PropertyGroup):
    """Render passes Photon writes besides Combined (view_layer.photon)."""
    use_pass_direct: BoolProperty(
        name="Photon Direct", description="Direct light, emission and specular paths to lights",
        default=False)
    use_pass_indirect: BoolProperty(
        name="Photon Indirect", description="Light that bounced off diffuse surfaces",
        default=False)
    use_pass_caustics: BoolProperty(
        name="Photon Caustics", description="Light focused onto diffuse surfaces by mirrors "
                                            "and glass (the caustic photon map)",
        default=False)
    use_pass_photon_map: BoolProperty(
        name="Photon Map", description="Dots where photons are stored, coloured by their "
                                       "power (not light)",
        default=False)


# (pass name in Blender, view-layer property, index in the native pass array)
LIGHT_PASSES = (
    ("Photon Direct", "use_pass_direct", 0),
    ("Photon Indirect", "use_pass_indirect", 1),
    ("Photon Caustics", "use_pass_caustics", 2),
    ("Photon Map", "use_pass_photon_map", 3),
)


def enabled_passes(view_layer):
    settings = getattr(view_layer, "photon", None)
    if settings is None:
        return []
    return [(name, index) for name, prop, index in LIGHT_PASSES if getattr(settings, prop)]


classes = (PhotonRenderSettings, PhotonViewLayerSettings)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.photon = PointerProperty(type=PhotonRenderSettings)
    bpy.types.ViewLayer.photon = PointerProperty(type=PhotonViewLayerSettings)


def unregister():
    del bpy.types.ViewLayer.photon
    del bpy.types.Scene.photon
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
