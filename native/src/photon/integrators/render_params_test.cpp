// The parameter schemas: every field of every parameter struct has exactly one entry, and the
// one clamp function enforces each entry's hard range with a warning.
#include "photon/integrators/render_params.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "photon/session/render_session.h"

namespace photon {
namespace render_params_test {
namespace {

template <class S>
void expect_covers_every_field(const ParamSchema<S>& schema) {
  SCOPED_TRACE(schema.group);
  EXPECT_EQ(schema.params.size(), aggregate_field_count<S>());
  // Each entry reaches its own field: changing one leaves every other entry's value alone.
  for (size_t i = 0; i < schema.params.size(); ++i) {
    S s{};
    const ParamSpec& spec = schema.params[i].spec;
    const double changed = spec.default_value != spec.max ? spec.max : spec.min;
    schema.params[i].set(s, changed);
    // A float field holds the value rounded to float.
    const double stored =
        spec.type == ParamType::kFloat ? static_cast<double>(static_cast<float>(changed)) : changed;
    EXPECT_EQ(schema.params[i].get(s), stored) << spec.name;
    for (size_t j = 0; j < schema.params.size(); ++j)
      if (j != i)
        EXPECT_EQ(schema.params[j].get(s), schema.params[j].spec.default_value)
            << spec.name << " also changed " << schema.params[j].spec.name;
  }
}

TEST(RenderParams, SchemasCoverEveryField) {
  expect_covers_every_field(sampling_schema());
  expect_covers_every_field(film_schema());
  expect_covers_every_field(performance_schema());
  expect_covers_every_field(photon_map_schema());
  expect_covers_every_field(radiosity_schema());
  expect_covers_every_field(spectral_schema());
  expect_covers_every_field(sppm_schema());
  expect_covers_every_field(vcm_schema());
}

TEST(RenderParams, NamesAreUniqueAndDefaultsInRange) {
  std::set<std::string> names;
  for (const RenderParamGroup& group : render_param_groups())
    for (const RenderParam& p : group.params) {
      const ParamSpec& spec = *p.spec;
      EXPECT_TRUE(names.insert(spec.name).second) << spec.name;
      EXPECT_FALSE(spec.label.empty()) << spec.name;
      EXPECT_FALSE(spec.description.empty()) << spec.name;
      EXPECT_LE(spec.min, spec.default_value) << spec.name;
      EXPECT_GE(spec.max, spec.default_value) << spec.name;
      if (!std::isnan(spec.soft_min)) EXPECT_GE(spec.soft_min, spec.min) << spec.name;
      if (!std::isnan(spec.soft_max)) EXPECT_LE(spec.soft_max, spec.max) << spec.name;
      EXPECT_EQ(find_render_param(spec.name), &p);
    }
  // RenderSettings holds the parameters plus the frame (size, border, film, passes) only.
  EXPECT_EQ(names.size(), 40u);
}

// Every numeric entry: a value just beyond each end of its hard range comes back at that end
// with one warning naming the parameter; values inside stay untouched, without a warning.
TEST(RenderParams, ClampEnforcesEveryRangeWithAWarning) {
  for (const RenderParamGroup& group : render_param_groups())
    for (const RenderParam& p : group.params) {
      const ParamSpec& spec = *p.spec;
      if (spec.type == ParamType::kBool || spec.type == ParamType::kEnum) continue;
      SCOPED_TRACE(spec.name);
      // Far enough out to be representable past the bound (2^53 + 1 is not a double).
      const double step = spec.type == ParamType::kFloat ? std::max(1.0, std::abs(spec.max))
                                                         : std::max(1.0, spec.max * 1e-3);
      struct Case {
        double in, out;
      };
      std::vector<Case> cases = {{spec.max + step, spec.max}};
      if (spec.min > 0.0 || spec.type == ParamType::kFloat || spec.type == ParamType::kInt)
        cases.push_back({spec.min - std::max(step, spec.min), spec.min});
      for (const Case& c : cases) {
        RenderSettings s;
        p.set(s, c.in);
        std::vector<std::string> warnings;
        clamp_render_params(&s, &warnings);
        const double got = p.get(s);
        if (spec.type == ParamType::kFloat)
          EXPECT_FLOAT_EQ(static_cast<float>(got), static_cast<float>(c.out)) << "from " << c.in;
        else
          EXPECT_EQ(got, c.out) << "from " << c.in;
        ASSERT_EQ(warnings.size(), 1u) << "from " << c.in;
        EXPECT_NE(warnings[0].find(spec.name), std::string::npos) << warnings[0];
      }
      RenderSettings s;
      p.set(s, spec.min);
      std::vector<std::string> warnings;
      clamp_render_params(&s, &warnings);
      EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings[0]);
    }
}

TEST(RenderParams, NaNAndUnknownEnumBecomeTheDefault) {
  RenderSettings s;
  s.radiosity_threshold = std::numeric_limits<float>::quiet_NaN();
  s.gather_radius = std::numeric_limits<float>::quiet_NaN();
  s.integrator = static_cast<IntegratorType>(7);
  std::vector<std::string> warnings;
  clamp_render_params(&s, &warnings);
  EXPECT_EQ(s.radiosity_threshold, RadiosityParams{}.radiosity_threshold);
  EXPECT_EQ(s.gather_radius, 0.0f);
  EXPECT_EQ(s.integrator, IntegratorType::kPhotonMap);
  EXPECT_EQ(warnings.size(), 3u);
}

// The session applies the schema: bounds that used to disagree between the add-on, the session
// and the radiosity solver now have one value.
TEST(RenderParams, SessionClampsWithTheSchemasBounds) {
  RenderSettings s;
  s.radiosity_iterations = 500;   // the solver alone allowed 1000
  s.radiosity_threshold = 1e-6f;  // the solver alone allowed 1e-6
  s.tile_size = 2;
  std::vector<std::string> warnings;
  const RenderSettings out = sanitized_settings(s, &warnings);
  EXPECT_EQ(out.radiosity_iterations, kMaxRadiosityIterations);
  EXPECT_FLOAT_EQ(out.radiosity_threshold, static_cast<float>(kMinRadiosityThreshold));
  EXPECT_EQ(out.tile_size, 4);
  EXPECT_EQ(warnings.size(), 3u);
}

TEST(RenderParams, JsonListsEveryParameter) {
  const std::string json = render_param_schema_json();
  for (const RenderParamGroup& group : render_param_groups())
    for (const RenderParam& p : group.params)
      EXPECT_NE(json.find("\"name\": \"" + p.spec->name + "\""), std::string::npos);
  EXPECT_NE(json.find("\"default\": 0.01,"), std::string::npos);  // floats printed shortest
  EXPECT_NE(json.find("\"default\": \"PHOTON_MAP\""), std::string::npos);
}

}  // namespace
}  // namespace render_params_test
}  // namespace photon
