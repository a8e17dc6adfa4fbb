#pragma once
/// \file
/// Where a registration starts (core::WarmStart), read from what a user or a stream has: a result JSON of an
/// earlier registration (its holistic space's T_observed_canonical and latent; a partwise result's first
/// part's pose alone), a JSON object {"T_observed_canonical": 4x4} or a bare 4x4 JSON array (rows), or 16
/// numbers on the command line (rows, separated by commas or spaces).

#include <nlohmann/json.hpp>
#include <string>

#include "partreg/core/registration/registration.hpp"

namespace partreg::io {

/// The warm start in `json` (any of the forms above). Throws InputError naming what is wrong.
core::WarmStart warm_start_from_json(const nlohmann::json& json);

/// `text` as 16 numbers, or else the path of a JSON file in one of the forms above. Throws InputError for
/// an unreadable file or a value that is none of them.
core::WarmStart read_warm_start(const std::string& text);

}  // namespace partreg::io
