#pragma once
// PLY header parsing shared by the cloud reader and the mesh-or-cloud test (internal to partreg_io).

#include <cstdint>
#include <filesystem>
#include <istream>
#include <string>
#include <vector>

namespace partreg::io::detail {

struct PlyProperty {
  std::string name;
  std::string type;  ///< scalar type, normalised to char/uchar/short/ushort/int/uint/float/double
  bool is_list = false;
  std::string count_type;  ///< type of a list's length (lists only)
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  enum class Format { ascii, binary_little_endian, binary_big_endian } format = Format::ascii;
  std::vector<PlyElement> elements;
  std::vector<std::string> comments;  ///< the text after "comment ", in order
  std::size_t count_of(const std::string& element) const;
};

/// Part names in a PLY header, one comment line each: "comment part_name INDEX NAME" (a name may hold
/// spaces). What partreg writes for an int `part` property, so that a file carries its parts by name.
std::string part_name_comments(const std::vector<std::string>& part_names);

/// The part names of such comments, by index (an index without a comment gets an empty name); empty when
/// there are none.
std::vector<std::string> part_names_from_comments(const std::vector<std::string>& comments);

/// Parses the header and leaves `in` at the first byte of the data. Throws InputError naming `file` for a
/// malformed header, one without end_header, or counts beyond the reading budget (read_limits.hpp).
PlyHeader read_ply_header(std::istream& in, const std::string& file);

/// Checks that the elements the header declares can fit into the `available` bytes after it (each value
/// takes at least its binary size, or two characters in ASCII). InputError naming `file` otherwise.
void check_ply_body_fits(const PlyHeader& header, std::uint64_t available, const std::string& file);

/// Reads the header from `in` (a file of `file_size` bytes) and checks its counts against that size; leaves
/// `in` at the first byte of the data.
PlyHeader read_checked_ply_header(std::istream& in, std::uint64_t file_size, const std::string& file);

/// A mesh's header (before assimp reads the file): a vertex element with scalar x, y and z.
void check_ply_mesh_header(const PlyHeader& header, const std::string& file);

/// Everything partreg checks in a PLY mesh before assimp reads it: the header's counts against the file's
/// size, its vertex properties, and its face lists (check_ply_face_lists).
void check_ply_mesh(const std::filesystem::path& path);

/// Walks the data after the header (`in` at its first byte) up to the end of the face element and checks
/// that every face lists at least 3 vertices: assimp's triangulation aborts on faces of 0 vertices.
/// InputError naming `file` and the face otherwise, or where the data ends early.
void check_ply_face_lists(std::istream& in, const PlyHeader& header, const std::string& file);

/// Reads the header of the PLY file `path` and checks its counts against the file's size.
PlyHeader read_checked_ply_header(const std::filesystem::path& path);

/// Size in bytes of a PLY scalar type.
std::size_t ply_type_size(const std::string& type);

}  // namespace partreg::io::detail
