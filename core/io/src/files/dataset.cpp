#include "partreg/io/dataset.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <numeric>
#include <set>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/io/mesh_io.hpp"

namespace partreg::io {
namespace fs = std::filesystem;
namespace {

bool skipped(const fs::path& entry) {
  const std::string name = entry.filename().string();
  return name.empty() || name[0] == '.' || name == "ground_truth";
}

// Whether `text` is well-formed UTF-8 (JSON, which models and results are written in, holds nothing else).
bool is_utf8(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const int extra = lead < 0x80           ? 0
                      : (lead >> 5) == 0x6  ? 1
                      : (lead >> 4) == 0xe  ? 2
                      : (lead >> 3) == 0x1e ? 3
                                            : -1;
    if (extra < 0 || text.size() - i <= static_cast<std::size_t>(extra)) return false;  // cut short
    for (int k = 1; k <= extra; ++k)
      if ((static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]) >> 6) != 0x2) return false;
    i += static_cast<std::size_t>(extra) + 1;
  }
  return true;
}

// Entry names become instance and part names: JSON strings in models and results, fields of eval's CSV
// rows ("body=1e-5;handle=2e-5"). A name that could not be written back (a newline, a comma, bytes that are
// not UTF-8) is refused before any work, naming the file.
void check_entry_name(const fs::path& entry) {
  const std::string name = entry.filename().string();
  bool plain = is_utf8(name);
  for (const unsigned char c : name)
    plain = plain && c >= 0x20 && c != 0x7f && c != ',' && c != '"' && c != ';' && c != '=';
  if (plain) return;
  std::string shown;  // the name as one printable line: other bytes as \xNN
  for (const unsigned char c : entry.string()) {
    if (c >= 0x20 && c < 0x7f) {
      shown += static_cast<char>(c);
      continue;
    }
    char hex[5];
    std::snprintf(hex, sizeof hex, "\\x%02x", c);
    shown += hex;
  }
  throw InputError("dataset entry " + shown +
                   ": its name holds a control character, one of , \" ; = "
                   "or bytes that are not UTF-8 (it names an instance or part in the results): rename it");
}

std::vector<fs::path> sorted_entries(const fs::path& folder) {
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(folder))
    if (!skipped(entry.path())) {
      check_entry_name(entry.path());
      entries.push_back(entry.path());
    }
  std::sort(entries.begin(), entries.end());
  return entries;
}

double mesh_area(const core::Mesh& mesh) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

// Merges part meshes into one instance: a mesh with a part per vertex, and an area-uniform sample with a
// part per point (each part gets samples in proportion to its area, so density is even across parts).
core::TrainingInstance instance_from_parts(const std::string& name, const std::vector<core::Mesh>& parts,
                                           const DatasetOptions& options, std::uint64_t seed) {
  std::vector<double> areas;
  for (const core::Mesh& part : parts) areas.push_back(mesh_area(part));
  const double total = std::accumulate(areas.begin(), areas.end(), 0.0);
  if (!(total > 0.0)) throw InputError("instance '" + name + "' has no surface area");
  core::TrainingInstance instance;
  instance.name = name;
  std::vector<core::Points> samples;
  std::vector<int> sample_parts, vertex_parts;
  std::vector<core::Mesh> meshes;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const auto count =
        std::max<std::size_t>(1, static_cast<std::size_t>(options.points_per_instance * areas[p] / total));
    samples.push_back(core::sample_surface(parts[p], count, seed + 7919 * p).points);
    sample_parts.insert(sample_parts.end(), count, static_cast<int>(p));
    vertex_parts.insert(vertex_parts.end(), static_cast<std::size_t>(parts[p].vertices.rows()),
                        static_cast<int>(p));
  }
  Eigen::Index rows = 0, vertices = 0, faces = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    rows += samples[p].rows();
    vertices += parts[p].vertices.rows();
    faces += parts[p].faces.rows();
  }
  instance.points.resize(rows, 3);
  instance.mesh.vertices.resize(vertices, 3);
  instance.mesh.faces.resize(faces, 3);
  Eigen::Index row = 0, vertex = 0, face = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    instance.points.middleRows(row, samples[p].rows()) = samples[p];
    instance.mesh.vertices.middleRows(vertex, parts[p].vertices.rows()) = parts[p].vertices;
    instance.mesh.faces.middleRows(face, parts[p].faces.rows()) =
        parts[p].faces.array() + static_cast<int>(vertex);
    row += samples[p].rows();
    vertex += parts[p].vertices.rows();
    face += parts[p].faces.rows();
  }
  instance.part =
      Eigen::Map<Eigen::VectorXi>(sample_parts.data(), static_cast<Eigen::Index>(sample_parts.size()));
  instance.mesh_vertex_part =
      Eigen::Map<Eigen::VectorXi>(vertex_parts.data(), static_cast<Eigen::Index>(vertex_parts.size()));
  return instance;
}

// The faces `face_rows` of `mesh` with only the vertices they use.
core::Mesh submesh(const core::Mesh& mesh, const std::vector<int>& face_rows) {
  std::vector<int> new_index(static_cast<std::size_t>(mesh.vertices.rows()), -1);
  std::vector<int> kept;
  core::Mesh part;
  part.faces.resize(static_cast<Eigen::Index>(face_rows.size()), 3);
  for (std::size_t f = 0; f < face_rows.size(); ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const int vertex = mesh.faces(face_rows[f], corner);
      int& mapped = new_index[static_cast<std::size_t>(vertex)];
      if (mapped < 0) mapped = static_cast<int>(kept.size()), kept.push_back(vertex);
      part.faces(static_cast<Eigen::Index>(f), corner) = mapped;
    }
  }
  part.vertices = mesh.vertices(kept, Eigen::all);
  return part;
}

// The part files of one instance folder (its regular files), in file-name order.
std::vector<fs::path> part_files(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const fs::path& entry : sorted_entries(folder))
    if (fs::is_regular_file(entry)) files.push_back(entry);
  return files;
}

std::vector<std::string> part_stems(const fs::path& folder) {
  std::vector<std::string> names;
  for (const fs::path& file : part_files(folder)) names.push_back(file.stem().string());
  return names;
}

// The part meshes of one instance folder, in the order part_stems names them.
std::vector<core::Mesh> part_meshes(const fs::path& folder) {
  std::vector<core::Mesh> parts;
  for (const fs::path& file : part_files(folder)) parts.push_back(read_mesh(file));
  return parts;
}

Dataset read_part_folders(const fs::path& folder, const std::vector<fs::path>& entries,
                          const DatasetOptions& options) {
  Dataset dataset;
  dataset.part_folders = true;
  dataset.part_names = part_stems(entries.front());
  if (dataset.part_names.empty())
    throw InputError("instance folder " + entries.front().string() + " holds no part file");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (!fs::is_directory(entries[i]))
      throw InputError(folder.string() + " mixes instance folders and files (" +
                       entries[i].filename().string() + ")");
    if (part_stems(entries[i]) != dataset.part_names)
      throw InputError("instance folder " + entries[i].string() + " has parts that differ from those of " +
                       entries.front().string() + " (every instance needs the same part files)");
    dataset.instances.push_back(
        instance_from_parts(entries[i].filename().string(), part_meshes(entries[i]), options, options.seed + i));
  }
  return dataset;
}

Dataset read_instance_files(const std::vector<fs::path>& entries, const DatasetOptions& options) {
  Dataset dataset;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    core::TrainingInstance instance;
    instance.name = entries[i].stem().string();
    if (is_mesh_file(entries[i])) instance.mesh = read_mesh(entries[i]);
    instance.points =
        read_as_cloud(entries[i], static_cast<std::size_t>(options.points_per_instance), options.seed + i)
            .points;
    dataset.instances.push_back(std::move(instance));
  }
  return dataset;
}

}  // namespace

Dataset read_dataset(const fs::path& folder, const DatasetOptions& options) {
  if (!fs::is_directory(folder)) throw InputError("dataset folder " + folder.string() + " does not exist");
  const std::vector<fs::path> entries = sorted_entries(folder);
  if (entries.empty()) throw InputError("dataset folder " + folder.string() + " is empty");
  if (entries.size() < 2)
    throw InputError("dataset folder " + folder.string() +
                     " holds only one instance; training needs at least two");
  Dataset dataset = fs::is_directory(entries.front()) ? read_part_folders(folder, entries, options)
                                                      : read_instance_files(entries, options);
  dataset.name = fs::absolute(folder).lexically_normal().filename().string();
  if (dataset.name.empty())
    dataset.name = fs::absolute(folder).lexically_normal().parent_path().filename().string();
  return dataset;
}

core::TrainingInstance read_part_folder(const fs::path& folder, const std::vector<std::string>& part_names,
                                        const DatasetOptions& options) {
  const std::vector<std::string> stems = part_stems(folder);
  if (stems.empty()) throw InputError("folder " + folder.string() + " holds no part file");
  core::TrainingInstance instance =
      instance_from_parts(folder.filename().string(), part_meshes(folder), options, options.seed);
  std::vector<int> index_of_stem;  // the folder's part order -> part_names' order
  for (const std::string& stem : stems) {
    const auto found = std::find(part_names.begin(), part_names.end(), stem);
    if (found == part_names.end()) {
      std::string names;
      for (const std::string& name : part_names) names += (names.empty() ? "" : ", ") + name;
      throw InputError("part file '" + stem + "' of " + folder.string() + " is not a part of the model (" +
                       names + ")");
    }
    index_of_stem.push_back(static_cast<int>(found - part_names.begin()));
  }
  for (int& part : instance.part) part = index_of_stem[static_cast<std::size_t>(part)];
  for (int& part : instance.mesh_vertex_part) part = index_of_stem[static_cast<std::size_t>(part)];
  return instance;
}

void apply_face_labels(Dataset& dataset, const std::string& instance,
                       const std::vector<std::string>& part_names, const Eigen::VectorXi& face_labels,
                       const DatasetOptions& options) {
  auto found =
      std::find_if(dataset.instances.begin(), dataset.instances.end(),
                   [&](const core::TrainingInstance& candidate) { return candidate.name == instance; });
  if (found == dataset.instances.end())
    throw InputError("the labels are for '" + instance + "', which is not in the dataset");
  const core::Mesh& mesh = found->mesh;
  if (mesh.faces.rows() != face_labels.size())
    throw InputError("the labels file has " + std::to_string(face_labels.size()) + " face labels but '" +
                     instance + "' has " + std::to_string(mesh.faces.rows()) + " faces");
  std::vector<core::Mesh> parts(part_names.size());
  for (std::size_t p = 0; p < parts.size(); ++p) {
    std::vector<int> rows;
    for (Eigen::Index f = 0; f < face_labels.size(); ++f)
      if (face_labels[f] == static_cast<int>(p)) rows.push_back(static_cast<int>(f));
    if (rows.empty())
      throw InputError("part '" + part_names[p] + "' has no face in the labels of '" + instance + "'");
    parts[p] = submesh(mesh, rows);
  }
  const auto index = static_cast<std::uint64_t>(found - dataset.instances.begin());
  *found = instance_from_parts(instance, parts, options, options.seed + index);
  dataset.part_names = part_names;
}

// A labels file made for one instance's mesh gives that instance (the canonical) its parts.
namespace {

// Labels files are for datasets without part files: refused before any file is read.
void refuse_part_folders(const Dataset& dataset) {
  if (dataset.part_folders)
    throw UsageError("dataset " + dataset.name + " has part files already; --labels is for datasets without");
}

// Gives `instance` the labels read from `labels_path` (its faces' or its points').
void apply_labels(Dataset& dataset, const PartLabels& labels, const std::filesystem::path& labels_path,
                  const std::string& instance, const DatasetOptions& options) {
  if (labels.target == PartLabels::Target::faces) {
    apply_face_labels(dataset, instance, labels.names, labels.labels, options);
    return;
  }
  auto found =
      std::find_if(dataset.instances.begin(), dataset.instances.end(),
                   [&](const core::TrainingInstance& candidate) { return candidate.name == instance; });
  if (found == dataset.instances.end())
    throw InputError("labels file " + labels_path.string() + " is for '" + instance + "', not in the dataset");
  check_labels_match(labels, static_cast<std::size_t>(found->points.rows()), "points of " + instance);
  found->part = labels.labels;
  dataset.part_names = labels.names;
}

}  // namespace

std::string apply_labels_file(Dataset& dataset, const std::filesystem::path& labels_path,
                              const std::string& canonical, const DatasetOptions& options) {
  refuse_part_folders(dataset);
  const PartLabels labels = read_labels_file(labels_path);
  const std::string instance =
      canonical.empty() ? std::filesystem::path(labels.source).stem().string() : canonical;
  apply_labels(dataset, labels, labels_path, instance, options);
  return instance;
}

std::string apply_labels_files(Dataset& dataset, const std::vector<std::filesystem::path>& labels_paths,
                               const std::string& canonical, const DatasetOptions& options) {
  if (labels_paths.empty()) return canonical;
  if (labels_paths.size() == 1) return apply_labels_file(dataset, labels_paths.front(), canonical, options);
  refuse_part_folders(dataset);
  // Several files: each labels the instance its `source` names; the canonical is `canonical` or the first's.
  std::vector<std::string> names;
  std::set<std::filesystem::path> seen;
  std::map<std::string, std::filesystem::path> labelled;
  std::string first;
  for (const std::filesystem::path& path : labels_paths) {
    if (!seen.insert(std::filesystem::weakly_canonical(path)).second) continue;
    const PartLabels labels = read_labels_file(path);
    const std::string instance = std::filesystem::path(labels.source).stem().string();
    if (names.empty()) names = labels.names, first = instance;
    if (labels.names != names)
      throw InputError("labels file " + path.string() + " names other parts than " +
                       labelled[first].string() + " (every labels file must name the same parts)");
    if (!labelled.emplace(instance, path).second)
      throw UsageError("labels files " + labelled[instance].string() + " and " + path.string() +
                       " both label '" + instance + "'");
    apply_labels(dataset, labels, path, instance, options);
  }
  if (canonical.empty()) return first;
  if (labelled.count(canonical) == 0)
    throw UsageError("the canonical '" + canonical + "' is none of the labelled instances");
  return canonical;
}

}  // namespace partreg::io
