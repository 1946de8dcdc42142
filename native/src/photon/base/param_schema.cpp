#include "photon/base/param_schema.h"

#include <algorithm>
#include <cstdio>

namespace photon {
namespace {

std::string format_value(const ParamSpec& spec, double v) {
  char buf[64];
  if (spec.type == ParamType::kFloat)
    std::snprintf(buf, sizeof buf, "%g", v);
  else
    std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

}  // namespace

const char* param_type_name(ParamType type) {
  switch (type) {
    case ParamType::kInt:
      return "int";
    case ParamType::kFloat:
      return "float";
    case ParamType::kBool:
      return "bool";
    case ParamType::kEnum:
      return "enum";
    case ParamType::kUInt64:
      return "uint64";
  }
  return "int";
}

bool clamp_param_value(const ParamSpec& spec, double* v, std::string* why) {
  const std::string name = spec.name + " = ";
  if (spec.type == ParamType::kBool) return true;
  if (spec.type == ParamType::kEnum) {
    for (const ParamEnumItem& item : spec.items)
      if (item.value == *v) return true;
    *why = name + format_value(spec, *v) + " names no " + spec.label + ": using " +
           format_value(spec, spec.default_value);
    *v = spec.default_value;
    return false;
  }
  if (std::isnan(*v)) {
    *why = name + "NaN: using the default " + format_value(spec, spec.default_value);
    *v = spec.default_value;
    return false;
  }
  double lo = spec.min, hi = spec.max;
  if (spec.type == ParamType::kFloat) {
    // Compare in the field's precision: 1e-4f read back as a double is below 1e-4.
    lo = static_cast<float>(lo);
    hi = static_cast<float>(hi);
  }
  if (*v >= lo && *v <= hi) return true;
  const double clamped = std::clamp(*v, lo, hi);
  *why = name + format_value(spec, *v) + " is outside [" + format_value(spec, lo) + ", " +
         format_value(spec, hi) + "]: clamped to " + format_value(spec, clamped);
  *v = clamped;
  return false;
}

}  // namespace photon
