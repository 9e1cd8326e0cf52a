// The impact tables a running `cueplan serve` answers searches with: one per cushion
// (the table's dimensionless parameters), loaded from the table cache or built there by
// one background thread, so that no request waits half a minute for a build. The
// shipped problems' cushions are queued at start; a request for another cushion queues
// its own, up to a bound on how many tables the server keeps.
#pragma once

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/impact_table.hpp"

namespace cueplan::server {

class ImpactTableStore {
 public:
  struct Settings {
    std::string cache_dir;                // where tables are kept; empty: built, not kept
    physics::ImpactTableOptions options;  // their shape; the command line's by default
    size_t max_tables = 8;                // the most cushions the server keeps tables for
    // Called from the building thread when a table is ready or failed, with one line.
    std::function<void(const std::string&)> on_note;
  };

  enum class State { queued, loading, building, ready, failed };

  // What the store has for a cushion.
  struct Lookup {
    State state = State::queued;
    std::shared_ptr<const physics::ImpactTable> table;  // when ready
    std::string message;  // failed: why; otherwise what is happening, for people
    bool refused = false;  // the store is full: no table will be made for this cushion
  };

  explicit ImpactTableStore(Settings settings);
  // Waits for a table being made (the command line does not wait: it exits instead).
  ~ImpactTableStore();
  ImpactTableStore(const ImpactTableStore&) = delete;
  ImpactTableStore& operator=(const ImpactTableStore&) = delete;

  // The table for this cushion, or what is being done about it; a cushion the store
  // does not know is queued (unless the store is full).
  Lookup find(const physics::CushionParams& params);
  // The same, but waits while the table is queued or being made: ready, failed or
  // refused.
  Lookup wait_for(const physics::CushionParams& params);
  // True while a table is queued or being made.
  bool working() const;
  // Each table's cushion (theta_deg, mu_cushion, mu_table, restitution), state and
  // note, for /api/health.
  nlohmann::ordered_json json() const;

 private:
  struct Entry {
    std::string key;  // ImpactTable::cache_file_name
    physics::CushionParams params;
    State state = State::queued;
    std::shared_ptr<const physics::ImpactTable> table;
    std::string note;
  };

  void run();  // the building thread
  Lookup lookup_of(const Entry& entry) const;

  Settings settings_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;     // the building thread: work queued, or stop
  std::condition_variable settled_;  // waiters: a table is ready or failed
  std::vector<std::unique_ptr<Entry>> entries_;  // in the order asked for
  bool stopping_ = false;
  std::thread builder_;
};

const char* to_string(ImpactTableStore::State state);

}  // namespace cueplan::server
