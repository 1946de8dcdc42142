"""Panels for the Photon engine, and Blender's own panels that apply to it."""

import textwrap

import bpy

from . import native, schema
from .render_settings import uses_cycles_film

ENGINE = "PHOTON"

# Blender's built-in panels that work for any engine using shader nodes: material slots and
# surface, world surface. Panels that list BLENDER_RENDER (dimensions, output, object, ...) are
# engine-independent and are enabled too.
EXTRA_PANELS = (
    "EEVEE_MATERIAL_PT_context_material",
    "EEVEE_MATERIAL_PT_surface",
    "EEVEE_WORLD_PT_surface",
    "DATA_PT_camera_dof",
    "DATA_PT_camera_dof_aperture",
    "MATERIAL_PT_preview",  # rendered by Photon (bl_use_preview)
)
# Blender's light panels are EEVEE's (diffuse/specular/volume factors, custom distance) or show
# only the type: Photon draws its own (PHOTON_PT_light).
EXCLUDED_PANELS = {"VIEWLAYER_PT_filter", "VIEWLAYER_PT_layer_passes", "DATA_PT_light",
                   # Registered before Photon's, Blender's Simplify would sit above them (as
                   # Cycles', Photon's own is registered after its render panels); Grease
                   # Pencil's part does not apply: Photon does not render Grease Pencil.
                   "RENDER_PT_simplify", "RENDER_PT_simplify_viewport",
                   "RENDER_PT_simplify_render", "RENDER_PT_simplify_greasepencil"}
# Characters per line of a message in a panel's error box (Blender does not wrap labels).
MESSAGE_WIDTH = 44


def compatible_panels():
    panels = [p for p in bpy.types.Panel.__subclasses__()
              if getattr(p, "COMPAT_ENGINES", None) is not None]
    # Some panels share their set with another (NODE_DATA_PT_light's is DATA_PT_light's):
    # adding the engine to one adds it to both, so an excluded panel's set is left alone.
    excluded_sets = {id(p.COMPAT_ENGINES) for p in panels if p.__name__ in EXCLUDED_PANELS}
    for panel in panels:
        if id(panel.COMPAT_ENGINES) in excluded_sets:
            continue
        if "BLENDER_RENDER" in panel.COMPAT_ENGINES or panel.__name__ in EXTRA_PANELS:
            yield panel


class PhotonPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES


def draw_message(layout, title, message):
    """An error box whose message is wrapped to the panel instead of cut off."""
    box = layout.box()
    box.alert = True
    box.label(text=title, icon="ERROR")
    for line in textwrap.wrap(message, MESSAGE_WIDTH):
        box.label(text=line)


class PHOTON_PT_render(PhotonPanel, bpy.types.Panel):
    bl_label = "Photon"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        if native.IMPORT_ERROR:
            draw_message(layout, "Photon cannot render:", native.IMPORT_ERROR)
        if schema.LOAD_ERROR:
            layout.label(text=f"Parameter schema missing: {schema.LOAD_ERROR}", icon="ERROR")
        schema.draw(layout, context.scene.photon, "sampling")


class PHOTON_PT_spectral(PhotonPanel, bpy.types.Panel):
    bl_label = "Spectral"
    bl_parent_id = "PHOTON_PT_render"

    def draw_header(self, context):
        self.layout.prop(context.scene.photon, "spectral", text="")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        props = context.scene.photon
        col = layout.column()
        col.active = props.spectral
        col.prop(props, "spectral_samples")
        if props.spectral and props.integrator == "RADIOSITY":
            col.label(text="Radiosity renders in RGB", icon="INFO")


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


class PHOTON_PT_simplify(PhotonPanel, bpy.types.Panel):
    """Render > Simplify, which Blender applies while evaluating the scene Photon syncs."""
    bl_label = "Simplify"
    bl_options = {"DEFAULT_CLOSED"}

    def draw_header(self, context):
        self.layout.prop(context.scene.render, "use_simplify", text="")

    def draw(self, context):
        pass


class PhotonSimplifyPanel(PhotonPanel):
    bl_parent_id = "PHOTON_PT_simplify"
    suffix = ""  # "_render" for the final render's limits

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        render = context.scene.render
        layout.active = render.use_simplify
        col = layout.column(align=True)
        col.prop(render, "simplify_subdivision" + self.suffix, text="Max Subdivision")
        col.prop(render, "simplify_child_particles" + self.suffix, text="Max Child Particles")


class PHOTON_PT_simplify_viewport(PhotonSimplifyPanel, bpy.types.Panel):
    bl_label = "Viewport"


class PHOTON_PT_simplify_render(PhotonSimplifyPanel, bpy.types.Panel):
    bl_label = "Render"
    suffix = "_render"


class PHOTON_PT_film(PhotonPanel, bpy.types.Panel):
    """Film: with Cycles enabled, the very properties Cycles' Film panel edits (Photon renders
    them alike, render_settings.film_settings), plus Photon's Box width; else Photon's own. Cycles'
    Transparent Glass is not drawn: Photon does not honour it."""
    bl_label = "Film"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        scene = context.scene
        props = scene.photon
        col = layout.column()
        if uses_cycles_film(scene):
            col.prop(scene.cycles, "film_exposure", text="Exposure")
            col.prop(scene.cycles, "pixel_filter_type", text="Pixel Filter")
            # Cycles' Box is always one pixel wide; Photon's Box width is its own.
            if scene.cycles.pixel_filter_type == "BOX":
                col.prop(props, "filter_width", text="Width")
            else:
                col.prop(scene.cycles, "filter_width", text="Width")
        else:
            col.prop(props, "exposure")
            col.prop(props, "filter_type")
            col.prop(props, "filter_width")
        layout.prop(scene.render, "film_transparent", text="Transparent")


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


class PHOTON_PT_passes_data(PhotonViewLayerPanel, bpy.types.Panel):
    """Blender's own pass toggles that Photon renders (data_passes.py), laid out as Cycles'
    Passes > Data and Light panels."""
    bl_label = "Data"
    bl_parent_id = "PHOTON_PT_passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        view_layer = context.view_layer
        col = layout.column(heading="Include", align=True)
        col.prop(view_layer, "use_pass_z")
        col.prop(view_layer, "use_pass_mist")
        col.prop(view_layer, "use_pass_position")
        col.prop(view_layer, "use_pass_normal")
        col.prop(view_layer, "use_pass_uv")
        col = layout.column(heading="Indexes", align=True)
        col.prop(view_layer, "use_pass_object_index")
        col.prop(view_layer, "use_pass_material_index")
        col = layout.column(heading="Color", align=True)
        col.prop(view_layer, "use_pass_diffuse_color", text="Diffuse")
        col.prop(view_layer, "use_pass_glossy_color", text="Glossy")
        col.prop(view_layer, "use_pass_transmission_color", text="Transmission")
        col.prop(view_layer, "use_pass_emit", text="Emission")
        cycles = getattr(view_layer, "cycles", None)  # Cycles keeps the Denoising Data toggle
        if cycles is not None:
            layout.column(heading="Denoising").prop(cycles, "denoising_store_passes",
                                                    text="Denoising Data")
        layout.prop(view_layer, "pass_alpha_threshold")


class PHOTON_PT_passes_cryptomatte(PhotonViewLayerPanel, bpy.types.Panel):
    """Blender's Cryptomatte toggles (Photon's IDs are always exact: no Accurate Mode)."""
    bl_label = "Cryptomatte"
    bl_parent_id = "PHOTON_PT_passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        view_layer = context.view_layer
        col = layout.column(heading="Include", align=True)
        col.prop(view_layer, "use_pass_cryptomatte_object", text="Object")
        col.prop(view_layer, "use_pass_cryptomatte_material", text="Material")
        col.prop(view_layer, "use_pass_cryptomatte_asset", text="Asset")
        layout.prop(view_layer, "pass_cryptomatte_depth", text="Levels")


class PHOTON_PT_passes_aov(PhotonViewLayerPanel, bpy.types.Panel):
    """View Layer > Shader AOV, as Blender draws it for EEVEE and Cycles: the AOVs that AOV
    Output nodes write (sync/aovs.py)."""
    bl_label = "Shader AOV"
    bl_parent_id = "PHOTON_PT_passes"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        view_layer = context.view_layer
        row = layout.row()
        list_type = "VIEWLAYER_UL_aov" if hasattr(bpy.types, "VIEWLAYER_UL_aov") else "UI_UL_list"
        row.column().template_list(list_type, "aovs", view_layer, "aovs", view_layer,
                                   "active_aov_index", rows=3)
        sub = row.column().column(align=True)
        sub.operator("scene.view_layer_add_aov", icon='ADD', text="")
        sub.operator("scene.view_layer_remove_aov", icon='REMOVE', text="")
        aov = view_layer.active_aov
        if aov and not aov.is_valid:
            layout.label(text="Conflicts with another render pass with the same name",
                         icon='ERROR')


class PHOTON_PT_layer_override(PhotonViewLayerPanel, bpy.types.Panel):
    """The view layer's Material Override (Blender draws it only in Cycles' own panel)."""
    bl_label = "Override"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(context.view_layer, "material_override")


class _IntegratorGroupPanel(PhotonPanel):
    """A panel of one integrator's schema group, shown while that integrator is chosen."""
    bl_parent_id = "PHOTON_PT_render"
    group = ""

    @classmethod
    def poll(cls, context):
        group = schema.group(cls.group)
        return super().poll(context) and group is not None and \
            context.scene.photon.integrator == group["integrator"]

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        schema.draw(layout, context.scene.photon, self.group)


class PHOTON_PT_sppm(_IntegratorGroupPanel, bpy.types.Panel):
    bl_label = "Progressive Photon Mapping"
    group = "sppm"


class PHOTON_PT_vcm(_IntegratorGroupPanel, bpy.types.Panel):
    bl_label = "Vertex Connection and Merging"
    group = "vcm"


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


class PhotonLightPanel(PhotonPanel):
    bl_context = "data"

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.light is not None


class PHOTON_PT_light(PhotonLightPanel, bpy.types.Panel):
    """What Photon renders of a lamp: its type, colour, power and size (Blender's own light
    panels are EEVEE's)."""
    bl_label = "Light"

    def draw(self, context):
        layout = self.layout
        light = context.light
        layout.row().prop(light, "type", expand=True)
        layout.use_property_split = True
        layout.use_property_decorate = False
        col = layout.column()
        settings = getattr(light, "photon", None)
        if settings is not None:
            col.prop(settings, "spectrum")
            if settings.spectrum == "BLACKBODY":
                col.prop(settings, "temperature")
            elif settings.spectrum == "ILLUMINANT":
                col.prop(settings, "illuminant")
        col.prop(light, "color")
        if hasattr(light, "use_temperature"):  # Blender 5.0+: tints the colour, as in Cycles
            row = col.row(align=True, heading="Temperature")
            row.prop(light, "use_temperature", text="")
            sub = row.row(align=True)
            sub.active = light.use_temperature
            sub.prop(light, "temperature", text="")
        col.prop(light, "energy")
        for name in ("exposure", "normalize"):  # Blender 5.0+
            if hasattr(light, name):
                col.prop(light, name)
        col.separator()
        if light.type in {'POINT', 'SPOT'}:
            col.prop(light, "shadow_soft_size", text="Radius")
        elif light.type == 'SUN':
            col.prop(light, "angle")
        elif light.type == 'AREA':
            col.prop(light, "shape")
            sub = col.column(align=True)
            if light.shape in {'SQUARE', 'DISK'}:
                sub.prop(light, "size")
            else:
                sub.prop(light, "size", text="Size X")
                sub.prop(light, "size_y", text="Y")


class PHOTON_PT_spot(PhotonLightPanel, bpy.types.Panel):
    bl_label = "Spot Shape"
    bl_parent_id = "PHOTON_PT_light"

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.light.type == 'SPOT'

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        light = context.light
        col = layout.column()
        col.prop(light, "spot_size", text="Size")
        col.prop(light, "spot_blend", text="Blend")
        col.prop(light, "show_cone")


class PHOTON_PT_material(PhotonPanel, bpy.types.Panel):
    """Material > Photon: settings Photon reads beside the node tree."""
    bl_label = "Photon"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.material is not None and \
            hasattr(context.material, "photon")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(context.material.photon, "abbe_number")


class PhotonObjectVisibilityPanel(PhotonPanel):
    """A subpanel of Object > Visibility for an object flag Photon reads (`flag`)."""
    bl_context = "object"
    bl_parent_id = "OBJECT_PT_visibility"
    flag = ""

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.object is not None and \
            hasattr(context.object, cls.flag)


class PHOTON_PT_object_ray_visibility(PhotonObjectVisibilityPanel, bpy.types.Panel):
    """Object > Visibility > Ray Visibility: the per-ray-type flags Photon honours (Blender draws
    them only in Cycles' panel)."""
    bl_label = "Ray Visibility"
    flag = "visible_camera"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        ob = context.object
        col = layout.column(heading="Ray Visibility", align=True)
        col.prop(ob, "visible_camera", text="Camera", toggle=False)
        col.prop(ob, "visible_diffuse", text="Diffuse", toggle=False)
        col.prop(ob, "visible_glossy", text="Glossy", toggle=False)
        col.prop(ob, "visible_transmission", text="Transmission", toggle=False)
        if ob.type != 'LIGHT':
            col.prop(ob, "visible_shadow", text="Shadow", toggle=False)


class PHOTON_PT_object_mask(PhotonObjectVisibilityPanel, bpy.types.Panel):
    """Object > Visibility > Mask: Blender's own panel shows Holdout; the shadow catcher flag is
    drawn only by Cycles' panel, so Photon draws it here."""
    bl_label = "Shadow Catcher"
    flag = "is_shadow_catcher"

    def draw_header(self, context):
        self.layout.prop(context.object, "is_shadow_catcher", text="")

    def draw(self, context):
        self.layout.label(text="Renders only the shadows cast on it")


classes = (PHOTON_PT_render, PHOTON_PT_spectral, PHOTON_PT_photon_mapping, PHOTON_PT_radiosity,
           PHOTON_PT_sppm,
           PHOTON_PT_vcm,
           PHOTON_PT_simplify, PHOTON_PT_simplify_viewport, PHOTON_PT_simplify_render,
           PHOTON_PT_performance, PHOTON_PT_film, PHOTON_PT_passes, PHOTON_PT_passes_data,
           PHOTON_PT_passes_cryptomatte, PHOTON_PT_passes_aov, PHOTON_PT_layer_override,
           PHOTON_PT_light, PHOTON_PT_spot, PHOTON_PT_material, PHOTON_PT_object_ray_visibility,
           PHOTON_PT_object_mask)


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
