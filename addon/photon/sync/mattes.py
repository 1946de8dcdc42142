"""Holdout and shadow-catcher flags of the objects a render draws (native Instance::holdout and
Instance::shadow_catcher; what the renderer does with them is in native/src/photon/integrators/matte.h).

As Cycles reads them (blender/object.cpp, Blender 3.4): an object is a holdout when its own
Object > Visibility > Holdout is set, or when it or the object instancing it is held out in the
view layer (`Object.holdout_get`: a layer collection marked Holdout, or the object's own flag);
it is a shadow catcher when it or its instancer has Object > Visibility > Shadow Catcher.
"""


class MatteFlags:
    """(holdout, shadow catcher) per depsgraph object instance, looked up once per object."""

    def __init__(self, depsgraph):
        self._view_layer = getattr(depsgraph, "view_layer", None)
        self._held = {}  # original object name -> held out in the view layer

    def _held_in_layer(self, obj):
        if obj is None or self._view_layer is None:
            return False
        original = getattr(obj, "original", obj) or obj
        key = original.name_full
        found = self._held.get(key)
        if found is None:
            try:
                # Base flags live on the original object and view layer: the evaluated
                # object's holdout_get reports False.
                found = bool(original.holdout_get(view_layer=self._view_layer))
            except (RuntimeError, ReferenceError, TypeError):
                found = False  # not in this view layer (an instanced object): no base flag
            self._held[key] = found
        return found

    def of(self, obj, parent=None):
        """(holdout, shadow_catcher) of evaluated object `obj`, instanced by `parent` (or None
        when it is drawn by itself)."""
        holdout = bool(getattr(obj, "is_holdout", False))
        holdout = holdout or self._held_in_layer(parent if parent is not None else obj)
        catcher = bool(getattr(obj, "is_shadow_catcher", False)) or (
            parent is not None and bool(getattr(parent, "is_shadow_catcher", False)))
        return holdout, catcher
