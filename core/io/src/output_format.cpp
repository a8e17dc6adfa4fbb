#include "partreg/io/output_format.hpp"

#include <map>
#include <vector>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"

namespace partreg::io {
namespace {

struct KindFormats {
  const char* what;
  std::vector<std::pair<std::string, FileFormat>> extensions;  // the first one is the default
};

const KindFormats& formats_of(OutputKind kind) {
  static const std::map<OutputKind, KindFormats> table = {
      {OutputKind::cloud,
       {"point cloud",
        {{".ply", FileFormat::ply}, {".pcd", FileFormat::pcd}, {".vtp", FileFormat::vtp}, {".xyz", FileFormat::xyz}}}},
      {OutputKind::mesh, {"mesh", {{".obj", FileFormat::obj}, {".ply", FileFormat::ply}, {".vtp", FileFormat::vtp}}}},
      {OutputKind::json, {"JSON", {{".json", FileFormat::json}}}},
      {OutputKind::image, {"image", {{".png", FileFormat::png}}}},
      {OutputKind::model, {"model", {{".prm", FileFormat::prm}}}}};
  return table.at(kind);
}

}  // namespace

std::string to_string(FileFormat format) {
  switch (format) {
    case FileFormat::ply: return "PLY";
    case FileFormat::pcd: return "PCD";
    case FileFormat::vtp: return "VTK PolyData (.vtp)";
    case FileFormat::xyz: return "XYZ text";
    case FileFormat::obj: return "OBJ";
    case FileFormat::json: return "JSON";
    case FileFormat::png: return "PNG";
    case FileFormat::prm: return "partreg model";
  }
  return "?";
}

FileFormat output_format(const std::filesystem::path& path, OutputKind kind, const std::string& option) {
  const KindFormats& formats = formats_of(kind);
  const std::string extension = lower_extension(path);
  for (const auto& [known, format] : formats.extensions)
    if (extension == known) return format;
  if (extension.empty()) {
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    const bool stream_like = path == "-" || std::filesystem::is_character_file(status) ||
                             std::filesystem::is_fifo(status) || std::filesystem::is_block_file(status);
    if (stream_like) return formats.extensions.front().second;
  }
  std::string allowed;
  for (const auto& entry : formats.extensions) allowed += (allowed.empty() ? "" : ", ") + entry.first;
  throw UsageError(option + " " + path.string() + ": " +
                   (extension.empty() ? std::string("no extension") : "'" + extension + "'") + " does not name a " +
                   formats.what + " format partreg writes (use " + allowed + ")");
}

void check_output(const std::string& path, OutputKind kind, const std::string& option) {
  if (path.empty()) return;
  output_format(path, kind, option);
  resolve_output(path);
}

}  // namespace partreg::io
