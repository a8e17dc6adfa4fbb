#include "partreg/io/frames_file.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::io {

std::vector<core::Frame> read_frames_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  checked_input_size(path, kReadBudget.max_document_bytes);  // a regular file (not a FIFO) within the budget
  std::ifstream in(path);
  if (!in) throw InputError("cannot open frames file " + file);
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded() || !json.is_object() || !json.contains("format") || json.at("format") != "partreg-frames")
    throw InputError(file + " is not a partreg frames file");
  if (!json.contains("version") || json.at("version") != 1)
    throw InputError(file + ": unsupported frames file version");
  std::vector<core::Frame> frames;
  try {
    if (json.at("frames").size() > kMaxFrames)
      throw InputError(file + " holds " + std::to_string(json.at("frames").size()) +
                       " frames, more than partreg reads (" + std::to_string(kMaxFrames) + ")");
    for (const auto& entry : json.at("frames")) {
      core::Frame frame;
      frame.name = entry.contains("name") ? entry.at("name").get<std::string>() : "frame " + std::to_string(frames.size());
      for (int i = 0; i < 3; ++i) {
        frame.position[i] = entry.at("position").at(i).get<double>();
        for (int j = 0; j < 3; ++j) frame.rotation(i, j) = entry.at("rotation").at(i).at(j).get<double>();
      }
      // 1e308 is finite but overflows the first transform into infinity (written as JSON null).
      if (!frame.position.allFinite() || frame.position.cwiseAbs().maxCoeff() > 1e12)
        throw InputError(file + ": the position of frame '" + frame.name + "' is not a finite number of "
                         "sensible size (|x| <= 1e12)");
      const double error = (frame.rotation.transpose() * frame.rotation - Eigen::Matrix3d::Identity()).norm();
      if (!(error < 1e-6) || frame.rotation.determinant() < 0.0)
        throw InputError(file + ": the rotation of frame '" + frame.name +
                         "' is not a proper orthonormal matrix");
      frames.push_back(frame);
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + " is a malformed frames file: " + e.what());
  }
  return frames;
}

void write_frames_file(const std::filesystem::path& path, const std::vector<core::Frame>& frames) {
  nlohmann::json list = nlohmann::json::array();
  for (const core::Frame& frame : frames) {
    nlohmann::json rotation = nlohmann::json::array();
    for (int i = 0; i < 3; ++i)
      rotation.push_back({frame.rotation(i, 0), frame.rotation(i, 1), frame.rotation(i, 2)});
    list.push_back({{"name", frame.name},
                    {"position", {frame.position.x(), frame.position.y(), frame.position.z()}},
                    {"rotation", rotation}});
  }
  const nlohmann::json json = {{"format", "partreg-frames"}, {"version", 1}, {"frames", list}};
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary);
    out << json.dump(2) << '\n';
    if (!out.flush()) throw InputError("cannot write " + path.string());
  });
}

}  // namespace partreg::io
