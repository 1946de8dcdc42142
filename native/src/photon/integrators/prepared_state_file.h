// A file holding what an integrator's prepare() computed, so that several renders of one frame
// (the bands of a frame split over a render farm) load it instead of preparing again.
//
// Layout, little-endian:
//   "PHOTPREP"            8 bytes
//   format version        u32 (kPreparedStateFormat)
//   integrator type       u32 (IntegratorType)
//   fingerprint           u64 (prepared_state_fingerprint.h: scene content and settings)
//   payload size          u64
//   payload checksum      u64 (XXH64 over the XXH64s of the payload's 1 MiB blocks)
//   payload               the integrator's state (its own layout, e.g. photon_map/
//                         prepared_state_io.h)
// The payload is written and read as a stream in blocks, so saving or loading a state never
// holds a second copy of it in memory. A reader refuses a file, with the reason, whose header
// differs from what the render expects, whose payload is shorter or longer than its size, or
// whose blocks do not hash to the checksum; every count read from a payload is checked
// against the bytes left before anything is allocated, so a damaged file cannot make a
// reader allocate more than the file holds.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "photon/integrators/sampling_params.h"

namespace photon {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "prepared-state files store the machine's little-endian values as they are");

// Bump when any integrator's payload layout or the meaning of its contents changes.
constexpr uint32_t kPreparedStateFormat = 1;

// Writes the payload of a prepared-state file at `path`, through a temporary file in the same
// folder that is renamed to `path` once complete (a reader never sees a partial file).
class PreparedStateWriter {
 public:
  PreparedStateWriter(const std::string& path, IntegratorType type, uint64_t fingerprint);
  ~PreparedStateWriter();  // removes the temporary file unless finish() succeeded
  PreparedStateWriter(const PreparedStateWriter&) = delete;
  PreparedStateWriter& operator=(const PreparedStateWriter&) = delete;

  void bytes(const void* data, size_t size);
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof(T));
  }
  // A count, then the elements.
  template <class T>
  void vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value<uint64_t>(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  uint64_t payload_size() const { return size_; }
  // Completes the header and renames the file into place; false with `error` on any failure.
  bool finish(std::string* error);

 private:
  void flush_block();

  std::string path_, temp_path_;
  std::FILE* file_ = nullptr;
  bool failed_ = false;
  std::string error_;
  uint64_t size_ = 0;
  std::vector<uint8_t> block_;
  std::vector<uint64_t> block_hashes_;
};

// Reads a prepared-state file's payload. open() checks the header; then the payload is read
// with bytes() / value() / vector(), each false (and ok() false) once the file runs short or
// a count exceeds what is left; finish() says whether the payload was read exactly to its end
// and hashes to the checksum. Nothing read may be used before finish() returned true.
class PreparedStateReader {
 public:
  PreparedStateReader() = default;
  ~PreparedStateReader();
  PreparedStateReader(const PreparedStateReader&) = delete;
  PreparedStateReader& operator=(const PreparedStateReader&) = delete;

  // False with `error` when the file is missing or unreadable, is not a prepared-state file,
  // has another format version, or was prepared for another integrator or fingerprint.
  bool open(const std::string& path, IntegratorType type, uint64_t fingerprint, std::string* error);
  bool bytes(void* data, size_t size);
  template <class T>
  bool value(T* v) {
    static_assert(std::is_trivially_copyable_v<T>);
    return bytes(v, sizeof(T));
  }
  template <class T>
  bool vector(std::vector<T>* v) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t count = 0;
    if (!value(&count)) return false;
    if (count > remaining() / sizeof(T)) return fail("a count exceeds the file's size");
    v->resize(static_cast<size_t>(count));
    return bytes(v->data(), static_cast<size_t>(count) * sizeof(T));
  }
  uint64_t remaining() const { return size_ - consumed_; }
  uint64_t payload_size() const { return size_; }
  bool ok() const { return error_.empty(); }
  // Marks the payload as unusable (a value out of its range); returns false.
  bool fail(const std::string& why);
  bool finish(std::string* error);

 private:
  bool refill();

  std::FILE* file_ = nullptr;
  std::string error_;
  uint64_t size_ = 0, consumed_ = 0, checksum_ = 0;
  std::vector<uint8_t> block_;
  size_t block_pos_ = 0;
  std::vector<uint64_t> block_hashes_;
};

}  // namespace photon
