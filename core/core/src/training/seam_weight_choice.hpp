#pragma once
// The coupled variant's seam weight, chosen per category at training (internal to partreg_core's training).
//
// How stiffly the seam term holds neighbouring parts together is a property of the category: the mugs'
// handles and the spray bottles' heads vary apart from their bodies and fit best with a soft seam (weight 1),
// the drills' handle and head move together and fit best with a stiff one (30); the training fields' own seam
// gaps do not order them (docs/training.md, "The seam weight"). So training measures it: each
// instance other than the canonical is held out in turn, the spaces are learned again without it, and its own
// whole sample and four partial views are registered with every candidate weight; the weight with the lowest
// mean error against the held-out instance wins.

#include <functional>
#include <string>
#include <vector>

#include "partreg/core/space/category_model.hpp"
#include "partreg/core/training/training.hpp"

namespace partreg::core::detail {

struct SeamWeightChoice {
  double weight = 0.0;
  std::string explanation;  ///< the candidates' mean errors, for the model's record and training's log
  std::vector<SeamWeightTrial> trials;  ///< each candidate's mean error (empty when none was measured)
};

/// Instances held out when choosing among `candidates` for `instances` training instances: every one but the
/// canonical, up to 8 (evenly spread); 0 when there is nothing to choose (one candidate, or fewer than three
/// instances: held out, one would leave the canonical alone).
std::vector<std::size_t> seam_weight_held_out(std::size_t instances, std::size_t canonical_index,
                                              const std::vector<double>& candidates);

/// Chooses among `settings.seam_weight_candidates` for `model` (trained on every instance; has parts).
/// `fields[s][i]` is the training field of space s (model.spaces order) for instance i, `samples[i]` instance
/// i's sample (normalised units). `step` is called once per held-out instance (seam_weight_held_out()) with a
/// line. One candidate, or none held out: the middle candidate (the later of two middles), "given" or "too
/// few instances to choose".
SeamWeightChoice choose_seam_weight(const CategoryModel& model,
                                    const std::vector<std::vector<Points>>& fields,
                                    const std::vector<Points>& samples, std::size_t canonical_index,
                                    const TrainingSettings& settings,
                                    const std::function<void(const std::string&)>& step);

}  // namespace partreg::core::detail
