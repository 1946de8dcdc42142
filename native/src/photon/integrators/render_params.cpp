#include "photon/integrators/render_params.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace photon {
namespace {

template <class S>
RenderParamGroup make_group(const ParamSchema<S>& schema) {
  RenderParamGroup group{schema.group, schema.label, schema.integrator, {}};
  for (const ParamEntry<S>& p : schema.params) {
    // RenderSettings derives from S: each field is reached through its base.
    group.params.push_back(
        {&p.spec, [get = p.get](const RenderSettings& r) { return get(static_cast<const S&>(r)); },
         [set = p.set](RenderSettings& r, double v) { set(static_cast<S&>(r), v); }});
  }
  return group;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// Integers print exactly (up to 2^53), other numbers with round-trip precision.
std::string json_number(double v) {
  char buf[40];
  if (v == static_cast<double>(static_cast<long long>(v)) && std::abs(v) <= 9007199254740992.0)
    std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(v));
  else
    std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string json_value(const ParamSpec& spec, double v) {
  if (spec.type == ParamType::kBool) return v != 0.0 ? "true" : "false";
  if (spec.type == ParamType::kFloat) {
    // Floats as the float the field holds, printed shortest (0.01, not 0.0099999997764825821).
    const float f = static_cast<float>(v);
    char buf[40];
    for (int digits = 6; digits <= 9; ++digits) {
      std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(f));
      if (std::strtof(buf, nullptr) == f) break;
    }
    std::string s = buf;
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
  }
  return json_number(v);
}

std::string spec_json(const ParamSpec& s) {
  std::string j = "{\"name\": " + json_string(s.name);
  j += ", \"type\": " + json_string(param_type_name(s.type));
  j += ", \"label\": " + json_string(s.label);
  j += ", \"description\": " + json_string(s.description);
  if (s.type == ParamType::kEnum) {
    for (const ParamEnumItem& item : s.items)
      if (item.value == s.default_value) j += ", \"default\": " + json_string(item.id);
  } else {
    j += ", \"default\": " + json_value(s, s.default_value);
  }
  j += ", \"min\": " + json_value(s, s.min) + ", \"max\": " + json_value(s, s.max);
  if (!std::isnan(s.soft_min)) j += ", \"soft_min\": " + json_value(s, s.soft_min);
  if (!std::isnan(s.soft_max)) j += ", \"soft_max\": " + json_value(s, s.soft_max);
  j += ", \"subtype\": " + json_string(s.subtype) + ", \"unit\": " + json_string(s.unit);
  j += ", \"ui_scale\": " + json_number(s.ui_scale);
  j += ", \"precision\": " + json_number(s.precision);
  j += ", \"items\": [";
  for (size_t i = 0; i < s.items.size(); ++i) {
    const ParamEnumItem& item = s.items[i];
    j += std::string(i ? ", " : "") + "{\"id\": " + json_string(item.id) +
         ", \"label\": " + json_string(item.label) +
         ", \"description\": " + json_string(item.description) +
         ", \"value\": " + json_number(item.value) + "}";
  }
  j += "], \"ui\": {\"column\": " + json_number(s.ui.column) +
       ", \"text\": " + json_string(s.ui.text) + ", \"active_if\": " + json_string(s.ui.active_if) +
       "}}";
  return j;
}

}  // namespace

const std::vector<RenderParamGroup>& render_param_groups() {
  static const std::vector<RenderParamGroup> groups{
      make_group(sampling_schema()),   make_group(film_schema()),
      make_group(photon_map_schema()), make_group(radiosity_schema()),
      make_group(sppm_schema()),       make_group(vcm_schema()),
      make_group(spectral_schema()),   make_group(performance_schema())};
  return groups;
}

const RenderParam* find_render_param(const std::string& name) {
  for (const RenderParamGroup& group : render_param_groups())
    for (const RenderParam& p : group.params)
      if (p.spec->name == name) return &p;
  return nullptr;
}

void clamp_render_params(RenderSettings* settings, std::vector<std::string>* warnings) {
  clamp_params<SamplingParams>(*settings, sampling_schema(), warnings);
  clamp_params<FilmParams>(*settings, film_schema(), warnings);
  clamp_params<PerformanceParams>(*settings, performance_schema(), warnings);
  clamp_params<PhotonMapParams>(*settings, photon_map_schema(), warnings);
  clamp_params<RadiosityParams>(*settings, radiosity_schema(), warnings);
  clamp_params<SppmParams>(*settings, sppm_schema(), warnings);
  clamp_params<VcmParams>(*settings, vcm_schema(), warnings);
  clamp_params<SpectralParams>(*settings, spectral_schema(), warnings);
}

std::string render_param_schema_json() {
  std::string j = "[";
  const std::vector<RenderParamGroup>& groups = render_param_groups();
  for (size_t g = 0; g < groups.size(); ++g) {
    const RenderParamGroup& group = groups[g];
    j += std::string(g ? ",\n " : "") + "{\"name\": " + json_string(group.name) +
         ", \"label\": " + json_string(group.label) +
         ", \"integrator\": " + json_string(group.integrator) + ", \"params\": [";
    for (size_t i = 0; i < group.params.size(); ++i)
      j += std::string(i ? ",\n  " : "\n  ") + spec_json(*group.params[i].spec);
    j += "]}";
  }
  return j + "]\n";
}

}  // namespace photon
