// photon_cli: renders a built-in scene without Blender, e.g.
//   photon_cli --scene cornell --width 256 --height 256 --samples 64 --out cornell.exr
// Every render parameter is an option generated from its schema (render_params.h): --help
// lists them, --print-schema writes the schema as JSON (staged with the add-on).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include "photon/integrators/photon_map/photon_memory.h"
#include "photon/integrators/render_params.h"
#include "photon/session/image_io.h"
#include "photon/session/render_session.h"
#include "photon/testing/sds_scenes.h"
#include "photon/testing/test_scenes.h"

using namespace photon;

namespace {

// "--gather-count" for the parameter gather_count.
std::string option_name(const std::string& name) {
  std::string o = "--" + name;
  std::replace(o.begin(), o.end(), '_', '-');
  return o;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Older spellings of generated options.
const std::map<std::string, std::string> kAliases = {
    {"--patch-size", "radiosity_patch_size"},
};

void usage(FILE* out) {
  std::fprintf(out,
               "usage: photon_cli [--scene cornell|caustic|glass_light|mirror_caustic|pool]\n"
               "                  [--width N] [--height N]\n"
               "                  [--passes PREFIX (writes PREFIX_direct.exr, ...)]\n"
               "                  [--print-schema | --write-schema FILE (the parameter schema\n"
               "                   as JSON, on stdout or into FILE)]\n"
               "                  [parameter options] --out FILE\n"
               "parameter options (out-of-range values are clamped with a warning):\n");
  for (const RenderParamGroup& group : render_param_groups()) {
    std::fprintf(out, "  %s:\n", group.label.c_str());
    for (const RenderParam& p : group.params) {
      const ParamSpec& spec = *p.spec;
      std::string arg = " N";
      if (spec.type == ParamType::kFloat) arg = " X";
      if (spec.type == ParamType::kBool) arg = " 0|1";
      if (spec.type == ParamType::kEnum) {
        arg = " ";
        for (size_t i = 0; i < spec.items.size(); ++i)
          arg += (i ? "|" : "") + lower(spec.items[i].id);
      }
      char range[128];
      std::snprintf(range, sizeof range, "default %.10g, range [%.10g, %.10g]", spec.default_value,
                    spec.min, spec.max);
      std::string detail = range;
      if (spec.type == ParamType::kBool)
        detail = std::string("default ") + (spec.default_value != 0.0 ? "1" : "0") + "; --no-" +
                 option_name(spec.name).substr(2) + " sets 0";
      if (spec.type == ParamType::kEnum)
        for (const ParamEnumItem& item : spec.items)
          if (item.value == spec.default_value) detail = "default " + lower(item.id);
      std::fprintf(out, "    %s%s\n        %s: %s (%s)\n", option_name(spec.name).c_str(),
                   arg.c_str(), spec.label.c_str(), spec.description.c_str(), detail.c_str());
    }
  }
}

// Sets parameter `p` from the command-line text `text`; false when it does not parse.
bool set_param(RenderSettings* settings, const RenderParam& p, const std::string& text) {
  const ParamSpec& spec = *p.spec;
  if (spec.type == ParamType::kEnum) {
    for (const ParamEnumItem& item : spec.items)
      if (lower(item.id) == lower(text)) {
        p.set(*settings, item.value);
        return true;
      }
    return false;
  }
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') return false;
  p.set(*settings, v);
  return true;
}

// A whole number of pixels from 1 to kMaxSide in `text`, strictly (no sign, no fraction, no
// trailing characters): atoi read "1e9" as 1 and "-5" as -5.
constexpr int kMaxSide = 65536;
bool parse_side(const char* text, int* out) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || errno != 0 || v < 1 || v > kMaxSide) return false;
  *out = static_cast<int>(v);
  return true;
}

// Peak bytes a render of `s` holds for its pixels: the film's sums, the session's image, the
// tiles handed over and kept here to write the passes (16 bytes of RGBA each, plus the light
// passes' 12 bytes per pass).
double frame_bytes(const RenderSettings& s) {
  const double pixels = static_cast<double>(s.full_width) * s.full_height;
  const double per_pixel = 16.0 * 3 + (s.light_passes ? kPassFloats * 4.0 * 3 : 0.0);
  return pixels * per_pixel;
}

int render(int argc, char** argv);

}  // namespace

int main(int argc, char** argv) {
  // Nothing escapes as an abort: a failure is a message and a non-zero exit.
  try {
    return render(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
  return 1;
}

namespace {

int render(int argc, char** argv) {
  RenderSettings settings;
  settings.full_width = settings.full_height = 256;
  std::string scene_name = "cornell", out, passes_prefix;
  for (int i = 1; i < argc; ++i) {
    auto next = [&](const char* flag) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", flag);
        std::exit(2);
      }
      return argv[++i];
    };
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      usage(stdout);
      return 0;
    } else if (arg == "--print-schema") {
      std::fputs(render_param_schema_json().c_str(), stdout);
      return 0;
    } else if (arg == "--write-schema") {
      const char* path = next("--write-schema");
      FILE* f = std::fopen(path, "w");
      if (!f || std::fputs(render_param_schema_json().c_str(), f) < 0 || std::fclose(f) != 0) {
        std::fprintf(stderr, "cannot write %s\n", path);
        return 1;
      }
      return 0;
    } else if (arg == "--scene") {
      scene_name = next("--scene");
    } else if (arg == "--width" || arg == "--height") {
      const char* text = next(arg.c_str());
      if (!parse_side(text, arg == "--width" ? &settings.full_width : &settings.full_height)) {
        std::fprintf(stderr, "%s: '%s' is not a whole number of pixels from 1 to %d\n", arg.c_str(),
                     text, kMaxSide);
        return 2;
      }
    } else if (arg == "--passes") {
      passes_prefix = next("--passes");
      settings.light_passes = true;
    } else if (arg == "--out") {
      out = next("--out");
    } else {
      // A parameter from the schema: --name value, or --no-name for a boolean.
      const RenderParam* param = nullptr;
      bool negated = false;
      for (const RenderParamGroup& group : render_param_groups())
        for (const RenderParam& p : group.params) {
          if (option_name(p.spec->name) == arg) param = &p;
          if (p.spec->type == ParamType::kBool &&
              "--no-" + option_name(p.spec->name).substr(2) == arg) {
            param = &p;
            negated = true;
          }
        }
      if (!param && kAliases.count(arg)) param = find_render_param(kAliases.at(arg));
      if (!param) {
        std::fprintf(stderr, "unknown option %s\n", arg.c_str());
        usage(stderr);
        return 2;
      }
      if (negated) {
        param->set(settings, 0.0);
      } else if (!set_param(&settings, *param, next(arg.c_str()))) {
        std::fprintf(stderr, "%s: cannot read '%s'\n", arg.c_str(), argv[i]);
        usage(stderr);
        return 2;
      }
    }
  }
  // The built-in scenes: the Cornell and caustic boxes and the SDS scenes (sds_scenes.h).
  auto scene = std::make_shared<Scene>();
  bool known = true;
  if (scene_name == "cornell")
    *scene = make_cornell_box();
  else if (scene_name == "caustic")
    *scene = make_caustic_box();
  else
    known = make_sds_scene(scene_name, scene.get());
  if (out.empty() || !known) {
    usage(stderr);
    return 2;
  }
  settings.x1 = settings.full_width;
  settings.y1 = settings.full_height;
  const double needed = frame_bytes(settings), available = available_memory_bytes();
  if (available > 0.0 && needed > available) {
    std::fprintf(stderr,
                 "error: a %dx%d image needs about %s of memory, more than the %s available\n",
                 settings.full_width, settings.full_height, bytes_text(needed).c_str(),
                 bytes_text(available).c_str());
    return 1;
  }
  // Clamped settings are said before the render, not after it.
  std::vector<std::string> early;
  sanitized_settings(settings, &early);
  for (const std::string& w : early) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const float aspect = static_cast<float>(settings.full_width) / settings.full_height;
  scene->camera.window_min_x = scene->camera.window_min_y * aspect;
  scene->camera.window_max_x = scene->camera.window_max_y * aspect;

  RenderSession session(scene, settings);
  session.start();
  std::vector<Tile> tiles;
  while (!session.finished()) {
    std::vector<Tile> batch = session.take_tiles(0.1);
    for (Tile& t : batch) tiles.push_back(std::move(t));
  }
  for (Tile& t : session.take_tiles(0.0)) tiles.push_back(std::move(t));
  session.wait();
  for (const std::string& w : session.warnings())
    if (std::find(early.begin(), early.end(), w) == early.end())
      std::fprintf(stderr, "warning: %s\n", w.c_str());
  const RenderStats stats = session.stats();
  std::printf("rendered %dx%d, %d spp, %d threads: build %.3f s, prepare %.3f s, render %.3f s\n",
              settings.full_width, settings.full_height, settings.samples, stats.threads,
              stats.build_seconds, stats.prepare_seconds, stats.render_seconds);
  const PrepareStats& prepared = stats.integrator;
  using ull = unsigned long long;
  if (const auto& pm = prepared.photon_map)
    std::printf(
        "  photons: %llu global and %llu caustic emitted, %llu and %llu stored in %.3f s; "
        "gather radius %g (caustic %g)\n",
        ull(pm->photons_emitted), ull(pm->caustic_photons_emitted), ull(pm->global_photons_stored),
        ull(pm->caustic_photons_stored), pm->photon_trace_seconds, pm->global_gather_radius,
        pm->caustic_gather_radius);
  if (const auto& cache = prepared.irradiance_cache)
    std::printf("  irradiance cache: %llu records, %llu gather rays in %.3f s\n",
                ull(cache->records), ull(cache->gather_rays), cache->seconds);
  if (const auto& r = prepared.radiosity)
    std::printf("  radiosity: %llu patches, %llu elements, %llu rays in %.3f s\n", ull(r->patches),
                ull(r->elements), ull(r->rays), r->solve_seconds);
  std::string error;
  if (!write_rgba_image(out, session.image(), session.region_width(), session.region_height(),
                        &error)) {
    std::fprintf(stderr, "cannot write %s: %s\n", out.c_str(), error.c_str());
    return 1;
  }
  std::printf("wrote %s\n", out.c_str());
  if (!passes_prefix.empty()) {
    // Reassemble each light pass from the tiles and write it as an RGBA image.
    const int w = session.region_width(), h = session.region_height();
    const char* names[kPassCount] = {"direct", "indirect", "caustics", "photon_map"};
    std::vector<std::vector<float>> images(kPassCount, std::vector<float>(size_t(w) * h * 4, 1.0f));
    for (const Tile& t : tiles)
      for (int k = 0; k < kPassCount; ++k) {
        const PassImage* pass = t.pass(light_pass_names()[k]);
        if (!pass) continue;
        for (int row = 0; row < t.height; ++row)
          for (int col = 0; col < t.width; ++col)
            for (int c = 0; c < 3; ++c)
              images[k][(size_t(t.y + row) * w + t.x + col) * 4 + c] =
                  pass->pixels[(size_t(row) * t.width + col) * 3 + c];
      }
    for (int k = 0; k < kPassCount; ++k) {
      const std::string path = passes_prefix + "_" + names[k] + ".exr";
      if (!write_rgba_image(path, images[k], w, h, &error)) {
        std::fprintf(stderr, "cannot write %s: %s\n", path.c_str(), error.c_str());
        return 1;
      }
      std::printf("wrote %s\n", path.c_str());
    }
  }
  return 0;
}

}  // namespace
