#include "photon/integrators/prepared_state_file.h"

#include <OpenImageIO/hash.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace photon {
namespace {

constexpr char kMagic[8] = {'P', 'H', 'O', 'T', 'P', 'R', 'E', 'P'};
constexpr size_t kBlockBytes = size_t{1} << 20;
constexpr long kHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8;
constexpr long kSizeOffset = 8 + 4 + 4 + 8;  // where the payload size and checksum go

uint64_t block_hash(const void* data, size_t size, size_t index) {
  return OIIO::xxhash::XXH64(data, size, index);
}

uint64_t combined_checksum(const std::vector<uint64_t>& hashes) {
  return OIIO::xxhash::XXH64(hashes.data(), hashes.size() * sizeof(uint64_t), kPreparedStateFormat);
}

std::string errno_text() {
  return std::strerror(errno);
}

// A name beside `path` that no other writer (another process, another thread) uses.
std::string temporary_name(const std::string& path) {
  static std::atomic<uint64_t> counter{0};
  return path + ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

// Why `path` cannot be replaced by a prepared-state file ("" when it can): it exists and is not a
// regular file (a device, a FIFO, a folder, a link), which renaming over it would destroy.
std::string replace_refusal(const std::string& path) {
  struct stat st;
  if (::lstat(path.c_str(), &st) != 0) return "";  // nothing there yet
  if (S_ISREG(st.st_mode)) return "";
  return path + " exists and is not a regular file; refusing to replace it";
}

}  // namespace

PreparedStateWriter::PreparedStateWriter(const std::string& path, IntegratorType type,
                                         uint64_t fingerprint)
    : path_(path), temp_path_(temporary_name(path)) {
  error_ = replace_refusal(path);
  if (!error_.empty()) {
    failed_ = true;
    temp_path_.clear();  // nothing created, nothing to remove
    return;
  }
  file_ = std::fopen(temp_path_.c_str(), "wb");
  if (!file_) {
    failed_ = true;
    error_ = "cannot create " + temp_path_ + ": " + errno_text();
    return;
  }
  block_.reserve(kBlockBytes);
  const uint32_t header[2] = {kPreparedStateFormat, static_cast<uint32_t>(type)};
  const uint64_t rest[3] = {fingerprint, 0, 0};  // size and checksum are filled in by finish()
  if (std::fwrite(kMagic, 1, sizeof kMagic, file_) != sizeof kMagic ||
      std::fwrite(header, sizeof header, 1, file_) != 1 ||
      std::fwrite(rest, sizeof rest, 1, file_) != 1) {
    failed_ = true;
    error_ = "cannot write " + temp_path_ + ": " + errno_text();
  }
}

PreparedStateWriter::~PreparedStateWriter() {
  if (file_) std::fclose(file_);
  if (!temp_path_.empty()) std::remove(temp_path_.c_str());
}

void PreparedStateWriter::flush_block() {
  if (block_.empty()) return;
  block_hashes_.push_back(block_hash(block_.data(), block_.size(), block_hashes_.size()));
  if (!failed_ && std::fwrite(block_.data(), 1, block_.size(), file_) != block_.size()) {
    failed_ = true;
    error_ = "cannot write " + temp_path_ + ": " + errno_text();
  }
  block_.clear();
}

void PreparedStateWriter::bytes(const void* data, size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  size_ += size;
  while (size > 0) {
    const size_t n = std::min(size, kBlockBytes - block_.size());
    block_.insert(block_.end(), p, p + n);
    p += n;
    size -= n;
    if (block_.size() == kBlockBytes) flush_block();
  }
}

bool PreparedStateWriter::finish(std::string* error) {
  flush_block();
  if (!failed_) {
    const uint64_t tail[2] = {size_, combined_checksum(block_hashes_)};
    // fsync: a full disk may refuse the blocks only when they are written out.
    if (std::fseek(file_, kSizeOffset, SEEK_SET) != 0 ||
        std::fwrite(tail, sizeof tail, 1, file_) != 1 || std::fflush(file_) != 0 ||
        ::fsync(::fileno(file_)) != 0) {
      failed_ = true;
      error_ = "cannot write " + temp_path_ + ": " + errno_text();
    }
  }
  if (file_ && std::fclose(file_) != 0 && !failed_) {
    failed_ = true;
    error_ = "cannot write " + temp_path_ + ": " + errno_text();
  }
  file_ = nullptr;
  if (!failed_) {
    // The path may have become a device or a folder while the state was written.
    const std::string refusal = replace_refusal(path_);
    if (!refusal.empty()) {
      failed_ = true;
      error_ = refusal;
    }
  }
  if (!failed_ && std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    failed_ = true;
    error_ = "cannot rename " + temp_path_ + " to " + path_ + ": " + errno_text();
  }
  if (failed_) {
    if (error) *error = error_;
    return false;
  }
  temp_path_.clear();  // renamed: nothing to remove
  return true;
}

PreparedStateReader::~PreparedStateReader() {
  if (file_) std::fclose(file_);
}

bool PreparedStateReader::fail(const std::string& why) {
  if (error_.empty()) error_ = why;
  return false;
}

bool PreparedStateReader::open(const std::string& path, IntegratorType type, uint64_t fingerprint,
                               std::string* error) {
  auto refuse = [&](const std::string& why) {
    error_ = why;
    if (error) *error = why;
    return false;
  };
  // Opened without blocking and checked on the open file: a FIFO with no writer would block
  // fopen() for ever, and a device or a folder is no prepared state.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return refuse("cannot open " + path + ": " + errno_text());
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return refuse(path + " is not a regular file");
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  file_ = ::fdopen(fd, "rb");
  if (!file_) {
    ::close(fd);
    return refuse("cannot open " + path + ": " + errno_text());
  }
  char magic[8];
  uint32_t header[2];
  uint64_t rest[3];
  if (std::fread(magic, 1, sizeof magic, file_) != sizeof magic ||
      std::memcmp(magic, kMagic, sizeof magic) != 0)
    return refuse(path + " is not a prepared-state file");
  if (std::fread(header, sizeof header, 1, file_) != 1 ||
      std::fread(rest, sizeof rest, 1, file_) != 1)
    return refuse(path + " is truncated (incomplete header)");
  if (header[0] != kPreparedStateFormat)
    return refuse(path + " has format version " + std::to_string(header[0]) +
                  ", this build reads " + std::to_string(kPreparedStateFormat));
  if (header[1] != static_cast<uint32_t>(type))
    return refuse(path + " was prepared by another integrator");
  if (rest[0] != fingerprint)
    return refuse(path + " was prepared for another scene or other render settings (fingerprint " +
                  std::to_string(rest[0]) + ", this render's " + std::to_string(fingerprint) + ")");
  size_ = rest[1];
  checksum_ = rest[2];
  // The payload must be exactly the rest of the file.
  const long here = std::ftell(file_);
  if (std::fseek(file_, 0, SEEK_END) != 0) return refuse("cannot read " + path);
  const long end = std::ftell(file_);
  if (here != kHeaderBytes || end < here || static_cast<uint64_t>(end - here) != size_ ||
      std::fseek(file_, here, SEEK_SET) != 0)
    return refuse(path + " is truncated or has trailing bytes (payload of " +
                  std::to_string(end - here) + " bytes, header says " + std::to_string(size_) +
                  ")");
  return true;
}

bool PreparedStateReader::refill() {
  const uint64_t left_in_file = size_ - (consumed_ + (block_.size() - block_pos_));
  const size_t n = static_cast<size_t>(std::min<uint64_t>(kBlockBytes, left_in_file));
  if (n == 0) return fail("the payload ends early");
  block_.resize(n);
  block_pos_ = 0;
  if (std::fread(block_.data(), 1, n, file_) != n) {
    block_.clear();
    return fail("cannot read the payload: " + errno_text());
  }
  block_hashes_.push_back(block_hash(block_.data(), n, block_hashes_.size()));
  return true;
}

bool PreparedStateReader::bytes(void* data, size_t size) {
  if (!ok() || !file_) return false;
  if (size > remaining()) return fail("the payload ends early");
  auto* p = static_cast<uint8_t*>(data);
  while (size > 0) {
    if (block_pos_ == block_.size() && !refill()) return false;
    const size_t n = std::min(size, block_.size() - block_pos_);
    std::memcpy(p, block_.data() + block_pos_, n);
    block_pos_ += n;
    consumed_ += n;
    p += n;
    size -= n;
  }
  return true;
}

bool PreparedStateReader::finish(std::string* error) {
  if (ok() && remaining() != 0)
    fail("the payload has " + std::to_string(remaining()) + " bytes the integrator did not read");
  if (ok() && combined_checksum(block_hashes_) != checksum_)
    fail("the payload does not match its checksum (the file is damaged)");
  if (!ok() && error) *error = error_;
  return ok();
}

}  // namespace photon
