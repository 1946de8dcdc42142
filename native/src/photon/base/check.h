// Checks of what must hold whatever the input (pbrt-v4's CHECK / DCHECK split): a failed check
// is a bug in Photon, never bad scene data, which is clamped or skipped with a warning instead.
//  - CHECK(cond) always runs: for cold paths (setup, once per tile or iteration) where a broken
//    invariant would go on to write out of bounds or render a silently wrong image.
//  - DCHECK(cond) runs only in builds without NDEBUG (the sanitizer build of the unit tests):
//    for hot paths (per sample, per pixel) where a branch would cost time.
// A failure throws CheckFailure naming the condition and its place. Inside Blender a throw, not
// an abort: the session's worker catches it (job.h) and the render ends as "Render failed"
// while Blender and the artist's unsaved work live on.
#pragma once

#include <stdexcept>
#include <string>

namespace photon {

class CheckFailure : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

[[noreturn]] void check_failed(const char* condition, const char* file, int line);

}  // namespace photon

#define CHECK(cond)                                                 \
  do {                                                              \
    if (!(cond)) ::photon::check_failed(#cond, __FILE__, __LINE__); \
  } while (false)
#define CHECK_LE(a, b) CHECK((a) <= (b))
#define CHECK_LT(a, b) CHECK((a) < (b))
#define CHECK_EQ(a, b) CHECK((a) == (b))

#ifdef NDEBUG
// Not evaluated, but still compiled, so a DCHECK cannot rot.
#define DCHECK(cond)       \
  do {                     \
    if (false && (cond)) { \
    }                      \
  } while (false)
#else
#define DCHECK(cond) CHECK(cond)
#endif
#define DCHECK_LT(a, b) DCHECK((a) < (b))
#define DCHECK_LE(a, b) DCHECK((a) <= (b))
