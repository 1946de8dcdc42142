"""Render settings stored on the scene as scene.photon, and Photon's settings of materials
(material.photon) and lights (light.photon)."""

import bpy
from bpy.props import (BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty,
                       StringProperty)

from . import schema, viewport


class PhotonRenderSettings(bpy.types.PropertyGroup):
    # The render parameters (integrator, samples, photon mapping, radiosity, performance) are
    # generated from the native schema below the class; the bake settings are the add-on's own.
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


class PhotonMaterialSettings(bpy.types.PropertyGroup):
    """material.photon: what Photon renders of a material beyond its node tree."""
    abbe_number: FloatProperty(
        name="Abbe Number",
        description="Dispersion of the material's Glass, Refraction and Principled transmission "
                    "in spectral mode: the IOR is taken at 587.6 nm and varies with the "
                    "wavelength by Cauchy's law (crown glass about 60, flint 30, diamond 55; "
                    "lower disperses more). 0: no dispersion",
        default=0.0, min=0.0, max=200.0, soft_max=100.0)


# The spectra a light can emit (native LightSpectrum / StandardIlluminant).
LIGHT_SPECTRA = [
    ("RGB", "RGB", "The light's colour (white is daylight D65 in spectral mode)"),
    ("BLACKBODY", "Blackbody",
     "Planck's law at the temperature: its colour in RGB mode, its spectrum in spectral mode; "
     "the light's colour only scales its brightness (by luminance)"),
    ("ILLUMINANT", "Illuminant",
     "A CIE standard illuminant; the light's colour only scales its brightness (by luminance)"),
]
ILLUMINANTS = [
    ("D65", "D65", "CIE D65, daylight (6504 K)"),
    ("A", "A", "CIE A, incandescent tungsten (2856 K)"),
    ("F2", "F2", "CIE F2, cool white fluorescent"),
    ("F7", "F7", "CIE F7, broadband daylight fluorescent"),
    ("F11", "F11", "CIE F11, narrow tri-band fluorescent"),
]


class PhotonLightSettings(bpy.types.PropertyGroup):
    """light.photon: the spectrum a lamp emits. A Blackbody node feeding the light's Emission
    colour (Use Nodes) sets Blackbody with its temperature while this is RGB."""
    spectrum: EnumProperty(name="Spectrum", description="What the light emits",
                           items=LIGHT_SPECTRA, default="RGB")
    temperature: FloatProperty(
        name="Temperature", description="Blackbody temperature", default=6500.0,
        min=800.0, max=100000.0, soft_min=1000.0, soft_max=12000.0)
    illuminant: EnumProperty(name="Illuminant", description="CIE standard illuminant",
                             items=ILLUMINANTS, default="D65")


# (pass name in Blender and in the native tiles, view-layer property)
LIGHT_PASSES = (
    ("Photon Direct", "use_pass_direct"),
    ("Photon Indirect", "use_pass_indirect"),
    ("Photon Caustics", "use_pass_caustics"),
    ("Photon Map", "use_pass_photon_map"),
)


def enabled_passes(view_layer):
    """The names of the view layer's enabled Photon light passes."""
    settings = getattr(view_layer, "photon", None)
    if settings is None:
        return []
    return [name for name, prop in LIGHT_PASSES if getattr(settings, prop)]


def _redraw_rendered_viewports(_settings, _context):
    """A render setting changed: Rendered viewports redraw, and their view_draw restarts the
    render with it (a property change alone reaches no view_update)."""
    viewport.tag_rendered_viewports()


def _add_schema_properties():
    for p in schema.params():
        PhotonRenderSettings.__annotations__[p["name"]] = schema.make_property(
            p, update=_redraw_rendered_viewports)


_add_schema_properties()

classes = (PhotonRenderSettings, PhotonViewLayerSettings, PhotonMaterialSettings,
           PhotonLightSettings)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.photon = PointerProperty(type=PhotonRenderSettings)
    bpy.types.ViewLayer.photon = PointerProperty(type=PhotonViewLayerSettings)
    bpy.types.Material.photon = PointerProperty(type=PhotonMaterialSettings)
    bpy.types.Light.photon = PointerProperty(type=PhotonLightSettings)


def unregister():
    del bpy.types.Light.photon
    del bpy.types.Material.photon
    del bpy.types.ViewLayer.photon
    del bpy.types.Scene.photon
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
