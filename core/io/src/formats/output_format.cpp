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

namespace {

// Where an output's bytes really go, as one comparable name ("" for a device that discards them).
std::string destination_of(const std::string& path) {
  namespace fs = std::filesystem;
  if (path == "-" || path == "/dev/stdout") return "<stdout>";
  const fs::path target = resolve_output(path).path;
  std::error_code error;
  if (fs::is_character_file(fs::status(target, error)) && target == "/dev/null") return "";
  const fs::path canonical = fs::weakly_canonical(fs::absolute(target, error), error);
  return (canonical.empty() ? target : canonical).string();
}

}  // namespace

void check_distinct_outputs(const std::vector<NamedOutput>& outputs) {
  std::map<std::string, std::string> option_of;  // destination -> the first option naming it
  for (const NamedOutput& output : outputs) {
    if (output.path.empty()) continue;
    const std::string destination = destination_of(output.path);
    if (destination.empty()) continue;
    const auto [seen, inserted] = option_of.emplace(destination, output.option);
    if (!inserted)
      throw UsageError(seen->second + " and " + output.option + " name the same output (" + output.path +
                       "): give each its own");
  }
}

}  // namespace partreg::io
