"""The Properties editor with Photon as the engine shows the settings Photon honours, once each:
one Light panel without EEVEE's factors, the object's ray visibility."""


def panels(blender):
    result, _ = blender.run_script("photon_panels.py")
    return result


def test_one_light_panel_and_no_eevee_only_light_settings(blender):
    data = panels(blender)["data"]
    names = {name for name, _label, _parent, _order in data}
    top_level_light = [name for name, label, parent, _ in data if label == "Light" and not parent]
    assert top_level_light == ["PHOTON_PT_light"], data
    # EEVEE's Light panel (diffuse / specular / volume factors) and its Custom Distance.
    assert not names & {"DATA_PT_EEVEE_light", "DATA_PT_EEVEE_light_distance", "DATA_PT_light"}
    assert "PHOTON_PT_spot" in names


def test_object_visibility_shows_the_ray_flags_photon_reads(blender):
    names = {name for name, _l, _p, _o in panels(blender)["object"]}
    assert {"OBJECT_PT_visibility", "PHOTON_PT_object_ray_visibility",
            "PHOTON_PT_object_mask"} <= names


def test_view_layer_passes_offer_cryptomatte_and_denoising_data(blender):
    """Passes Photon writes have their toggles under Photon Passes (Blender's own Passes
    panel, which lists passes Photon does not write, is hidden)."""
    data = panels(blender)["view_layer"]
    children = {name: parent for name, _label, parent, _order in data}
    assert children.get("PHOTON_PT_passes_cryptomatte") == "PHOTON_PT_passes", data
    assert children.get("PHOTON_PT_passes_data") == "PHOTON_PT_passes", data
    assert "VIEWLAYER_PT_layer_passes" not in children
