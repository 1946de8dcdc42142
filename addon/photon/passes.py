"""The render result's passes: registering the ones Photon writes (Combined, the light passes of
properties.LIGHT_PASSES, the data and Cryptomatte passes of data_passes.py) so they exist in the
compositor, and writing finished tiles (or a whole preview image) into them, with the
Cryptomatte metadata Blender's Cryptomatte node reads."""

import numpy as np

from . import data_passes, properties
from .native import native_module


def register(engine, scene, view_layer):
    """RenderEngine.update_render_passes: registering makes the passes exist in the
    compositor's Render Layers node."""
    engine.register_pass(scene, view_layer, "Combined", 4, "RGBA", "COLOR")
    for name in properties.enabled_passes(view_layer):
        engine.register_pass(scene, view_layer, name, 3, "RGB", "COLOR")
    try:
        native = native_module()
    except RuntimeError:
        return  # render() reports the failed import
    data_passes.register(engine, native, scene, view_layer)


def add_light_passes(engine, view_layer):
    """Adds the view layer's enabled light passes to the result of the render in progress;
    returns their names."""
    enabled = properties.enabled_passes(view_layer)
    for name in enabled:
        engine.add_pass(name, 3, "RGB", layer=view_layer.name)
    return enabled


def add_cryptomatte_metadata(engine, sync_stats, layer):
    """The Cryptomatte layers' names, hashing and manifests into the result's metadata, as
    Cycles writes them (Blender's Cryptomatte node reads them)."""
    crypto = sync_stats.cryptomatte
    if crypto is None or not crypto.any():
        return
    metadata = crypto.layer_metadata(layer)
    if metadata:
        final = engine.get_result()  # the render's own result (not a tile's), as Cycles does
        for key, value in metadata:
            final.stamp_data_add_field(key, value)


class TileWriter:
    """Writes tiles into one view layer and view of the engine's render result, every pass by
    its name (as Cycles' output driver reads passes); `missing` collects the passes of the
    result Photon did not write."""

    def __init__(self, engine, layer="", view=""):
        self.engine = engine
        self.layer = layer
        self.view = view  # the multiview view ("": every view of a mono render)
        self.missing = set()

    def write(self, x, y_bottom, w, h, rgba, tile_passes=None, preview=False):
        """Writes a tile: Combined from `rgba`, every other pass of the result from
        `tile_passes` ({name: [h, w, channels]}, top row first). With `preview` (the quick
        preview), Combined only: the other passes stay zero until their tiles come."""
        # Native tiles are top row first; Blender's result rows go bottom-up.
        pixels = np.ascontiguousarray(rgba[::-1], dtype=np.float32)
        result = self.engine.begin_result(x, y_bottom, w, h, layer=self.layer, view=self.view)
        passes = result.layers[0].passes
        if len(passes) == 1:
            passes.foreach_set("rect", pixels.ravel())
        else:
            tile_passes = tile_passes or {}
            parts = []
            for render_pass in passes:
                ours = tile_passes.get(render_pass.name)
                if render_pass.name == "Combined":
                    parts.append(pixels.ravel())
                elif ours is not None and ours.shape[2] == render_pass.channels:
                    parts.append(np.ascontiguousarray(ours[::-1], dtype=np.float32).ravel())
                else:
                    # Passes Photon does not produce (enabled on the view layer): Blender's
                    # default, zero, and one warning after the render.
                    if not preview:
                        self.missing.add(render_pass.name)
                    parts.append(np.zeros(w * h * render_pass.channels, dtype=np.float32))
            passes.foreach_set("rect", np.concatenate(parts))
        self.engine.end_result(result)
