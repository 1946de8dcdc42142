"""Per-view-layer settings of the view layer being rendered: a collection's Indirect Only and
Holdout toggles, and the layer's Material Override (the depsgraph of that layer already leaves
out excluded collections and disabled objects)."""


def material_override(depsgraph):
    """The view layer's override material (evaluated when the depsgraph holds it), or None."""
    material = getattr(depsgraph.view_layer, "material_override", None)
    if material is None:
        return None
    try:
        return depsgraph.id_eval_get(material)
    except (KeyError, RuntimeError, ReferenceError):
        return material


def _any_layer_flag(layer_collection):
    """True when any collection of the view layer is set holdout or indirect-only."""
    todo = [layer_collection]
    while todo:
        layer = todo.pop()
        if layer.holdout or layer.indirect_only:
            return True
        todo.extend(layer.children)
    return False


class LayerVisibility:
    """Applies the view layer's indirect-only state of an object to its native ray visibility,
    as Cycles' object sync does (indirect-only objects lose camera visibility; holdout wins over
    indirect-only, and holdouts themselves are drawn by sync_mattes)."""

    def __init__(self, native, depsgraph, reporter):
        self._native = native
        self._view_layer = depsgraph.view_layer_eval
        # Most scenes set neither toggle on any collection: then nothing is looked up per object.
        self._collections = _any_layer_flag(depsgraph.view_layer.layer_collection)
        self._cache = {}  # object name -> (holdout, indirect only)

    def apply(self, inst, obj, visibility):
        """`visibility` of depsgraph instance `inst` of object `obj`; an instance's instancer
        decides, as its collections hold the instance (Cycles reads the parent's flags)."""
        if not self._collections and not getattr(obj, "is_holdout", False):
            return visibility
        if inst.is_instance and inst.parent is not None:
            obj = inst.parent
        flags = self._cache.get(obj.name)
        if flags is None:
            holdout = bool(obj.holdout_get(view_layer=self._view_layer))
            indirect = not holdout and bool(obj.indirect_only_get(view_layer=self._view_layer))
            flags = self._cache[obj.name] = (holdout, indirect)
        if flags[1]:
            visibility &= ~self._native.VISIBLE_CAMERA
        return visibility
