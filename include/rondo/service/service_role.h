// Whether this `rondo serve` is the active executive or a standby, at which epoch, and how old its
// lease is: written by the process's lease thread, read by /healthz and /metrics (and by the
// standby's server). Thread-safe. An SQLite service is always active, with no lease (epoch 0).
//
//   ServiceRole role;
//   role.became_active(epoch);   // the lease taken
//   role.renewed();              // after each renewal
//   double age = role.lease_age_seconds();
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace rondo::service {

class ServiceRole {
 public:
  // A PostgreSQL service starts as a standby, an SQLite one is active at once (no lease).
  explicit ServiceRole(bool leased) : leased_(leased), active_(!leased) {}

  bool leased() const { return leased_; }
  bool active() const { return active_; }
  std::int64_t epoch() const { return epoch_; }
  int step_downs() const { return step_downs_; }

  // The lease is this process's, at `epoch`, renewed now.
  void became_active(std::int64_t epoch) {
    epoch_ = epoch;
    renewed();
    active_ = true;
  }
  void renewed() { renewed_ns_ = now_ns(); }
  // A standby's view of the lease: its epoch, holder and the age of its renewal as read.
  void seen(std::int64_t epoch, std::string holder, double age_seconds) {
    epoch_ = epoch;
    renewed_ns_ = now_ns() - static_cast<std::int64_t>(age_seconds * 1e9);
    std::lock_guard lock(mutex_);
    holder_ = std::move(holder);
  }
  void stepped_down() {
    active_ = false;
    ++step_downs_;
  }
  std::string holder() const {
    std::lock_guard lock(mutex_);
    return holder_;
  }
  // Seconds since the lease's latest renewal (this process's own, or the holder's as a standby saw it).
  double lease_age_seconds() const { return static_cast<double>(now_ns() - renewed_ns_) / 1e9; }

  // The /metrics lines: rondo_role, rondo_lease_epoch, rondo_lease_age_seconds, rondo_step_downs_total.
  std::string prometheus() const;

 private:
  static std::int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  const bool leased_;
  std::atomic<bool> active_;
  std::atomic<std::int64_t> epoch_{0};
  std::atomic<std::int64_t> renewed_ns_{now_ns()};
  std::atomic<int> step_downs_{0};
  mutable std::mutex mutex_;
  std::string holder_;
};

}  // namespace rondo::service
