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


def test_view_layer_passes_offer_cryptomatte_denoising_data_and_shader_aovs(blender):
    """Passes Photon writes have their toggles under Photon Passes (Blender's own Passes
    panel, which lists passes Photon does not write, is hidden)."""
    data = panels(blender)["view_layer"]
    children = {name: parent for name, _label, parent, _order in data}
    assert children.get("PHOTON_PT_passes_cryptomatte") == "PHOTON_PT_passes", data
    assert children.get("PHOTON_PT_passes_aov") == "PHOTON_PT_passes", data
    assert children.get("PHOTON_PT_passes_data") == "PHOTON_PT_passes", data
    assert "VIEWLAYER_PT_layer_passes" not in children


def test_simplify_is_photons_own_below_its_render_panels(blender):
    """Blender's Simplify panel, registered before any add-on, sat above Photon's panels;
    Photon shows its own copy of it, registered after its render panels (as Cycles does)."""
    data = panels(blender)["render"]
    names = [name for name, _label, _parent, _order in data]
    assert "RENDER_PT_simplify" not in names and "RENDER_PT_simplify_greasepencil" not in names
    parents = {name: parent for name, _label, parent, _order in data}
    assert parents.get("PHOTON_PT_simplify_viewport") == "PHOTON_PT_simplify"
    assert parents.get("PHOTON_PT_simplify_render") == "PHOTON_PT_simplify"
    assert names.index("PHOTON_PT_render") < names.index("PHOTON_PT_simplify")


def test_the_light_panel_shows_the_light_settings_photon_renders(blender):
    """Drawn for each light type: every property exists on the light, and Blender 5.0's
    Temperature, Exposure and Normalize (which Photon renders as Cycles does) are shown."""
    result, proc = blender.run_script("light_panel_props.py")
    for light_type, shown in result["lights"].items():
        missing = [name for _owner, name, exists in shown if not exists]
        assert not missing, (light_type, missing, proc.log)
        names = {name for _owner, name, _exists in shown}
        assert {"color", "energy"} <= names, (light_type, shown)
        newer = {"use_temperature", "temperature", "exposure", "normalize"}
        if result["version"] >= [5, 0, 0]:
            assert newer <= names, (light_type, shown)
        else:
            assert not newer & names, (light_type, shown)
    assert {"spot_size", "spot_blend"} <= {n for _o, n, _e in result["lights"]["SPOT"]}
