"""Registration state of the add-on, before and after disabling and re-enabling it."""

import addon_utils
import bpy

import harness


def engine_registered():
    # What an artist sees: can the scene's render engine be set to PHOTON?
    render = bpy.context.scene.render
    previous = render.engine
    try:
        render.engine = "PHOTON"
        return True
    except TypeError:
        return False
    finally:
        render.engine = previous


def main():
    import photon
    result = {"import_error": photon.NATIVE_IMPORT_ERROR,
              "engine_registered": engine_registered(),
              "has_settings": hasattr(bpy.types.Scene, "photon")}
    s = bpy.context.scene.photon
    result["defaults"] = {name: getattr(s, name) for name in (
        "integrator", "samples", "max_depth", "seed", "threads", "tile_size")}
    result["panel_registered"] = hasattr(bpy.types, "PHOTON_PT_render")
    addon_utils.disable("photon", default_set=True)
    result["after_disable"] = {"engine_registered": engine_registered(),
                               "has_settings": hasattr(bpy.types.Scene, "photon"),
                               "panel_registered": hasattr(bpy.types, "PHOTON_PT_render")}
    addon_utils.enable("photon", default_set=True)
    result["after_enable"] = {"engine_registered": engine_registered(),
                              "has_settings": hasattr(bpy.types.Scene, "photon")}
    return result


harness.run(main)
