#pragma once
/// \file
/// Reading a category's training folder. Two layouts (instances are assumed pose-aligned in one frame):
///  - one file per instance (any mesh or cloud format partreg reads): DATASET/<instance>.<ext>;
///  - one subfolder per instance with one mesh per part, the file stem naming the part:
///    DATASET/<instance>/<part>.<ext> (as ../shared/data/kettles). Parts then come with every instance.
/// Folders named `ground_truth` and hidden entries are skipped (synthetic categories keep their
/// correspondences there).

#include <filesystem>
#include <string>
#include <vector>

#include "partreg/core/training/training.hpp"

namespace partreg::io {

/// How instances are turned into points.
struct DatasetOptions {
  int points_per_instance = 4000;  ///< surface samples per mesh instance (clouds are kept as they are)
  std::uint64_t seed = 1;          ///< sampling seed (instance i uses seed + i)
};

/// A category read from disk.
struct Dataset {
  std::string name;                               ///< the folder's name
  bool part_folders = false;                      ///< true for the one-subfolder-per-instance layout
  std::vector<std::string> part_names;            ///< empty for a category without part files
  std::vector<core::TrainingInstance> instances;  ///< sorted by name
};

/// Reads a dataset folder. Throws InputError naming the folder or file for an empty folder, a single
/// instance, unreadable files, or part folders whose part names differ between instances.
Dataset read_dataset(const std::filesystem::path& folder, const DatasetOptions& options = {});

/// One instance from a folder of part meshes (the layout of one kettle: <part>.<ext>, the stem naming the
/// part): an area-uniform sample of `options.points_per_instance` points with a part per point, indexing
/// `part_names`, which must name every file's stem (InputError naming the stranger otherwise, or for a folder
/// without part files).
core::TrainingInstance read_part_folder(const std::filesystem::path& folder,
                                        const std::vector<std::string>& part_names,
                                        const DatasetOptions& options = {});

/// Gives one instance parts from per-face labels of its mesh (a labels file made for it): the mesh is split
/// by label and re-sampled like a part-folder instance. Throws InputError when the face count differs.
void apply_face_labels(Dataset& dataset, const std::string& instance,
                       const std::vector<std::string>& part_names, const Eigen::VectorXi& face_labels,
                       const DatasetOptions& options = {});

/// Gives the instance a labels file was made for (`canonical`, or the labels' source file name) its parts;
/// returns that instance's name. UsageError for a dataset with part files; InputError for a mismatch.
std::string apply_labels_file(Dataset& dataset, const std::filesystem::path& labels_path,
                              const std::string& canonical, const DatasetOptions& options = {});

/// Several labels files, each giving the instance its `source` names its parts (that instance then trains on
/// its own parts and is scored against them in eval); the canonical is `canonical`, which must be one of them,
/// or the first file's. One file: apply_labels_file (`canonical` may name the instance it was made for).
/// Returns the canonical's name. A file listed twice counts once; UsageError for two files naming one
/// instance or a `canonical` none labels, InputError for part names that differ from the first file's.
std::string apply_labels_files(Dataset& dataset, const std::vector<std::filesystem::path>& labels_paths,
                               const std::string& canonical, const DatasetOptions& options = {});

}  // namespace partreg::io
