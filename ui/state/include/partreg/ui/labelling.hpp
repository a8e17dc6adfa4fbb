#pragma once
/// \file
/// Editing the part labels of a canonical mesh: parts (create, rename, recolour, merge, delete), the surface
/// brush, the connected fill, the geometric selectors and undo/redo. Every edit pushes an undo snapshot and
/// marks the document dirty; a failing edit throws before changing anything.

#include <string>
#include <vector>

#include "partreg/core/geometry/part_selection.hpp"
#include "partreg/ui/app_state.hpp"

namespace partreg::ui {

/// Reads a mesh and starts its labels with every face unlabelled. InputError for a file that fails.
LabelDocument load_label_document(const std::string& mesh_path);

/// Reads a labels file for the document's mesh: InputError when it labels points or another face count.
void load_labels(LabelDocument& document, const std::string& labels_path);

/// The index of part `name`; UsageError listing the parts when there is none.
int find_part(const LabelDocument& document, const std::string& name);

void create_part(LabelDocument& document, const std::string& name);  ///< and makes it current
void rename_part(LabelDocument& document, const std::string& name, const std::string& new_name);
void recolor_part(LabelDocument& document, const std::string& name, int red, int green, int blue);
/// Relabels `from`'s faces as `into` and removes `from`.
void merge_parts(LabelDocument& document, const std::string& from, const std::string& into);
/// Removes a part; its faces become unlabelled.
void delete_part(LabelDocument& document, const std::string& name);

/// Faces whose centroid lies within `radius` (scene units) of `centre` that are connected to `seed_face`
/// through such faces get the current part. Returns how many changed.
int paint_faces(LabelDocument& document, int seed_face, const Eigen::Vector3d& centre, double radius);
/// The faces connected (through shared edges) to `seed_face` that carry its label get the current part.
int fill_faces(LabelDocument& document, int seed_face);
/// Faces whose centroid the selector holds get the current part.
int select_faces(LabelDocument& document, const core::PartSelector& selector);

bool undo(LabelDocument& document);  ///< false when there is nothing to undo
bool redo(LabelDocument& document);

/// Writes the labels file (atomically) and clears the dirty flag.
void save_labels(LabelDocument& document, const std::string& path);

/// Faces per part (index -> count) and unlabelled faces at the end.
std::vector<int> part_face_counts(const LabelDocument& document);

}  // namespace partreg::ui
