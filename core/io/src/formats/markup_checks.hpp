#pragma once
// Checks of glTF/GLB and .vtp files before assimp or VTK parses them (internal to partreg_io). Both libraries
// parse recursively and trust the sizes a file states: a glTF of 200,000 nested brackets, a node chain
// 30,000 deep, GLB chunk lengths beyond the file or a .vtp of 200,000 nested tags crashed them, and huge
// declared counts made them allocate gigabytes. Each check refuses such a file with one line naming it.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace partreg::io::detail {

/// InputError naming `file` when JSON arrays and objects in `text` nest deeper than the budget
/// (brackets inside strings do not count).
void check_json_nesting(std::string_view text, const std::string& file);

/// A .gltf or .glb file (`size` bytes, already checked against the budget): GLB header and chunk lengths
/// within the file, the JSON's nesting within the budget, and a node hierarchy that is a forest (no node
/// with two parents, no cycle) at most 256 levels deep.
void check_gltf(const std::filesystem::path& path, std::uint64_t size);

/// A .vtp file: XML elements nested within the budget (up to the appended data, which is not XML), and
/// the counts its tags declare (points, cells, tuples, components) within the budget.
void check_vtp(const std::filesystem::path& path);

}  // namespace partreg::io::detail
