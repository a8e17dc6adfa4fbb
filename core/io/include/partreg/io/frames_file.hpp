#pragma once
/// \file
/// Frames attached to a canonical (grasp poses, contact points with orientation), as JSON:
/// {"format": "partreg-frames", "version": 1, "frames": [{"name": "grasp", "position": [x, y, z],
///  "rotation": [[r00, r01, r02], [r10, r11, r12], [r20, r21, r22]]}]} in the category's data frame
/// (the observed frame after `partreg register`).

#include <filesystem>
#include <vector>

#include "partreg/core/registration/deformation.hpp"

namespace partreg::io {

/// The most frames one file may hold. A grasp set has tens to thousands; 200,000 (a 42 MB file) took 89 s
/// to transfer and write back.
inline constexpr std::size_t kMaxFrames = 10'000;

/// Reads frames; InputError naming the file and frame for malformed JSON, more than kMaxFrames frames, or a
/// rotation that is not a proper orthonormal matrix (|R^T R - I| > 1e-6 or det R < 0).
std::vector<core::Frame> read_frames_file(const std::filesystem::path& path);

/// Writes frames atomically.
void write_frames_file(const std::filesystem::path& path, const std::vector<core::Frame>& frames);

}  // namespace partreg::io
