#include "photon/session/job.h"

#include <algorithm>
#include <cmath>
#include <exception>

namespace photon {

Job::Job(std::string failure_label) : failure_label_(std::move(failure_label)) {}

Job::~Job() {
  stop_worker();
}

void Job::start() {
  if (started_.exchange(true)) return;
  worker_ = std::thread([this] { run_guarded(); });
}

void Job::wait() {
  if (worker_.joinable()) worker_.join();
}

void Job::cancel() {
  cancel_ = true;
}

void Job::stop_preparation() {
  stop_preparation_ = true;
}

void Job::stop_worker() {
  cancel();
  wait();
}

float Job::progress() const {
  if (preparing_) return std::clamp(prepare_fraction_.load(), 0.0f, 1.0f);
  const size_t total = work_total_.load();
  if (total == 0) return 1.0f;
  return static_cast<float>(std::min(work_done_.load(), total)) / static_cast<float>(total);
}

std::string Job::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

std::vector<std::string> Job::warnings() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return warnings_;
}

std::string Job::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

JobSnapshot Job::snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  JobSnapshot s;
  s.status = status_;
  s.progress = progress();
  s.preparing = preparing_;
  s.finished = finished_;
  s.cancelled = cancel_;
  s.error = error_;
  return s;
}

PrepareControl Job::prepare_control() {
  PrepareControl control;
  control.cancel = &cancel_;
  control.stop_early = &stop_preparation_;
  control.progress = [this](const std::string& status, float fraction) {
    // A NaN from a 0/0 in a report is shown as no progress rather than passed to Blender.
    prepare_fraction_ = std::isfinite(fraction) ? fraction : 0.0f;
    set_status(status);
  };
  control.warn = [this](const std::string& warning) { add_warning(warning); };
  return control;
}

void Job::set_status(const std::string& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  status_ = status;
}

void Job::add_warning(const std::string& warning) {
  std::lock_guard<std::mutex> lock(mutex_);
  warnings_.push_back(warning);
}

void Job::add_warnings(const std::vector<std::string>& warnings) {
  std::lock_guard<std::mutex> lock(mutex_);
  warnings_.insert(warnings_.end(), warnings.begin(), warnings.end());
}

void Job::run_guarded() {
  // Nothing may escape the worker thread: an exception there would terminate Blender.
  std::string error;
  try {
    run();
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "unknown error";
  } catch (...) {
    error = "unknown error";
  }
  preparing_ = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error.empty()) {
      cancel_ = true;  // stops whatever else of the work still polls the flag
      error_ = error;
      warnings_.push_back(failure_label_ + " failed: " + error);
      status_ = "Failed";
    } else {
      status_ = cancel_ ? "Cancelled" : "Done";
    }
    finished_ = true;
  }
  on_finished();
}

}  // namespace photon
