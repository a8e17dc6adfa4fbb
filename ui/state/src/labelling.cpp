#include "partreg/ui/labelling.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <utility>

#include "partreg/core/errors.hpp"
#include "partreg/io/mesh_io.hpp"

namespace partreg::ui {
namespace {

// Keeps undo snapshots bounded: 64 label vectors of a 100k-face mesh are about 25 MB.
constexpr std::size_t kMaxUndo = 64;

void push_undo(LabelDocument& document) {
  document.undo_stack.push_back(document.labels);
  if (document.undo_stack.size() > kMaxUndo) document.undo_stack.erase(document.undo_stack.begin());
  document.redo_stack.clear();
  document.dirty = true;
}

int current_part_or_throw(const LabelDocument& document) {
  if (!document.loaded()) throw UsageError("no mesh is loaded to label (load MESH first)");
  if (document.current_part < 0 || document.current_part >= static_cast<int>(document.labels.names.size()))
    throw UsageError("no part is selected (create_part NAME or select_part NAME first)");
  return document.current_part;
}

Eigen::Vector3d centroid(const core::Mesh& mesh, Eigen::Index face) {
  return (mesh.vertices.row(mesh.faces(face, 0)) + mesh.vertices.row(mesh.faces(face, 1)) +
          mesh.vertices.row(mesh.faces(face, 2)))
             .transpose() /
         3.0;
}

FaceAdjacency face_adjacency(const core::Mesh& mesh) {
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int corner = 0; corner < 3; ++corner) {
      const int a = mesh.faces(f, corner), b = mesh.faces(f, (corner + 1) % 3);
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  std::vector<std::vector<int>> lists(static_cast<std::size_t>(mesh.faces.rows()));
  for (const auto& [edge, faces] : edge_faces)
    for (const int f : faces)
      for (const int g : faces)
        if (f != g) lists[static_cast<std::size_t>(f)].push_back(g);
  FaceAdjacency adjacency;
  adjacency.start.push_back(0);
  for (const auto& list : lists) {
    adjacency.neighbours.insert(adjacency.neighbours.end(), list.begin(), list.end());
    adjacency.start.push_back(static_cast<int>(adjacency.neighbours.size()));
  }
  return adjacency;
}

// Faces reachable from `seed` through faces for which `accept` holds (the seed must hold it too).
template <typename Accept>
std::vector<int> flood(LabelDocument& document, int seed, Accept accept) {
  const core::Mesh& mesh = document.mesh;
  if (!document.adjacency) document.adjacency = std::make_shared<const FaceAdjacency>(face_adjacency(mesh));
  const FaceAdjacency& adjacency = *document.adjacency;
  std::vector<char> seen(static_cast<std::size_t>(mesh.faces.rows()), 0);
  std::vector<int> reached, stack{seed};
  seen[static_cast<std::size_t>(seed)] = 1;
  while (!stack.empty()) {
    const int face = stack.back();
    stack.pop_back();
    reached.push_back(face);
    for (int k = adjacency.start[face]; k < adjacency.start[face + 1]; ++k) {
      const int next = adjacency.neighbours[static_cast<std::size_t>(k)];
      if (seen[static_cast<std::size_t>(next)] || !accept(next)) continue;
      seen[static_cast<std::size_t>(next)] = 1;
      stack.push_back(next);
    }
  }
  return reached;
}

int assign(LabelDocument& document, const std::vector<int>& faces) {
  const int part = current_part_or_throw(document);
  const int changed = static_cast<int>(
      std::count_if(faces.begin(), faces.end(), [&](int f) { return document.labels.labels[f] != part; }));
  if (changed == 0) return 0;
  push_undo(document);
  for (const int f : faces) document.labels.labels[f] = part;
  return changed;
}

// Drops part `part`: its faces become unlabelled and higher indices move down by one.
void remove_part(LabelDocument& document, int part) {
  io::PartLabels& labels = document.labels;
  for (Eigen::Index f = 0; f < labels.labels.size(); ++f) {
    if (labels.labels[f] == part)
      labels.labels[f] = -1;
    else if (labels.labels[f] > part)
      --labels.labels[f];
  }
  labels.names.erase(labels.names.begin() + part);
  labels.colors.erase(labels.colors.begin() + part);
  if (document.current_part == part)
    document.current_part = labels.names.empty() ? -1 : 0;
  else if (document.current_part > part)
    --document.current_part;
}

void check_seed(const LabelDocument& document, int seed_face) {
  if (seed_face < 0 || seed_face >= document.mesh.faces.rows()) throw UsageError("no face under the brush");
}

}  // namespace

LabelDocument load_label_document(const std::string& mesh_path) {
  LabelDocument document;
  document.mesh = io::read_mesh(mesh_path);
  document.mesh_path = mesh_path;
  document.labels.source = std::filesystem::path(mesh_path).filename().string();
  document.labels.labels = Eigen::VectorXi::Constant(document.mesh.faces.rows(), -1);
  return document;
}

void load_labels(LabelDocument& document, const std::string& labels_path) {
  if (!document.loaded()) throw UsageError("load a mesh before its labels");
  io::PartLabels labels = io::read_labels_file(labels_path);
  if (labels.target != io::PartLabels::Target::faces)
    throw InputError(labels_path + " labels points, not mesh faces");
  io::check_labels_match(labels, static_cast<std::size_t>(document.mesh.faces.rows()),
                         "faces in " + document.mesh_path);
  push_undo(document);
  document.labels = std::move(labels);
  document.current_part = document.labels.names.empty() ? -1 : 0;
  document.dirty = false;
}

int find_part(const LabelDocument& document, const std::string& name) {
  const auto& names = document.labels.names;
  const auto found = std::find(names.begin(), names.end(), name);
  if (found != names.end()) return static_cast<int>(found - names.begin());
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw UsageError("no part '" + name + "' (parts: " + (known.empty() ? "none" : known) + ")");
}

void create_part(LabelDocument& document, const std::string& name) {
  if (!document.loaded()) throw UsageError("no mesh is loaded to label (load MESH first)");
  const auto& names = document.labels.names;
  if (std::find(names.begin(), names.end(), name) != names.end())
    throw UsageError("there is already a part '" + name + "'");
  push_undo(document);
  document.current_part = document.labels.part_index(name);
}

void rename_part(LabelDocument& document, const std::string& name, const std::string& new_name) {
  const int part = find_part(document, name);
  const auto& names = document.labels.names;
  if (std::find(names.begin(), names.end(), new_name) != names.end())
    throw UsageError("there is already a part '" + new_name + "'");
  push_undo(document);
  document.labels.names[static_cast<std::size_t>(part)] = new_name;
}

void recolor_part(LabelDocument& document, const std::string& name, int red, int green, int blue) {
  const int part = find_part(document, name);
  for (const int c : {red, green, blue})
    if (c < 0 || c > 255) throw UsageError("colour channels are 0 to 255");
  push_undo(document);
  document.labels.colors[static_cast<std::size_t>(part)] = {
      static_cast<std::uint8_t>(red), static_cast<std::uint8_t>(green), static_cast<std::uint8_t>(blue)};
}

void merge_parts(LabelDocument& document, const std::string& from, const std::string& into) {
  const int source = find_part(document, from), target = find_part(document, into);
  if (source == target) throw UsageError("cannot merge a part into itself");
  push_undo(document);
  for (Eigen::Index f = 0; f < document.labels.labels.size(); ++f)
    if (document.labels.labels[f] == source) document.labels.labels[f] = target;
  remove_part(document, source);
}

void delete_part(LabelDocument& document, const std::string& name) {
  const int part = find_part(document, name);
  push_undo(document);
  remove_part(document, part);
}

int paint_faces(LabelDocument& document, int seed_face, const Eigen::Vector3d& centre, double radius) {
  current_part_or_throw(document);
  check_seed(document, seed_face);
  const double radius2 = radius * radius;
  // Connected to the picked face, so the brush never jumps through thin walls to the other side.
  const std::vector<int> faces = flood(document, seed_face, [&](int f) {
    return (centroid(document.mesh, f) - centre).squaredNorm() <= radius2;
  });
  return assign(document, faces);
}

int fill_faces(LabelDocument& document, int seed_face) {
  current_part_or_throw(document);
  check_seed(document, seed_face);
  const int seed_label = document.labels.labels[seed_face];
  const std::vector<int> faces =
      flood(document, seed_face, [&](int f) { return document.labels.labels[f] == seed_label; });
  return assign(document, faces);
}

int select_faces(LabelDocument& document, const core::PartSelector& selector) {
  current_part_or_throw(document);
  const std::vector<bool> selected = core::select_faces(document.mesh, selector);
  std::vector<int> faces;
  for (std::size_t f = 0; f < selected.size(); ++f)
    if (selected[f]) faces.push_back(static_cast<int>(f));
  if (faces.empty()) throw InputError("the selector holds no face of " + document.mesh_path);
  return assign(document, faces);
}

bool undo(LabelDocument& document) {
  if (document.undo_stack.empty()) return false;
  document.redo_stack.push_back(std::move(document.labels));
  document.labels = std::move(document.undo_stack.back());
  document.undo_stack.pop_back();
  document.current_part = std::min(document.current_part, static_cast<int>(document.labels.names.size()) - 1);
  document.dirty = true;
  return true;
}

bool redo(LabelDocument& document) {
  if (document.redo_stack.empty()) return false;
  document.undo_stack.push_back(std::move(document.labels));
  document.labels = std::move(document.redo_stack.back());
  document.redo_stack.pop_back();
  document.current_part = std::min(document.current_part, static_cast<int>(document.labels.names.size()) - 1);
  document.dirty = true;
  return true;
}

void save_labels(LabelDocument& document, const std::string& path) {
  if (!document.loaded()) throw UsageError("no labels to save (load MESH first)");
  io::write_labels_file(path, document.labels);
  document.dirty = false;
}

std::vector<int> part_face_counts(const LabelDocument& document) {
  std::vector<int> counts(document.labels.names.size() + 1, 0);
  for (Eigen::Index f = 0; f < document.labels.labels.size(); ++f) {
    const int label = document.labels.labels[f];
    ++counts[label < 0 ? counts.size() - 1 : static_cast<std::size_t>(label)];
  }
  return counts;
}

}  // namespace partreg::ui
