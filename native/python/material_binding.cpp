#include "material_binding.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "photon/scene/material_params.h"
#include "photon/session/image_io.h"
#include "photon/shading/texture_convert.h"
#include "photon/spectral/dispersion.h"
#include "program_binding.h"

namespace py = pybind11;
using namespace photon;

namespace photon_python {
namespace {

[[noreturn]] void fail(const std::string& message) {
  throw py::value_error(message);
}

// A texture index as stored in an Input: negative means none, anything past int32 is out of
// range for every scene (sanitize_material then drops it).
int32_t texture_index(int64_t index) {
  return static_cast<int32_t>(std::clamp<int64_t>(index, -1, INT32_MAX));
}

void check_keys(const py::dict& d, std::initializer_list<const char*> allowed,
                const std::string& what) {
  for (auto item : d) {
    const std::string key = py::str(item.first);
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; }))
      fail(what + ": unknown key '" + key + "'");
  }
}

bool is_number(const py::handle& h) {
  return py::isinstance<py::float_>(h) || py::isinstance<py::int_>(h);
}

// value = float | [r, g, b] | {"texture": int, "channel": "COLOR" | "ALPHA"}, read as given:
// sanitize_material clamps constants and drops texture indices with no texture afterwards.
Input parse_input(const py::handle& value, ParamKind kind, const Input& fallback,
                  const std::string& what) {
  if (is_number(value)) {
    // A number for a colour is a grey (Blender's float -> colour conversion).
    return Input::constant(value.cast<float>());
  }
  if (py::isinstance<py::dict>(value) &&
      py::reinterpret_borrow<py::dict>(value).contains("register")) {
    py::dict d = py::reinterpret_borrow<py::dict>(value);
    check_keys(d, {"register", "value"}, what);
    Input in = fallback;  // the constant stays for when the program cannot run
    if (d.contains("value")) {
      Input v = parse_input(d["value"], kind, fallback, what);
      in.value = v.value;
    }
    in.texture = -1;
    in.reg =
        static_cast<int32_t>(std::clamp<int64_t>(d["register"].cast<int64_t>(), -1, INT32_MAX));
    return in;
  }
  if (py::isinstance<py::dict>(value)) {
    py::dict d = py::reinterpret_borrow<py::dict>(value);
    check_keys(d, {"texture", "channel"}, what);
    if (!d.contains("texture") || !py::isinstance<py::int_>(d["texture"]))
      fail(what + ": a texture input needs an integer 'texture'");
    Input in = fallback;
    in.texture = texture_index(d["texture"].cast<int64_t>());
    if (in.texture < 0) return fallback;
    in.channel = TextureChannel::kColor;
    if (d.contains("channel")) {
      const std::string channel = py::str(d["channel"]);
      if (channel == "ALPHA")
        in.channel = TextureChannel::kAlpha;
      else if (channel != "COLOR")
        fail(what + ": unknown channel '" + channel + "'");
    }
    return in;
  }
  if (py::isinstance<py::sequence>(value) && !py::isinstance<py::str>(value)) {
    if (kind == ParamKind::kScalar) fail(what + " expects a number or a texture, not a colour");
    auto seq = py::reinterpret_borrow<py::sequence>(value);
    if (seq.size() != 3) fail(what + ": a colour needs 3 values");
    for (auto item : seq)
      if (!is_number(item)) fail(what + ": colour values must be numbers");
    return Input::constant(Vec3{seq[0].cast<float>(), seq[1].cast<float>(), seq[2].cast<float>()});
  }
  fail(what + ": expected a number, [r, g, b] or {'texture': index}");
}

Closure parse_closure(const py::handle& item, const std::string& what) {
  if (!py::isinstance<py::dict>(item)) fail(what + " must be a dict");
  py::dict d = py::reinterpret_borrow<py::dict>(item);
  check_keys(d,
             {"type", "sharp", "beckmann", "cycles4", "multiscatter", "diffuse_multiscatter",
              "abbe", "params", "normal_map", "normal", "clearcoat_normal", "weight"},
             what);
  if (!d.contains("type")) fail(what + " has no 'type'");
  const std::string type = py::str(d["type"]);
  const ClosureSpec* found = find_closure(type.c_str());
  if (!found) fail(what + ": unknown closure type '" + type + "'");
  Closure closure;
  closure.type = found->type;
  closure.params = default_params(closure.type);  // inputs the dict leaves out
  if (d.contains("sharp")) closure.sharp = d["sharp"].cast<bool>();
  if (d.contains("beckmann")) closure.beckmann = d["beckmann"].cast<bool>();
  // Blender 4+ nodes: Cycles 4's microfacet model, and its Multiscatter GGX energy scaling.
  closure.cycles4 = closure.type == ClosureType::kPrincipledV2 ||
                    (d.contains("cycles4") && d["cycles4"].cast<bool>());
  if (d.contains("multiscatter")) closure.multiscatter = d["multiscatter"].cast<bool>();
  if (!closure.cycles4) closure.multiscatter = false;
  // Cycles 4.3+'s energy-preserving Oren-Nayar (a Diffuse BSDF's; Principled v2 always).
  if (d.contains("diffuse_multiscatter"))
    closure.diffuse_multiscatter = d["diffuse_multiscatter"].cast<bool>();
  if (d.contains("abbe")) {
    // Non-finite or negative: no dispersion; others inside real materials' range (the add-on
    // warns when it clamps).
    closure.abbe = spectral::physical_abbe(d["abbe"].cast<float>());
  }

  if (d.contains("params")) {
    if (!py::isinstance<py::dict>(d["params"])) fail(what + ": 'params' must be a dict");
    for (auto p : py::reinterpret_borrow<py::dict>(d["params"])) {
      const std::string key = py::str(p.first);
      const ClosureParamSpec* info = find_param(key.c_str());
      if (!info) fail(what + ": unknown param '" + key + "'");
      closure[info->param] =
          parse_input(p.second, info->kind, closure[info->param], what + " param '" + key + "'");
    }
  }

  if (d.contains("normal_map") && !d["normal_map"].is_none()) {
    if (!py::isinstance<py::dict>(d["normal_map"])) fail(what + ": 'normal_map' must be a dict");
    py::dict n = d["normal_map"];
    check_keys(n, {"texture", "strength"}, what + " normal_map");
    if (!n.contains("texture") || !py::isinstance<py::int_>(n["texture"]))
      fail(what + ": normal_map needs an integer 'texture'");
    closure.normal.texture = texture_index(n["texture"].cast<int64_t>());
    if (n.contains("strength")) closure.normal.strength = n["strength"].cast<float>();
  }

  if (d.contains("normal") && !d["normal"].is_none()) {
    py::dict n = d["normal"];
    check_keys(n, {"register"}, what + " normal");
    closure.normal_reg =
        static_cast<int32_t>(std::clamp<int64_t>(n["register"].cast<int64_t>(), -1, INT32_MAX));
  }

  if (d.contains("clearcoat_normal") && !d["clearcoat_normal"].is_none()) {
    py::dict n = d["clearcoat_normal"];
    check_keys(n, {"register"}, what + " clearcoat_normal");
    closure.clearcoat_normal_reg =
        static_cast<int32_t>(std::clamp<int64_t>(n["register"].cast<int64_t>(), -1, INT32_MAX));
  }

  if (d.contains("weight")) {
    if (!py::isinstance<py::list>(d["weight"])) fail(what + ": 'weight' must be a list");
    for (auto w : py::reinterpret_borrow<py::list>(d["weight"])) {
      if (!py::isinstance<py::dict>(w)) fail(what + ": weight factors must be dicts");
      py::dict f = py::reinterpret_borrow<py::dict>(w);
      check_keys(f, {"fac", "complement"}, what + " weight");
      if (!f.contains("fac")) fail(what + ": a weight factor needs 'fac'");
      WeightFactor factor;
      factor.fac = parse_input(f["fac"], ParamKind::kScalar,
                               Input::constant(kMixFactor.default_value), what + " weight fac");
      if (f.contains("complement")) factor.complement = f["complement"].cast<bool>();
      closure.weight.push_back(factor);
    }
  }
  return closure;
}

py::object describe_input(const Input& in, ParamKind kind) {
  if (in.reg >= 0) {
    py::dict d;
    d["register"] = in.reg;
    return std::move(d);
  }
  if (in.texture >= 0) {
    py::dict d;
    d["texture"] = in.texture;
    d["channel"] = in.channel == TextureChannel::kAlpha ? "ALPHA" : "COLOR";
    return std::move(d);
  }
  if (kind == ParamKind::kScalar) return py::float_(in.value.x);
  py::list rgb;
  for (float c : {in.value.x, in.value.y, in.value.z}) rgb.append(c);
  return std::move(rgb);
}

}  // namespace

std::vector<MaterialAov> parse_aovs(const py::handle& aovs, const std::string& owner) {
  std::vector<MaterialAov> out;
  if (aovs.is_none()) return out;
  if (!py::isinstance<py::list>(aovs) && !py::isinstance<py::tuple>(aovs))
    fail(owner + ": aovs must be a list of dicts");
  for (auto item : py::reinterpret_borrow<py::sequence>(aovs)) {
    const std::string what = owner + " AOV output";
    if (!py::isinstance<py::dict>(item)) fail(what + " must be a dict");
    py::dict d = py::reinterpret_borrow<py::dict>(item);
    check_keys(d, {"name", "type", "value"}, what);
    if (!d.contains("name") || !d.contains("type") || !d.contains("value"))
      fail(what + " needs 'name', 'type' and 'value'");
    MaterialAov aov;
    aov.name = py::str(d["name"]);
    const std::string type = py::str(d["type"]);
    if (type != "COLOR" && type != "VALUE") fail(what + ": type must be COLOR or VALUE");
    aov.color = type == "COLOR";
    aov.value = parse_input(d["value"], aov.color ? ParamKind::kColor : ParamKind::kScalar,
                            Input::constant(0.0f), what + " '" + aov.name + "'");
    out.push_back(std::move(aov));
  }
  return out;
}

Material parse_material(const std::string& name, const py::handle& closures, int64_t texture_count,
                        const py::handle& program, std::string* warning, const py::handle& aovs) {
  if (!py::isinstance<py::list>(closures) && !py::isinstance<py::tuple>(closures))
    fail("closures must be a list of dicts");
  Material material;
  material.name = name;
  size_t i = 0;
  for (auto item : py::reinterpret_borrow<py::sequence>(closures))
    material.closures.push_back(
        parse_closure(item, "material '" + name + "' closure " + std::to_string(i++)));
  if (!program.is_none()) material.program = parse_program(program);
  material.aovs = parse_aovs(aovs, "material '" + name + "'");
  sanitize_material(&material, texture_count < 0 ? SIZE_MAX : static_cast<size_t>(texture_count),
                    warning);
  return material;
}

ImageTexture parse_texture(const std::string& path, bool srgb, const std::string& extension,
                           const std::string& interpolation) {
  ImageTexture t;
  t.path = path;
  t.srgb = srgb;
  if (extension == "REPEAT")
    t.extension = TextureExtension::kRepeat;
  else if (extension == "EXTEND")
    t.extension = TextureExtension::kExtend;
  else if (extension == "CLIP")
    t.extension = TextureExtension::kClip;
  else
    fail("unknown texture extension '" + extension + "'");
  if (interpolation == "Closest")
    t.interpolation = TextureInterpolation::kClosest;
  else if (interpolation == "Linear")
    t.interpolation = TextureInterpolation::kLinear;
  else if (interpolation == "Cubic")
    t.interpolation = TextureInterpolation::kCubic;
  else
    fail("unknown texture interpolation '" + interpolation + "'");
  return t;
}

void parse_texture_alpha(ImageTexture* t, const std::string& alpha, bool unassociate) {
  if (alpha == "KEEP")
    t->alpha = TextureAlpha::kKeep;
  else if (alpha == "ASSOCIATE")
    t->alpha = TextureAlpha::kAssociate;
  else if (alpha == "IGNORE")
    t->alpha = TextureAlpha::kIgnore;
  else
    fail("unknown texture alpha handling '" + alpha + "'");
  t->unassociate = unassociate;
}

py::dict describe_material(const Material& material) {
  py::list closures;
  for (const Closure& c : material.closures) {
    py::dict d;
    d["type"] = closure_spec(c.type).name;
    d["sharp"] = c.sharp;
    if (c.beckmann) d["beckmann"] = true;
    if (c.cycles4) {
      d["cycles4"] = true;
      d["multiscatter"] = c.multiscatter;
    }
    if (c.diffuse_multiscatter) d["diffuse_multiscatter"] = true;
    d["abbe"] = c.abbe;
    py::dict params;
    for (const ClosureParamSpec& info : closure_spec(ClosureType::kPrincipled).params)
      params[info.key] = describe_input(c[info.param], info.kind);
    if (c.type == ClosureType::kPrincipledV2)
      for (const ClosureParamSpec& info : closure_spec(ClosureType::kPrincipledV2).params)
        params[info.key] = describe_input(c[info.param], info.kind);
    d["params"] = params;
    if (c.normal.texture >= 0) {
      py::dict n;
      n["texture"] = c.normal.texture;
      n["strength"] = c.normal.strength;
      d["normal_map"] = n;
    }
    py::list weight;
    for (const WeightFactor& f : c.weight) {
      py::dict w;
      w["fac"] = describe_input(f.fac, ParamKind::kScalar);
      w["complement"] = f.complement;
      weight.append(w);
    }
    d["weight"] = weight;
    closures.append(d);
  }
  py::dict out;
  out["name"] = material.name;
  out["closures"] = closures;
  py::list aovs;
  for (const MaterialAov& aov : material.aovs) {
    py::dict d;
    d["name"] = aov.name;
    d["type"] = aov.color ? "COLOR" : "VALUE";
    d["value"] = describe_input(aov.value, aov.color ? ParamKind::kColor : ParamKind::kScalar);
    aovs.append(d);
  }
  out["aovs"] = aovs;
  return out;
}

namespace {

py::dict scalar_spec(float default_value, ParamRange range) {
  py::dict d;
  d["default"] = default_value;
  d["min"] = range.lo;
  d["max"] = range.hi;
  return d;
}

// The table of material_params.h as plain Python data (the add-on converts node trees with it).
py::list material_parameters() {
  py::list closures;
  for (const ClosureSpec& c : closure_specs()) {
    py::list params;
    for (const ClosureParamSpec& p : c.params) {
      const bool is_color = p.kind == ParamKind::kColor;
      py::dict d = scalar_spec(p.default_value, p.range);
      if (is_color)
        d["default"] = py::make_tuple(p.default_value, p.default_value, p.default_value);
      d["key"] = p.key;
      py::list sockets;
      for (const char* socket : p.sockets)
        if (socket) sockets.append(socket);
      d["sockets"] = py::tuple(sockets);
      d["kind"] = is_color ? "color" : "scalar";
      params.append(d);
    }
    py::dict d;
    d["closure"] = c.name;
    d["node"] = c.node;
    d["params"] = params;
    closures.append(d);
  }
  return closures;
}

}  // namespace

void register_material_functions(py::module_& m) {
  m.def("material_parameters", &material_parameters,
        "Every closure type as {'closure', 'node' (bpy node type), 'params'}: each param "
        "{'key', 'sockets' (Blender input names), 'kind' ('color' | 'scalar'), 'default', "
        "'min', 'max'}, the ranges constants and texture values are clamped to.");
  m.attr("NORMAL_MAP_STRENGTH") =
      scalar_spec(kNormalMapStrength.default_value, kNormalMapStrength.range);
  m.attr("MIX_FACTOR") = scalar_spec(kMixFactor.default_value, kMixFactor.range);
  py::class_<TexturePixels, std::shared_ptr<TexturePixels>>(
      m, "TexturePixels",
      "Float RGBA pixels of an image that exists only in memory (a generated image), bottom "
      "row first as Blender stores them; fill `array` in place (image.pixels.foreach_get) and "
      "pass it to Scene.add_texture_pixels. Released once converted.")
      .def(py::init([](int width, int height, bool is_float) {
             if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
               throw py::value_error("texture size must be within 1..65536");
             return std::make_shared<TexturePixels>(width, height, is_float);
           }),
           py::arg("width"), py::arg("height"), py::arg("is_float") = true)
      .def_property_readonly("width", &TexturePixels::width)
      .def_property_readonly("height", &TexturePixels::height)
      .def_property_readonly("array", [](const TexturePixels& p) {
        // A view of the native memory (no copy); the capsule keeps it alive as long as the
        // array lives, even after the texture released its own reference.
        std::shared_ptr<float[]> data = p.storage();
        if (!data) throw py::value_error("the pixels were released after conversion");
        auto* keep = new std::shared_ptr<float[]>(data);
        py::capsule owner(keep,
                          [](void* ptr) { delete static_cast<std::shared_ptr<float[]>*>(ptr); });
        const py::ssize_t n = static_cast<py::ssize_t>(p.width()) * p.height() * 4;
        return py::array_t<float>({n}, {static_cast<py::ssize_t>(sizeof(float))}, data.get(),
                                  owner);
      });
  m.def(
      "describe_material",
      [](const std::string& name, const py::list& closures, int64_t texture_count,
         const py::object& aovs) {
        return describe_material(
            parse_material(name, closures, texture_count, py::none(), nullptr, aovs));
      },
      py::arg("name"), py::arg("closures"), py::arg("texture_count") = -1,
      py::arg("aovs") = py::none(),
      "Parses closure dicts as Scene.add_material does and returns the Material as dicts "
      "(every param listed, clamped values and fallbacks applied).");
  m.def(
      "write_texture",
      [](const std::string& path,
         const py::array_t<float, py::array::c_style | py::array::forcecast>& rgba) {
        if (rgba.ndim() != 3 || rgba.shape(2) != 4)
          throw py::value_error("rgba must have shape (height, width, 4)");
        const int height = static_cast<int>(rgba.shape(0));
        const int width = static_cast<int>(rgba.shape(1));
        std::vector<float> pixels(rgba.data(), rgba.data() + rgba.size());
        std::string error;
        bool ok;
        {
          py::gil_scoped_release release;
          ok = write_rgba_image(path, pixels, width, height, &error);
        }
        if (!ok) throw std::runtime_error("cannot write " + path + ": " + error);
      },
      py::arg("path"), py::arg("rgba"),
      "Writes float RGBA pixels (top row first) to an image file (EXR keeps the values).");
}

}  // namespace photon_python
