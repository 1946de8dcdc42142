// The common driver of long native work (a render, a lighting bake): one worker thread, cancel
// and stop-early flags, progress and status that any thread may poll, warnings, and exception
// capture. A derived job only supplies its work (run()) and the results it hands out.
#pragma once

#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "photon/integrators/integrator.h"

namespace photon {

// A consistent view of a job, taken under one lock (status and progress of the same moment).
struct JobSnapshot {
  std::string status;
  float progress = 0.0f;  // fraction of the current phase (preparation, then the work)
  bool preparing = false;
  bool finished = false;
  bool cancelled = false;
  std::string error;  // set when the work threw
};

class Job {
 public:
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;
  virtual ~Job();

  void start();  // returns at once; run() goes on the job's own thread (once)
  void wait();   // blocks until the work has finished, been cancelled or failed
  void cancel();
  // Ends the current preparation (photon tracing, a radiosity solve) early; the work then goes
  // on with what was prepared so far.
  void stop_preparation();

  bool finished() const { return finished_.load(); }
  // True after cancel(), and after a failure (which stops the rest of the work too).
  bool cancelled() const { return cancel_.load(); }
  bool preparing() const { return preparing_.load(); }
  // During preparation: the fraction the preparation last reported; then the fraction of the
  // work units done (never decreasing, 1 when there is no work).
  float progress() const;
  std::string status() const;
  std::vector<std::string> warnings() const;
  // Why the work failed (the exception's message); empty unless status() is "Failed".
  std::string error() const;
  JobSnapshot snapshot() const;

 protected:
  // `failure_label` names the work in the warning a failure adds ("Render" -> "Render failed:
  // ...").
  explicit Job(std::string failure_label);

  // The work, on the worker thread. It polls cancel_flag() / prepare_control(); whatever it
  // throws becomes the error status, never std::terminate.
  virtual void run() = 0;
  // On the worker thread once finished() is true (e.g. to wake threads waiting for results).
  virtual void on_finished() {}

  // Cancels and joins the worker. Every derived destructor calls it first, so the worker never
  // runs on after the derived members it uses are destroyed.
  void stop_worker();

  // Control of an integrator's preparation wired to this job: its cancel and stop-early flags,
  // progress reports setting status and fraction, warnings added to warnings().
  PrepareControl prepare_control();
  void set_status(const std::string& status);
  void add_warning(const std::string& warning);
  void add_warnings(const std::vector<std::string>& warnings);
  void set_preparing(bool preparing) { preparing_ = preparing; }
  // Work units of the main phase (tiles, points); work_done() counts finished ones.
  void set_work_total(size_t total) { work_total_ = total; }
  std::atomic<size_t>& work_done() { return work_done_; }
  const std::atomic<bool>& cancel_flag() const { return cancel_; }

 private:
  void run_guarded();

  const std::string failure_label_;
  std::thread worker_;
  std::atomic<bool> started_{false};
  std::atomic<bool> cancel_{false};
  std::atomic<bool> stop_preparation_{false};
  std::atomic<bool> preparing_{false};
  std::atomic<bool> finished_{false};
  std::atomic<float> prepare_fraction_{0.0f};
  std::atomic<size_t> work_total_{0};
  std::atomic<size_t> work_done_{0};

  mutable std::mutex mutex_;  // status_, warnings_, error_
  std::string status_ = "Waiting";
  std::vector<std::string> warnings_;
  std::string error_;
};

}  // namespace photon
