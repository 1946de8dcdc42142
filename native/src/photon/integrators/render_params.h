// Every render parameter of RenderSettings, by group, from the schemas the algorithms declare
// (sampling_params.h, photon_map_params.h, radiosity_params.h): the one list that clamps them,
// that Python, the command line and the add-on's JSON are generated from.
#pragma once

#include <string>
#include <vector>

#include "photon/integrators/integrator.h"

namespace photon {

struct RenderParam {
  const ParamSpec* spec = nullptr;
  std::function<double(const RenderSettings&)> get;
  std::function<void(RenderSettings&, double)> set;
};

struct RenderParamGroup {
  std::string name, label, integrator;  // as in ParamSchema
  std::vector<RenderParam> params;
};

const std::vector<RenderParamGroup>& render_param_groups();

// The parameter called `name` (the field's name), or null.
const RenderParam* find_render_param(const std::string& name);

// Clamps every schema'd parameter into its hard range, one warning per changed value.
void clamp_render_params(RenderSettings* settings, std::vector<std::string>* warnings);

// The schema as JSON: a list of groups {name, label, integrator, params: [{name, type, label,
// description, default, min, max, soft_min?, soft_max?, subtype, unit, ui_scale, precision,
// items: [{id, label, description, value}], ui: {column, text, active_if}}]}.
std::string render_param_schema_json();

}  // namespace photon
