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
