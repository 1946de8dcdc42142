// A parameter schema: each algorithm declares its parameters once, as a table of entries
// (name, type, hard and soft range, UI label and description, unit) pointing at the fields of its
// parameter struct. One clamp function driven by the table validates input; the same table is
// exported to Python and JSON, where the Blender add-on generates its properties and panels from
// it, and to the command line, where it generates the options.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace photon {

enum class ParamType : uint8_t { kInt, kFloat, kBool, kEnum, kUInt64 };

const char* param_type_name(ParamType type);

struct ParamEnumItem {
  std::string id;  // as Blender's EnumProperty item identifier (e.g. "PHOTON_MAP")
  std::string label;
  std::string description;
  int value = 0;  // the native enum's value
};

// How the add-on lays the parameter out in its panel.
struct ParamUi {
  int column = 0;         // consecutive parameters with the same non-zero column are aligned
  std::string text;       // label in the panel when it differs from the property's name
  std::string active_if;  // drawn inactive unless this parameter is non-zero
};

struct ParamSpec {
  std::string
      name;  // the field, the Blender property (scene.photon.<name>) and --<name-with-dashes>
  ParamType type = ParamType::kInt;
  std::string label;
  std::string description;
  double default_value = 0.0;   // read from the default-constructed struct
  double min = 0.0, max = 0.0;  // hard range: clamp() enforces it
  double soft_min = std::numeric_limits<double>::quiet_NaN();  // UI slider range (NaN: none)
  double soft_max = std::numeric_limits<double>::quiet_NaN();
  std::string subtype;  // Blender property subtype ("DISTANCE", "FACTOR", ...), "" for none
  std::string unit;     // Blender unit ("LENGTH", "TIME"), "" for none
  // The Blender property holds value / ui_scale (radiosity rays are shown in thousands).
  double ui_scale = 1.0;
  int precision = -1;  // displayed decimals of a float (-1: Blender's default)
  std::vector<ParamEnumItem> items;
  ParamUi ui;
};

// One entry of a struct S's schema: the spec and typed access to its field.
template <class S>
struct ParamEntry {
  ParamSpec spec;
  std::function<double(const S&)> get;
  std::function<void(S&, double)> set;
};

template <class S>
struct ParamSchema {
  std::string group;       // "photon_map"
  std::string label;       // "Photon Mapping": the add-on's panel
  std::string integrator;  // enum item id of the integrator using it ("" = every integrator)
  std::vector<ParamEntry<S>> params;
};

template <class T>
constexpr ParamType param_type_of() {
  if constexpr (std::is_same_v<T, bool>)
    return ParamType::kBool;
  else if constexpr (std::is_enum_v<T>)
    return ParamType::kEnum;
  else if constexpr (std::is_same_v<T, uint64_t>)
    return ParamType::kUInt64;
  else if constexpr (std::is_floating_point_v<T>)
    return ParamType::kFloat;
  else
    return ParamType::kInt;
}

// An entry for field `member` of S; its default is the field's initializer in S.
template <class S, class T>
ParamEntry<S> param(T S::*member, ParamSpec spec) {
  spec.type = param_type_of<T>();
  ParamEntry<S> p;
  p.get = [member](const S& s) -> double {
    if constexpr (std::is_enum_v<T>)
      return static_cast<double>(static_cast<std::underlying_type_t<T>>(s.*member));
    else
      return static_cast<double>(s.*member);
  };
  p.set = [member](S& s, double v) {
    if constexpr (std::is_enum_v<T>)
      s.*member = static_cast<T>(static_cast<std::underlying_type_t<T>>(v));
    else if constexpr (std::is_same_v<T, bool>)
      s.*member = v != 0.0;
    else if constexpr (std::is_integral_v<T>)
      // Saturates instead of the undefined behaviour of casting NaN or out-of-range doubles.
      s.*member =
          std::isnan(v)                                             ? T{}
          : v <= static_cast<double>(std::numeric_limits<T>::min()) ? std::numeric_limits<T>::min()
          : v >= static_cast<double>(std::numeric_limits<T>::max()) ? std::numeric_limits<T>::max()
                                                                    : static_cast<T>(v);
    else
      s.*member = static_cast<T>(v);
  };
  spec.default_value = p.get(S{});
  p.spec = std::move(spec);
  return p;
}

// The value `v` of a parameter brought into its hard range: NaN and enum values that name no
// item become the default. Returns false (and the message in *why) when it had to change.
bool clamp_param_value(const ParamSpec& spec, double* v, std::string* why);

// Every parameter of `s` into its schema's range, one warning per changed value.
template <class S>
void clamp_params(S& s, const ParamSchema<S>& schema, std::vector<std::string>* warnings) {
  for (const ParamEntry<S>& p : schema.params) {
    double v = p.get(s);
    std::string why;
    if (clamp_param_value(p.spec, &v, &why)) continue;
    p.set(s, v);
    if (warnings) warnings->push_back(schema.label + ": " + why);
  }
}

// Number of fields of an aggregate struct (brace-initialisable from that many values): lets a
// test check that a schema covers every field.
namespace detail {
struct AnyField {
  template <class T>
  constexpr operator T() const noexcept;
};
template <class S, class, class... A>
struct BraceInitializable : std::false_type {};
template <class S, class... A>
struct BraceInitializable<S, std::void_t<decltype(S{std::declval<A>()...})>, A...>
    : std::true_type {};
template <class S, class... A>
constexpr size_t field_count() {
  if constexpr (sizeof...(A) > 64)
    return 64;
  else if constexpr (BraceInitializable<S, void, A..., AnyField>::value)
    return field_count<S, A..., AnyField>();
  else
    return sizeof...(A);
}
}  // namespace detail

template <class S>
constexpr size_t aggregate_field_count() {
  return detail::field_count<S>();
}

}  // namespace photon
