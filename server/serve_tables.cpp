#include "serve_tables.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <utility>

#include "cueplan/api/table_cache.hpp"

namespace cueplan::server {
using namespace cueplan::api;  // the api's types and checks, as the server's own
namespace {

namespace phys = cueplan::physics;
using nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

constexpr double kDegreesPerRadian = 57.29577951308232;

std::string cushion_text(const phys::CushionParams& p) {
  return fmt::format("theta {:.4g} deg, mu_cushion {:.4g}, mu_table {:.4g}, restitution {:.4g}",
                     std::asin(p.sin_theta()) * kDegreesPerRadian, p.mu_cushion, p.mu_table,
                     p.restitution);
}

}  // namespace

const char* to_string(ImpactTableStore::State state) {
  switch (state) {
    case ImpactTableStore::State::queued: return "queued";
    case ImpactTableStore::State::loading: return "loading";
    case ImpactTableStore::State::building: return "building";
    case ImpactTableStore::State::ready: return "ready";
    case ImpactTableStore::State::failed: return "failed";
  }
  return "failed";
}

ImpactTableStore::ImpactTableStore(Settings settings)
    : settings_(std::move(settings)), builder_([this] { run(); }) {}

ImpactTableStore::~ImpactTableStore() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  builder_.join();
}

ImpactTableStore::Lookup ImpactTableStore::lookup_of(const Entry& entry) const {
  return {entry.state, entry.table, entry.note, false};
}

ImpactTableStore::Lookup ImpactTableStore::find(const phys::CushionParams& params) {
  const std::string key = phys::ImpactTable::cache_file_name(params, settings_.options);
  std::lock_guard<std::mutex> lock(mutex_);
  for (const std::unique_ptr<Entry>& e : entries_)
    if (e->key == key) return lookup_of(*e);
  if (entries_.size() >= settings_.max_tables) {
    Lookup refused;
    refused.state = State::failed;
    refused.refused = true;
    refused.message = fmt::format(
        "this server keeps impact tables for at most {} cushions and has no room for this one "
        "({})",
        settings_.max_tables, cushion_text(params));
    return refused;
  }
  auto entry = std::make_unique<Entry>();
  entry->key = key;
  entry->params = params;
  entry->note = "queued: the table is loaded from the cache or built (once; a build takes "
                "about 30 s on 2 cores)";
  const Lookup queued = lookup_of(*entry);
  entries_.push_back(std::move(entry));
  wake_.notify_all();
  return queued;
}

ImpactTableStore::Lookup ImpactTableStore::wait_for(const phys::CushionParams& params) {
  const Lookup found = find(params);
  if (found.refused || found.state == State::ready || found.state == State::failed) return found;
  const std::string key = phys::ImpactTable::cache_file_name(params, settings_.options);
  std::unique_lock<std::mutex> lock(mutex_);
  const Entry* entry = nullptr;
  for (const std::unique_ptr<Entry>& e : entries_)
    if (e->key == key) entry = e.get();
  settled_.wait(lock, [&] { return entry->state == State::ready || entry->state == State::failed; });
  return lookup_of(*entry);
}

bool ImpactTableStore::working() const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const std::unique_ptr<Entry>& e : entries_)
    if (e->state != State::ready && e->state != State::failed) return true;
  return false;
}

ordered_json ImpactTableStore::json() const {
  std::lock_guard<std::mutex> lock(mutex_);
  ordered_json tables = ordered_json::array();
  for (const std::unique_ptr<Entry>& e : entries_) {
    const phys::CushionParams& p = e->params;
    tables.push_back({{"cushion",
                       {{"theta_deg", std::asin(p.sin_theta()) * kDegreesPerRadian},
                        {"mu_cushion", p.mu_cushion},
                        {"mu_table", p.mu_table},
                        {"restitution", p.restitution}}},
                      {"state", to_string(e->state)},
                      {"note", e->note}});
  }
  return tables;
}

void ImpactTableStore::run() {
  for (;;) {
    Entry* entry = nullptr;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] {
        if (stopping_) return true;
        for (const std::unique_ptr<Entry>& e : entries_)
          if (e->state == State::queued) return true;
        return false;
      });
      if (stopping_) return;
      for (const std::unique_ptr<Entry>& e : entries_)
        if (e->state == State::queued) {
          entry = e.get();
          break;
        }
      // Entries are never removed, so the pointer stays good outside the lock.
      std::error_code ec;
      const bool cached =
          !settings_.cache_dir.empty() &&
          std::filesystem::exists(std::filesystem::path(settings_.cache_dir) / entry->key, ec);
      entry->state = cached ? State::loading : State::building;
      entry->note = cached ? "loading from the table cache"
                           : "building (once, then cached; about 30 s on 2 cores)";
    }

    const Clock::time_point started = Clock::now();
    std::shared_ptr<phys::ImpactTable> table;
    std::string note;
    try {
      table = std::make_shared<phys::ImpactTable>(
          load_or_build_table(entry->params, settings_.options, settings_.cache_dir, &note));
    } catch (const std::exception& e) {
      note = e.what();
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
    const bool ok = table && !table->empty();
    std::string line;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      entry->state = ok ? State::ready : State::failed;
      if (ok) entry->table = std::move(table);
      const bool built = entry->note.rfind("building", 0) == 0;
      entry->note = ok ? fmt::format("ready ({} in {:.3g} s)", built ? "built" : "loaded", seconds)
                       : "cannot make the impact table: " + note;
      line = "impact table for " + cushion_text(entry->params) + ": " + entry->note;
    }
    settled_.notify_all();
    if (settings_.on_note) settings_.on_note(line);
  }
}

}  // namespace cueplan::server
