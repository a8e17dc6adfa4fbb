#pragma once
/// \file
/// A depth camera's files: intrinsics JSON, depth images (16-bit PNG in depth_scale units per metre, or
/// NumPy .npy float32/float64 in metres), masks (PNG, non-zero = selected). Every reader checks sizes against
/// the file and the reading budget before it allocates, and throws InputError naming the file on bad data.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "partreg/scene/camera.hpp"

namespace partreg::scene {

/// Reads intrinsics: {"fx","fy","cx","cy","width","height"[,"depth_scale"]} (depth_scale defaults to 1000,
/// millimetres), or Open3D's PinholeCameraIntrinsic JSON as Open3D writes it: {"width","height",
/// "intrinsic_matrix": the 3x3 matrix's 9 numbers column-major} (depth_scale may be added beside them).
/// InputError for a missing key, a non-number, NaN or an impossible value (Intrinsics::validate).
Intrinsics read_intrinsics(const std::filesystem::path& path);

/// Intrinsics from JSON already parsed, as read_intrinsics reads a file; `what` names it in errors.
Intrinsics intrinsics_from_json(const nlohmann::json& json, const std::string& what);

/// The intrinsics as read_intrinsics reads them (both forms: our keys and Open3D's intrinsic_matrix).
nlohmann::json intrinsics_json(const Intrinsics& intrinsics);

/// Reads a depth image: a single-channel 16-bit PNG (value / depth_scale metres, 0 = nothing measured) or a
/// 2-D .npy of float32 or float64 metres (0 or NaN = nothing measured). InputError for another format, an
/// 8-bit or multi-channel PNG, a negative depth, or a size different from the intrinsics'.
DepthImage read_depth_image(const std::filesystem::path& path, const Intrinsics& intrinsics);

/// Writes `depth` as a 16-bit single-channel PNG of round(metres x depth_scale) (0 where nothing was
/// measured or beyond 65535 units), atomically (atomic_file.hpp).
void write_depth_png(const std::filesystem::path& path, const DepthImage& depth, double depth_scale);

/// Reads a mask PNG (any bit depth or channels; a pixel is selected where its grey value is non-zero).
/// InputError when its size differs from the intrinsics'.
PixelMask read_mask(const std::filesystem::path& path, const Intrinsics& intrinsics);

/// Writes `mask` as an 8-bit PNG, 255 where selected, atomically.
void write_mask_png(const std::filesystem::path& path, const PixelMask& mask);

}  // namespace partreg::scene
