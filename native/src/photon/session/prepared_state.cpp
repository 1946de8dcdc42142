#include "photon/session/prepared_state.h"

#include <chrono>

#include "photon/integrators/prepared_state_file.h"
#include "photon/integrators/prepared_state_fingerprint.h"
#include "photon/integrators/registry.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

void prepare_with_state_files(const RenderContext& context, const TextureSet& textures,
                              IntegratorType type, Integrator* integrator,
                              const PrepareControl& control, const PreparedStateFiles& files,
                              PreparedStateStats* stats, std::vector<std::string>* warnings) {
  *stats = PreparedStateStats{};
  const bool wanted = !files.load.empty() || !files.save.empty();
  const IntegratorCapabilities caps = integrator_capabilities(type);
  uint64_t fingerprint = 0;
  bool shareable = wanted && caps.shares_preparation;
  if (wanted && !caps.shares_preparation) {
    warnings->push_back(std::string("prepared-state files are used by the PHOTON_MAP integrator "
                                    "only; this render's ") +
                        caps.name + " integrator prepares as usual and saves nothing");
  }
  std::string why_not;
  if (shareable && !prepared_state_fingerprint(*context.scene, *context.settings, textures,
                                               &fingerprint, &why_not)) {
    warnings->push_back("prepared state not used: " + why_not);
    shareable = false;
  }
  stats->fingerprint = fingerprint;

  bool loaded = false;
  if (shareable && !files.load.empty()) {
    control.report("Loading prepared state", 0.0f);
    const auto t0 = Clock::now();
    PreparedStateReader reader;
    std::string error;
    loaded = reader.open(files.load, type, fingerprint, &error) &&
             integrator->load_prepared(&reader, &error);
    if (loaded) {
      stats->loaded = true;
      stats->bytes = reader.payload_size();
      stats->load_seconds = seconds_since(t0);
    } else {
      warnings->push_back("prepared state refused (" + error + "): preparing this render itself");
    }
  }
  if (!loaded) integrator->prepare(context, control);
  if (control.cancelled() || !shareable || files.save.empty()) return;

  control.report("Saving prepared state", 1.0f);
  const auto t0 = Clock::now();
  PreparedStateWriter writer(files.save, type, fingerprint);
  integrator->save_prepared(&writer);
  std::string error;
  if (writer.finish(&error)) {
    stats->saved = true;
    stats->save_seconds = seconds_since(t0);
    stats->bytes = writer.payload_size();
  } else {
    warnings->push_back("prepared state not saved: " + error);
  }
}

}  // namespace photon
