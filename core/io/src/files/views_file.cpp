#include "partreg/io/views_file.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

namespace partreg::io {

std::optional<Eigen::Vector3d> viewpoint_in_listing(const std::string& text, const std::string& file_name) {
  const nlohmann::json listing = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (listing.is_discarded() || !listing.is_object() || !listing.contains("views") || !listing.at("views").is_array())
    return std::nullopt;
  for (const nlohmann::json& view : listing.at("views")) {
    if (!view.is_object() || !view.contains("file") || view.at("file") != file_name) continue;
    if (!view.contains("viewpoint") || !view.at("viewpoint").is_array() || view.at("viewpoint").size() != 3)
      return std::nullopt;
    Eigen::Vector3d viewpoint;
    for (int i = 0; i < 3; ++i) {
      const nlohmann::json& value = view.at("viewpoint").at(static_cast<std::size_t>(i));
      if (!value.is_number()) return std::nullopt;
      viewpoint[i] = value.get<double>();
    }
    if (!viewpoint.allFinite() || viewpoint.cwiseAbs().maxCoeff() > 1e12) return std::nullopt;
    return viewpoint;
  }
  return std::nullopt;
}

std::optional<Eigen::Vector3d> viewpoint_from_listing(const std::filesystem::path& cloud) {
  const std::filesystem::path listing = cloud.parent_path() / "views.json";
  std::error_code error;
  if (!std::filesystem::is_regular_file(listing, error) || std::filesystem::file_size(listing, error) > (64u << 20))
    return std::nullopt;
  std::ifstream in(listing);
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  return viewpoint_in_listing(text, cloud.filename().string());
}

}  // namespace partreg::io
