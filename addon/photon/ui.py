"""Panels for the Photon engine, and Blender's own panels that apply to it."""

import bpy

from . import schema

ENGINE = "PHOTON"

# Blender's built-in panels that work for any engine using shader nodes: material slots and
# surface, world surface. Panels that list BLENDER_RENDER (dimensions, output, object, ...) are
# engine-independent and are enabled too.
EXTRA_PANELS = (
    "EEVEE_MATERIAL_PT_context_material",
    "EEVEE_MATERIAL_PT_surface",
    "EEVEE_WORLD_PT_surface",
    "DATA_PT_light",
    "DATA_PT_EEVEE_light",
    "DATA_PT_EEVEE_light_distance",
    "DATA_PT_spot",
    "DATA_PT_camera_dof",
    "DATA_PT_camera_dof_aperture",
    "RENDER_PT_film",
    "MATERIAL_PT_preview",  # rendered by Photon (bl_use_preview)
)
EXCLUDED_PANELS = {"VIEWLAYER_PT_filter", "VIEWLAYER_PT_layer_passes"}


def compatible_panels():
    for panel in bpy.types.Panel.__subclasses__():
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if engines is None or panel.__name__ in EXCLUDED_PANELS:
            continue
        if "BLENDER_RENDER" in engines or panel.__name__ in EXTRA_PANELS:
            yield panel


class PhotonPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES


class PHOTON_PT_render(PhotonPanel, bpy.types.Panel):
    bl_label = "Photon"

    def draw(self, context):
        from . import NATIVE_IMPORT_ERROR
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        if NATIVE_IMPORT_ERROR:
            box = layout.box()
            box.alert = True
            box.label(text="The native renderer failed to load:", icon="ERROR")
            for line in NATIVE_IMPORT_ERROR.split(": "):
                box.label(text=line)
        if schema.LOAD_ERROR:
            layout.label(text=f"Parameter schema missing: {schema.LOAD_ERROR}", icon="ERROR")
        schema.draw(layout, context.scene.photon, "sampling")


class PHOTON_PT_photon_mapping(PhotonPanel, bpy.types.Panel):
    bl_label = "Photon Mapping"
    bl_parent_id = "PHOTON_PT_render"

    @classmethod
    def poll(cls, context):
        group = schema.group("photon_map")
        return super().poll(context) and group is not None and \
            context.scene.photon.integrator == group["integrator"]

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        schema.draw(layout, context.scene.photon, "photon_map")


class PHOTON_PT_radiosity(PhotonPanel, bpy.types.Panel):
    bl_label = "Radiosity"
    bl_parent_id = "PHOTON_PT_render"

    @classmethod
    def poll(cls, context):
        group = schema.group("radiosity")
        return super().poll(context) and group is not None and \
            context.scene.photon.integrator == group["integrator"]

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        schema.draw(layout, context.scene.photon, "radiosity")


class PhotonViewLayerPanel(PhotonPanel):
    bl_context = "view_layer"


class PHOTON_PT_passes(PhotonViewLayerPanel, bpy.types.Panel):
    bl_label = "Photon Passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.view_layer.photon
        col = layout.column(heading="Light", align=True)
        col.prop(settings, "use_pass_direct", text="Direct")
        col.prop(settings, "use_pass_indirect", text="Indirect")
        col.prop(settings, "use_pass_caustics", text="Caustics")
        col = layout.column(heading="Debug", align=True)
        col.prop(settings, "use_pass_photon_map", text="Photon Map")


class PHOTON_PT_layer_override(PhotonViewLayerPanel, bpy.types.Panel):
    """The view layer's Material Override (Blender draws it only in Cycles' own panel)."""
    bl_label = "Override"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(context.view_layer, "material_override")


class PHOTON_PT_performance(PhotonPanel, bpy.types.Panel):
    bl_label = "Performance"
    bl_parent_id = "PHOTON_PT_render"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        schema.draw(layout, context.scene.photon, "performance")
        # Blender's own setting (Cycles shows it too): keeps unchanged meshes between frames.
        layout.prop(context.scene.render, "use_persistent_data", text="Persistent Data")


class PHOTON_PT_object_mask(bpy.types.Panel):
    """Object > Visibility > Mask: Blender's own panel shows Holdout; the shadow catcher flag is
    drawn only by Cycles' panel, so Photon draws it here."""
    bl_label = "Shadow Catcher"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"
    bl_parent_id = "OBJECT_PT_visibility"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES and context.object is not None and \
            hasattr(context.object, "is_shadow_catcher")

    def draw_header(self, context):
        self.layout.prop(context.object, "is_shadow_catcher", text="")

    def draw(self, context):
        self.layout.label(text="Renders only the shadows cast on it")


classes = (PHOTON_PT_render, PHOTON_PT_photon_mapping, PHOTON_PT_radiosity, PHOTON_PT_performance,
           PHOTON_PT_passes, PHOTON_PT_layer_override, PHOTON_PT_object_mask)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    for panel in compatible_panels():
        panel.COMPAT_ENGINES.add(ENGINE)


def unregister():
    for panel in compatible_panels():
        panel.COMPAT_ENGINES.discard(ENGINE)
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
