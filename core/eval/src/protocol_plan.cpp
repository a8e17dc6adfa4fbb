// What a run of the protocol covers: the named protocols, the levels each sweep runs, the instances a run
// (or one shard of it) tests, and the seeds its jobs draw from.
#include <string>
#include <vector>

#include "partreg/core/errors.hpp"
#include "partreg/eval/perturbation.hpp"
#include "partreg/eval/protocol.hpp"

namespace partreg::eval {

std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t value) {
  // splitmix64 step: seeds of neighbouring jobs are unrelated, and a job's seed depends only on what it is.
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL + value * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::vector<int> planned_levels(Perturbation kind, const Protocol& protocol) {
  const int count = static_cast<int>(sweep_levels(kind).size());
  std::vector<int> levels;
  if (kind == Perturbation::yaw) {
    for (int level = 0; level < count; ++level) levels.push_back(level);
    return levels;
  }
  for (int level : protocol.levels)
    if (level >= 0 && level < kFirstWideRotationLevel) levels.push_back(level);
  if (kind == Perturbation::rotation && protocol.wide_rotation)
    for (int level = kFirstWideRotationLevel; level < count; ++level) levels.push_back(level);
  return levels;
}

Protocol protocol_by_name(const std::string& name) {
  if (name == "paper") return Protocol{};
  if (name == "quick") {
    Protocol quick;
    quick.name = "quick", quick.views = 12, quick.sweep_views = 2, quick.levels = {0, 2, 4};
    quick.max_test_instances = 2;
    return quick;
  }
  throw UsageError("unknown protocol '" + name + "' (paper, quick)");
}

std::vector<std::string> tested_instances(const EvalInput& input, const EvalSettings& settings) {
  const Protocol& protocol = settings.protocol;
  if (input.instances.size() < 3)
    throw InputError("category " + input.category + " has " + std::to_string(input.instances.size()) +
                     " instances: leave-one-out needs at least 3 (2 to train on, 1 to test)");
  if (protocol.folds != 0 && (protocol.folds < 2 || protocol.folds > int(input.instances.size())))
    throw UsageError("a fold count of " + std::to_string(protocol.folds) + " for " +
                     std::to_string(input.instances.size()) +
                     " instances: it must be 0 (leave-one-out) or between 2 and the instance count");
  if (settings.training.size > 0.0)
    throw UsageError("eval observes the category's own files in their own units: --size has no place there");
  if (settings.shard_count < 1 || settings.shard < 0 || settings.shard >= settings.shard_count)
    throw UsageError("shard index " + std::to_string(settings.shard) + " with a shard count of " +
                     std::to_string(settings.shard_count) +
                     ": the count must be at least 1 and the index in [0, count)");
  if (settings.full_view_points < 1 || settings.truth_points < 0)
    throw UsageError(
        "a full view of " + std::to_string(settings.full_view_points) + " and a truth of " +
        std::to_string(settings.truth_points) +
        " surface samples: the full view needs at least 1, the truth 0 (the training sample) or more");
  std::vector<std::string> candidates;
  for (const core::TrainingInstance& instance : input.instances)
    if (instance.name != input.fixed_canonical) candidates.push_back(instance.name);
  if (protocol.max_test_instances > 0 && protocol.max_test_instances < int(candidates.size())) {
    std::vector<std::string> spread;  // evenly spread over the sorted names
    for (int i = 0; i < protocol.max_test_instances; ++i)
      spread.push_back(candidates[i * candidates.size() / protocol.max_test_instances]);
    candidates = spread;
  }
  std::vector<std::string> tested;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (int(i % settings.shard_count) == settings.shard) tested.push_back(candidates[i]);
  return tested;
}

}  // namespace partreg::eval
