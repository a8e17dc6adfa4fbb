#pragma once
/// \file
/// The category model file (`.prm`): a versioned, self-checking container for core::CategoryModel.
///
/// Layout (all little-endian; details in docs/model_format.md):
///   8 bytes  magic "PRTREGM\n"
///   8 bytes  uint64 length H of the JSON header
///   H bytes  JSON header: format version, partreg version, category, normalisation, parts, training record,
///            spaces' scalars, and a table of arrays (name, dtype, shape, offset, bytes, FNV-1a 64 checksum)
///   ...      the arrays' raw bytes, each starting at an 8-byte aligned offset from the end of the header
/// No language-specific serialisation: any language with a JSON parser can read it.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "partreg/core/space/category_model.hpp"

namespace partreg::io {

/// The model file format this build reads and writes. Bump it on any incompatible change.
/// 2: the training instances' holistic weight fields and their latents in every space.
inline constexpr int kModelFormatVersion = 2;

/// Writes `model` to `path` atomically (a temporary file renamed into place).
void write_model(const std::filesystem::path& path, const core::CategoryModel& model);

/// Reads a model. Throws InputError with one clear line for a missing file, a file that is not a partreg
/// model, another format version, a truncated file, or an array whose checksum does not match (corruption).
core::CategoryModel read_model(const std::filesystem::path& path);

/// The model file's training block (docs/model_format.md), which `info` and `train --json` print as well.
nlohmann::json training_record_json(const core::TrainingRecord& record);

}  // namespace partreg::io
