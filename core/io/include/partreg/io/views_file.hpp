#pragma once
/// \file
/// `views.json`, the listing `partreg views` writes beside its clouds: each view's file name, direction and
/// viewpoint (data units). Readers use it to know where the camera stood for a view's cloud.

#include <Eigen/Core>
#include <filesystem>
#include <optional>

namespace partreg::io {

/// The viewpoint of the cloud file `cloud` from the views.json beside it; nullopt when there is no listing,
/// it does not list the file, or it is not a partreg listing (then the observation simply has no known
/// viewpoint). A viewpoint that is not a finite point of sensible size (|x| <= 1e12) is not used either.
std::optional<Eigen::Vector3d> viewpoint_from_listing(const std::filesystem::path& cloud);

/// The viewpoint of `file_name` in listing text `text` (views.json's content), as above.
std::optional<Eigen::Vector3d> viewpoint_in_listing(const std::string& text, const std::string& file_name);

}  // namespace partreg::io
