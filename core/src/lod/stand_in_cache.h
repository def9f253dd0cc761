// The stand-ins a model has built for the levels of detail queries asked of it (Model::atDetail), kept with the
// model: each level is built once, on first request, under the cache's lock; later requests only look it up.
// Internal.
#pragma once

#include "unidist/model.h"

#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace unidist::lod {

/// What a builder makes for one level: the stand-in (null when the model has no coarser form within the level)
/// and its proved deviation from the model.
struct Built {
  std::unique_ptr<const Model> model;
  double deviation = 0;
};

/// Throws InputError unless maxDeviation is finite and >= 0.
void checkLevel(double maxDeviation);

class StandInCache {
 public:
  /// The stand-in for `level` (> 0), built by build(level) on the first request for it.
  template <class Build>
  StandIn get(const Model& owner, double level, Build&& build) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& e : entries_)
      if (e.level == level) return e.model ? StandIn{e.model.get(), e.deviation} : StandIn{&owner, 0.0};
    Built b = build(level);
    entries_.push_back(Entry{level, std::move(b.model), b.deviation});
    const Entry& e = entries_.back();
    return e.model ? StandIn{e.model.get(), e.deviation} : StandIn{&owner, 0.0};
  }

  /// "level-of-detail" for Model::structures(): built once any level was asked; bytes of every stand-in.
  StructureReport report() const {
    std::lock_guard<std::mutex> lock(mutex_);
    StructureReport r{"level-of-detail", !entries_.empty(), 0};
    for (const Entry& e : entries_)
      if (e.model) r.bytes += e.model->memoryBytes();
    return r;
  }

 private:
  struct Entry {
    double level;
    std::unique_ptr<const Model> model;
    double deviation;
  };
  mutable std::mutex mutex_;
  mutable std::vector<Entry> entries_;
};

}  // namespace unidist::lod
