#pragma once
/// \file
/// The one place that decides an output's format: from its extension, for what is written (a cloud, a mesh,
/// JSON, an image, a model). A name that promises a format partreg does not write is a usage error, found
/// before any work: commands call check_output() on every output path first.
///
/// | kind  | extensions                                         | default for "-", a device or a FIFO |
/// |-------|----------------------------------------------------|-------------------------------------|
/// | cloud | .ply (binary), .pcd (binary, PCL), .vtp (VTK), .xyz | PLY                                |
/// | mesh  | .obj, .ply (ascii), .vtp (VTK)                      | OBJ                                |
/// | json  | .json                                               | JSON                               |
/// | image | .png                                                | PNG                                |
/// | model | .prm                                                | model                              |

#include <filesystem>
#include <string>
#include <vector>

namespace partreg::io {

enum class OutputKind { cloud, mesh, json, image, model };
enum class FileFormat { ply, pcd, vtp, xyz, obj, json, png, prm };

/// The format `path` is written in for `kind`. A path without an extension is allowed only for "-", a
/// device or a FIFO (they get the kind's default). UsageError naming `option` (e.g. "--points-out") and the
/// extensions allowed otherwise.
FileFormat output_format(const std::filesystem::path& path, OutputKind kind, const std::string& option = "output");

/// Checks one output before any work: its format (UsageError) and that it can be written (its folder
/// exists, it is not a folder: InputError). Empty paths (an output not asked for) pass.
void check_output(const std::string& path, OutputKind kind, const std::string& option);

/// One output of a command: its option ("--json") and path ("" when not asked for).
struct NamedOutput {
  std::string option;
  std::string path;
};

/// UsageError naming both options when two outputs of one command lead to the same file (after "-" and
/// /dev/stdout, "..", and symbolic links): one would overwrite or interleave the other. /dev/null and other
/// devices that discard may be named twice.
void check_distinct_outputs(const std::vector<NamedOutput>& outputs);

/// The name of a format for messages ("PLY", "PCD", ...).
std::string to_string(FileFormat format);

}  // namespace partreg::io
