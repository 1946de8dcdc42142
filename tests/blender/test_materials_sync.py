"""Blender node trees to native closure lists (addon/photon/sync/materials.py), and the native
parser (_photon.describe_material) agreeing with what the add-on sends."""

import math
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402


@pytest.fixture(scope="module")
def converted(blender, tmp_path_factory):
    folder = tmp_path_factory.mktemp("material_images")
    result, proc = blender.run_script("material_closures.py", folder)
    assert "exception" not in result, result.get("exception")
    yield result
    if result.get("temp_dir"):
        shutil.rmtree(result["temp_dir"], ignore_errors=True)


def material(converted, name):
    return converted["materials"][name]


def only_closure(converted, name):
    closures = material(converted, name)["closures"]
    assert len(closures) == 1, closures
    return closures[0]


def close(a, b, tol=1e-5):
    return np.allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), atol=tol)


def test_principled_metal_reads_its_inputs_and_reports_the_subsurface_fallback_once(
        blender, converted):
    closure = only_closure(converted, "Metal")
    assert closure["weight"] == []
    p = closure["params"]
    assert close(p["color"], [0.9, 0.6, 0.2])
    assert close(p["emission"], [1.0, 0.5, 0.0]) and close(p["strength"], 3.0)
    warnings = material(converted, "Metal")["warnings"]
    if blender.version < (4, 0):
        assert closure["type"] == "PRINCIPLED"
        assert close([p["metallic"], p["roughness"], p["clearcoat"], p["clearcoat_roughness"]],
                     [1.0, 0.2, 0.4, 0.1])
        assert close([p["specular"], p["ior"], p["alpha"], p["transmission"]],
                     [0.5, 1.45, 1.0, 0])
        assert close([p["sheen"], p["sheen_tint"], p["subsurface"]], [0.3, 0.5, 0.1])
        assert warnings == [
            "Material 'Metal': subsurface scattering is not supported; Subsurface is rendered "
            "as diffuse mixed towards Subsurface Color (as Cycles renders it without "
            "subsurface scattering)"]
        return
    # Principled v2: the v1 inputs the scene sets land on their v2 sockets (Clearcoat on Coat
    # Weight, Sheen on Sheen Weight, Subsurface on Subsurface Weight).
    assert closure["type"] == "PRINCIPLED_V2"
    assert close([p["metallic"], p["roughness"], p["coat_weight"], p["coat_roughness"]],
                 [1.0, 0.2, 0.4, 0.1])
    assert close([p["specular_ior_level"], p["ior"], p["alpha"], p["transmission"]],
                 [0.5, 1.5, 1.0, 0])
    assert close([p["sheen_weight"], p["subsurface"]], [0.3, 0.1])
    assert close(p["sheen_tint_color"], [1.0, 1.0, 1.0])
    assert warnings == [
        "Material 'Metal': subsurface scattering is not supported; Subsurface Weight is "
        "rendered as diffuse of the Base Color",
        "Material 'Metal': Principled BSDF inputs not supported yet are rendered at their "
        "defaults: Sheen Weight"]


def test_mix_by_image_alpha_gives_complementary_weights_on_the_texture(blender, converted):
    closures = material(converted, "MixAlpha")["closures"]
    # From Blender 4.0 the Glossy node is the merged Glossy/Anisotropic one.
    glossy_type = "GLOSSY" if blender.version < (4, 0) else "ANISOTROPIC"
    assert [c["type"] for c in closures] == ["DIFFUSE", glossy_type]
    diffuse, glossy = closures
    index = diffuse["params"]["color"]["texture"]
    assert diffuse["params"]["color"] == {"texture": index, "channel": "COLOR"}
    fac = {"texture": index, "channel": "ALPHA"}
    assert diffuse["weight"] == [{"fac": fac, "complement": True}]
    assert glossy["weight"] == [{"fac": fac, "complement": False}]
    assert not glossy["sharp"] and close(glossy["params"]["roughness"], 0.3)
    assert glossy["beckmann"]  # the node's distribution, rendered as itself
    texture = converted["textures"][index]
    assert texture["path"].endswith("color.png")
    assert (texture["srgb"], texture["extension"], texture["interpolation"]) == (
        True, "CLIP", "Cubic")  # Smart renders as Cubic
    assert material(converted, "MixAlpha")["warnings"] == []


def test_multiscatter_ggx_is_rendered_in_4x_and_reported_in_3x(blender, converted):
    closure = only_closure(converted, "MultiGlossy")
    warnings = material(converted, "MultiGlossy")["warnings"]
    if blender.version >= (4, 0):
        assert closure["multiscatter"] and warnings == []
    else:
        assert "multiscatter" not in closure
        assert warnings == [
            "Material 'MultiGlossy': node 'Glossy BSDF': the Multiscatter GGX distribution is "
            "rendered as single-scattering GGX (darker where rough)"]


def test_ashikhmin_shirley_is_rendered_as_ggx_and_reported(blender, converted):
    closure = only_closure(converted, "AshikhminGlossy")
    # Blender 4's Glossy BSDF is the anisotropic one (it absorbed the Anisotropic BSDF).
    assert closure["type"] == ("ANISOTROPIC" if blender.version >= (4, 0) else "GLOSSY")
    assert not closure.get("beckmann") and not closure["sharp"]
    assert close(closure["params"]["roughness"], 0.4)
    assert material(converted, "AshikhminGlossy")["warnings"] == [
        "Material 'AshikhminGlossy': node 'Glossy BSDF': the Ashikhmin Shirley distribution is "
        "rendered as GGX"]


def test_add_shader_through_reroute_keeps_both_and_shares_the_texture(converted):
    closures = material(converted, "AddEmit")["closures"]
    assert [c["type"] for c in closures] == ["DIFFUSE", "EMISSION"]
    assert all(c["weight"] == [] for c in closures)
    mix_texture = material(converted, "MixAlpha")["closures"][0]["params"]["color"]["texture"]
    add_texture = closures[0]["params"]["color"]["texture"]
    # One texture per image and reading: MixAlpha's node uses its Alpha output, so its colour is
    # divided by alpha after the lookup (Cycles' unassociate) and AddEmit's is not; both read
    # the same premultiplied conversion of the file.
    mix, add = converted["textures"][mix_texture], converted["textures"][add_texture]
    assert (mix["path"], mix["alpha"], mix["unassociate"]) == (add["path"], "ASSOCIATE", True)
    assert not add["unassociate"]
    assert close(closures[1]["params"]["color"], [1.0, 0.9, 0.8])
    assert close(closures[1]["params"]["strength"], 5.0)
    paths = [t.get("path", "") for t in converted["textures"]]
    settings = [(t.get("path", t.get("name")), t["extension"], t["interpolation"],
                 t["unassociate"]) for t in converted["textures"]]
    assert len(set(settings)) == len(settings)
    # CLIP/Cubic with and without Alpha used, and EXTEND/Closest
    assert sum(p.endswith("color.png") for p in paths) == 3


def test_constant_mixes_prune_and_weight(blender, converted):
    closures = material(converted, "MixConst")["closures"]
    # Mix(0.25, Mix(0, Glass, Transparent), Add(Translucent, Refraction)).
    assert [c["type"] for c in closures] == ["GLASS", "TRANSLUCENT", "REFRACTION"]
    glass, translucent, refraction = closures
    # Sharp glass: 3.x's Sharp distribution, GGX at roughness 0 from 4.0 (Sharp is gone).
    assert close(glass["params"]["ior"], 1.5)
    assert glass["sharp"] if blender.version < (4, 0) else close(glass["params"]["roughness"], 0)
    # Constant factors reach the native side multiplied into one number per closure.
    assert glass["weight"] == [{"fac": 0.75, "complement": False}]
    assert translucent["weight"] == refraction["weight"] == [{"fac": 0.25, "complement": False}]
    assert not refraction["sharp"]


def test_packed_and_generated_images_are_written_for_openimageio(converted):
    closure = only_closure(converted, "Packed")
    packed = converted["textures"][closure["params"]["color"]["texture"]]
    assert packed["path"].startswith(converted["temp_dir"]) and packed["path"].endswith(".png")
    assert packed["interpolation"] == "Closest" and packed["srgb"]
    pixels = read_image(packed["path"])
    assert pixels.shape == (2, 4, 4)
    # Alpha is 0 on one row and 1 on the other; OpenImageIO premultiplies, so read the opaque row.
    assert close(pixels[..., 3], [[1.0] * 4, [0.0] * 4])
    assert close(pixels[0, :, :3], np.broadcast_to([0.1, 0.2, 0.3], (4, 3)), tol=2 / 255)
    # The generated image: its pixels in native memory as Blender holds them, bottom row first
    # (a byte image's generated colour is sRGB-encoded, as Cycles reads it), decoded natively
    # because of the srgb flag.
    roughness = closure["params"]["roughness"]
    assert isinstance(roughness, dict), roughness
    generated = converted["textures"][roughness["texture"]]
    assert generated["srgb"] and (generated["width"], generated["height"]) == (4, 4)
    pixels = np.array(generated["pixels"]).reshape(4, 4, 4)
    assert close(pixels, np.broadcast_to([0.2, 0.4, 0.6, 1.0], (4, 4, 4)), tol=1 / 255)


def test_missing_image_warns_with_its_path_and_falls_back(converted):
    p = only_closure(converted, "Missing")["params"]
    assert p["color"] == [0.8, 0.8, 0.8]       # neutral grey, not magenta or black
    assert close(p["metallic"], 0.35)          # the Alpha fed Metallic: its own value
    assert material(converted, "Missing")["warnings"] == [
        "Material 'Missing': node 'Gone Texture': image file '/nonexistent/photon/gone.png' "
        "is missing; using a constant instead"]


def test_unsupported_nodes_fall_back_to_their_nearest_meaning(converted):
    p = only_closure(converted, "Wave")["params"]
    assert close(p["color"], [0.1, 0.5, 0.2])  # Base Color's own value, not the wireframe
    # Image (through Mapping of Generated) -> Ambient Occlusion -> Emission: the image, through
    # the unsupported node, read by the material's shader program.
    assert set(p["emission"]) == {"register", "value"}
    assert any(t.get("path", "").endswith("color.png") and
               (t["extension"], t["interpolation"]) == ("EXTEND", "Closest")
               for t in converted["textures"])
    program = material(converted, "Wave")["program"]
    types = [n["type"] for n in program["nodes"]]
    assert types == ["ShaderNodeTexCoord", "ShaderNodeMapping", "ShaderNodeTexImage"], types
    warnings = material(converted, "Wave")["warnings"]
    assert ("Material 'Wave': node 'Wavy' (ShaderNodeWireframe) is not supported yet; using the "
            "value of the 'Base Color' input it feeds") in warnings
    assert any("node 'Hue Fix'" in w and "using its Color input" in w for w in warnings)
    assert len(warnings) == 2, warnings

    toon = only_closure(converted, "Toon")
    assert toon["type"] == "DIFFUSE" and close(toon["params"]["color"], [0.2, 0.4, 0.9])
    assert material(converted, "Toon")["warnings"] == [
        "Material 'Toon': node 'Toon BSDF' (ShaderNodeBsdfToon) is not supported yet; "
        "rendering it as diffuse"]


def test_colour_and_value_outputs_into_a_shader_input_emit_as_in_cycles(converted):
    """Cycles turns a colour (or value) output linked into a shader input into an Emission of
    that colour at strength 1 (of white at that strength), with no warning."""
    checker = only_closure(converted, "ColorToSurface")
    assert checker["type"] == "EMISSION" and checker["params"]["strength"] == 1.0
    assert set(checker["params"]["color"]) == {"register", "value"}  # the checker's program
    assert material(converted, "ColorToSurface")["warnings"] == []
    value = only_closure(converted, "ValueToSurface")
    assert value["type"] == "EMISSION" and value["params"] == {
        "color": [1.0, 1.0, 1.0], "strength": 2.5}
    assert material(converted, "ValueToSurface")["warnings"] == []
    closures = material(converted, "MixedWithColor")["closures"]
    assert [c["type"] for c in closures][1:] == ["EMISSION"], closures
    assert close(closures[1]["params"]["color"], [0.9, 0.3, 0.1])
    assert closures[1]["weight"] == [{"fac": 0.25, "complement": False}]


def test_colour_into_the_surface_renders_as_cycles_does(blender, tmp_path):
    """A Checker's Color straight into the Material Output: the checker, unlit, in both."""
    images = {}
    for engine in ("CYCLES", "PHOTON"):
        out = tmp_path / f"{engine}.exr"
        result, proc = blender.run_script("color_to_surface.py", engine, out)
        assert "exception" not in result, result.get("exception")
        images[engine] = read_image(out)[:, :, :3]
    ours, theirs = images["PHOTON"], images["CYCLES"]
    assert theirs.mean() > 0.1, "Cycles' render is black"
    # Emission seen directly: only the checker's edges differ, by their pixel-filter noise.
    assert np.abs(ours.mean(axis=(0, 1)) / theirs.mean(axis=(0, 1)) - 1.0).max() < 0.01
    assert np.mean(np.abs(ours - theirs) > 0.05) < 0.1


def test_node_group_inputs_reach_the_inner_shader(blender, converted):
    closure = only_closure(converted, "Grouped")
    assert closure["type"] == ("PRINCIPLED" if blender.version < (4, 0) else "PRINCIPLED_V2")
    assert close(closure["params"]["color"], [0.2, 0.3, 0.4])
    assert close(closure["params"]["roughness"], 0.65)   # a Value node outside the group
    assert material(converted, "Grouped")["warnings"] == []


def test_normal_maps(converted):
    bumpy = only_closure(converted, "Bumpy")
    assert close(bumpy["params"]["color"], [0.05, 0.1, 0.15])  # RGB node
    normal = bumpy["normal_map"]
    assert close(normal["strength"], 0.7)
    texture = converted["textures"][normal["texture"]]
    assert texture["path"].endswith("normal.png") and texture["srgb"] is False
    # Object space: the shader program's Normal Map node computes the normal.
    other = only_closure(converted, "ObjectNormals")
    assert "normal_map" not in other and set(other["normal"]) == {"register"}
    program = material(converted, "ObjectNormals")["program"]
    assert [n["type"] for n in program["nodes"]][-1] == "ShaderNodeNormalMap"
    assert program["nodes"][-1]["enums"]["space"] == "OBJECT"
    assert material(converted, "ObjectNormals")["warnings"] == []


def test_absurd_values_are_clamped_with_warnings(converted):
    p = only_closure(converted, "Absurd")["params"]
    assert p["roughness"] == 0.5 and p["strength"] == 1e6 and p["ior"] == pytest.approx(1e-3)
    warnings = " | ".join(material(converted, "Absurd")["warnings"])
    assert "'Roughness' of node 'Principled BSDF' is not a finite number" in warnings
    assert "'Emission Strength' of node 'Principled BSDF' is 1e+30" in warnings
    assert "'IOR' of node 'Principled BSDF' is -3" in warnings


def test_materials_without_shaders_use_the_viewport_colour(blender, converted):
    # Blender 5.0 dropped Material.use_nodes: a new material always renders its node tree (the
    # default Principled BSDF), in Cycles as in Photon.
    no_nodes = [0.3, 0.2, 0.1] if blender.version < (5, 0) else [0.8, 0.8, 0.8]
    assert close(only_closure(converted, "NoNodes")["params"]["color"], no_nodes)
    assert close(only_closure(converted, "Unconnected")["params"]["color"], [0.6, 0.5, 0.4])
    assert material(converted, "Unconnected")["warnings"] == [
        "Material 'Unconnected' has no shader connected to its output; rendering its "
        "viewport colour"]


# ---- The native parser: _photon.describe_material in Debian's python3 ----

def assert_same_value(sent, parsed, where):
    if isinstance(sent, dict) and "register" in sent:
        # Described without its program, a program input keeps the constant sent with it.
        sent = sent.get("value", parsed)
    if isinstance(sent, dict):
        assert parsed == {"channel": "COLOR", **sent}, where
    else:
        assert close(sent, parsed, tol=1e-6 * max(1.0, np.max(np.abs(sent)))), where


def test_describe_material_round_trips_every_converted_material(converted, native):
    count = len(converted["textures"])
    for name, entry in converted["materials"].items():
        described = native.describe_material(name, entry["closures"], count)
        assert described["name"] == name
        assert len(described["closures"]) == len(entry["closures"]), name
        for sent, parsed in zip(entry["closures"], described["closures"]):
            where = f"{name} {sent['type']}"
            assert parsed["type"] == sent["type"] and parsed["sharp"] == sent["sharp"], where
            for key, value in sent["params"].items():
                assert_same_value(value, parsed["params"][key], f"{where} {key}")
            assert len(parsed["weight"]) == len(sent["weight"]), where
            for w_sent, w_parsed in zip(sent["weight"], parsed["weight"]):
                assert w_parsed["complement"] == w_sent["complement"], where
                assert_same_value(w_sent["fac"], w_parsed["fac"], f"{where} fac")
            if "normal_map" in sent:
                assert parsed["normal_map"]["texture"] == sent["normal_map"]["texture"]
                assert close(parsed["normal_map"]["strength"], sent["normal_map"]["strength"])
            else:
                assert "normal_map" not in parsed, where


def test_describe_material_defaults_clamps_and_fallbacks(native):
    closures = [{"type": "GLOSSY", "sharp": True,
                 "params": {"color": 0.5, "roughness": math.nan, "ior": 1e9,
                            "metallic": {"texture": 7, "channel": "ALPHA"}},
                 "normal_map": {"texture": 9, "strength": 2.0},
                 "weight": [{"fac": math.inf, "complement": True},
                            {"fac": {"texture": 1}}]}]
    parsed = native.describe_material("m", closures, 2)["closures"][0]
    assert parsed["sharp"] and parsed["params"]["color"] == [0.5, 0.5, 0.5]
    assert parsed["params"]["ior"] == 100.0                   # clamped to the range
    default = native.describe_material("d", [{"type": "GLOSSY"}])["closures"][0]["params"]
    assert parsed["params"]["roughness"] == default["roughness"]   # NaN -> default
    assert parsed["params"]["metallic"] == default["metallic"]     # texture 7 of 2 -> default
    assert "normal_map" not in parsed                              # texture 9 of 2 -> none
    assert parsed["weight"][0] == {"fac": 0.5, "complement": True}  # inf -> Mix default
    assert parsed["weight"][1] == {"fac": {"texture": 1, "channel": "COLOR"},
                                   "complement": False}
    # Blender's Principled defaults for params a closure does not send.
    assert close([default["specular"], default["ior"], default["alpha"], default["strength"]],
                 [0.5, 1.45, 1.0, 1.0])
    assert default["emission"] == [0.0, 0.0, 0.0]


@pytest.mark.parametrize("closure, message", [
    ({"type": "TOON"}, "unknown closure type 'TOON'"),
    ({"type": "DIFFUSE", "colour": [1, 1, 1]}, "unknown key 'colour'"),
    ({"type": "DIFFUSE", "params": {"velvet": 1.0}}, "unknown param 'velvet'"),
    ({"type": "DIFFUSE", "params": {"color": {"texture": 0, "channel": "RED"}}},
     "unknown channel 'RED'"),
    ({"type": "DIFFUSE", "params": {"roughness": [1, 2, 3]}}, "expects a number or a texture"),
    ({"type": "DIFFUSE", "weight": [{"factor": 0.5}]}, "unknown key 'factor'"),
    ({"params": {}}, "has no 'type'"),
])
def test_describe_material_rejects_what_the_addon_never_sends(native, closure, message):
    with pytest.raises(ValueError, match=message):
        native.describe_material("bad", [closure])


def test_scene_adds_textures_and_materials(native):
    scene = native.Scene()
    assert scene.add_texture("/a.png") == 0
    assert scene.add_texture("/b.exr", srgb=False, extension="CLIP", interpolation="Cubic") == 1
    assert scene.texture_count == 2
    with pytest.raises(ValueError, match="unknown texture extension 'MIRROR'"):
        scene.add_texture("/c.png", extension="MIRROR")
    with pytest.raises(ValueError, match="unknown texture interpolation 'Smart'"):
        scene.add_texture("/c.png", interpolation="Smart")  # the add-on sends Cubic
    closures = [{"type": "DIFFUSE", "params": {"color": {"texture": 1}}}]
    assert scene.add_material("a", closures) == 0
    assert scene.add_material("b", [{"type": "EMISSION", "params": {"strength": 2.0}}]) == 1
    with pytest.raises(ValueError, match="unknown closure type"):
        scene.add_material("c", [{"type": "TOON"}])  # the add-on never sends it
    assert scene.material_count == 2


# ---- A render through the engine: needs Scene.add_material / add_texture ----

def test_render_with_textures_and_unsupported_nodes_finishes_with_warnings(
        blender, tmp_path, monkeypatch):
    temp = tmp_path / "tmp"
    temp.mkdir()
    monkeypatch.setenv("TMPDIR", str(temp))  # where the packed image is written
    blend = tmp_path / "materials.blend"
    blender.run_script("make_material_scene.py", tmp_path / "images", blend)
    proc = blender.run([str(blend), "-E", "PHOTON", "-o", str(tmp_path / "out_####"),
                        "-F", "OPEN_EXR", "-x", "1", "-f", "1"], check=False)
    assert proc.returncode == 0, proc.log
    assert "Photon: rendered frame 1" in proc.stdout, proc.log
    assert np.isfinite(read_image(tmp_path / "out_0001.exr")).all()
    for expected in [
            "Material 'WaveMat': node 'Wireframe' (ShaderNodeWireframe) is not supported yet; "
            "using the value of the 'Base Color' input it feeds",
            f"Material 'WaveMat': node 'Lost Texture': image file "
            f"'{tmp_path / 'images' / 'lost.png'}' is missing; using a constant instead",
            "Material 'ToonMat': node 'Toon BSDF' (ShaderNodeBsdfToon) is not supported yet; "
            "rendering it as diffuse"]:
        assert f"Photon: warning: {expected}" in proc.stdout, f"missing {expected!r}\n{proc.log}"
    assert "TexturedMix" not in proc.stdout, proc.log  # nothing to say about it
    # The packed image was written for the render and deleted after it.
    assert not list(temp.glob("photon_textures_*")), list(temp.iterdir())
