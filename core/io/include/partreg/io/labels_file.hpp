#pragma once
/// \file
/// Part labels of a canonical mesh or point set: a small versioned JSON file that `partreg label` and the GUI
/// write and `partreg train --labels` reads. Format in docs/labels.md.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace partreg::io {

/// The labels file version this build reads and writes.
inline constexpr int kLabelsFormatVersion = 1;

/// Parts and one label per mesh face or per point (-1 = unlabelled).
struct PartLabels {
  enum class Target { faces, points };
  std::vector<std::string> names;                   ///< part index -> name (unique)
  std::vector<std::array<std::uint8_t, 3>> colors;  ///< part index -> sRGB colour
  Target target = Target::faces;
  Eigen::VectorXi labels;  ///< one per face or point
  std::string source;      ///< file name of the mesh or cloud it was made for

  /// The index of part `name`, adding it (with the next palette colour) when new.
  int part_index(const std::string& name);
};

/// A colour-blind-safe palette colour (Okabe-Ito) for part `index`.
std::array<std::uint8_t, 3> part_color(int index);

/// Reads a labels file; InputError (naming the file) for malformed JSON, another format or version,
/// duplicate part names, labels out of range, or a count that does not match the labels.
PartLabels read_labels_file(const std::filesystem::path& path);

/// Writes a labels file atomically.
void write_labels_file(const std::filesystem::path& path, const PartLabels& labels);

/// Throws InputError when `labels` does not hold exactly `count` labels ("... for the faces of mug.obj").
void check_labels_match(const PartLabels& labels, std::size_t count, const std::string& what);

}  // namespace partreg::io
