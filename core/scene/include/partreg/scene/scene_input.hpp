#pragma once
/// \file
/// A scene as the commands and the Python module take it: a depth image with its intrinsics (and optionally
/// the object's mask), or a scene cloud (PCD, PLY, ... in the camera frame, metres) with optional intrinsics.

#include <filesystem>
#include <optional>

#include "partreg/scene/segmentation.hpp"

namespace partreg::scene {

/// Reads a depth image and its intrinsics (camera_io.hpp), and the object's mask when `mask` is not empty.
SceneView read_depth_view(const std::filesystem::path& depth, const std::filesystem::path& intrinsics,
                          const std::filesystem::path& mask = {});

/// A depth image already in memory (metres, row-major, intrinsics.height x intrinsics.width; 0 or NaN = none).
SceneView depth_view(const DepthImage& depth, const Intrinsics& intrinsics, const PixelMask* mask = nullptr);

/// Reads a scene cloud in the camera frame (NaN points dropped); with `intrinsics` (not empty) its points get
/// the pixels they project to, so a pixel pick works.
SceneView read_scene_cloud(const std::filesystem::path& cloud, const std::filesystem::path& intrinsics = {});

}  // namespace partreg::scene
