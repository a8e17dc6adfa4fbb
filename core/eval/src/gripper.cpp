// The gripper test, grasp sampling and re-seating (gripper.hpp): fingers closed by rays cast with Embree.
#include "partreg/eval/gripper.hpp"

#include "embree_mesh.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <cmath>
#include <limits>
#include <random>

#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"

namespace partreg::eval {
namespace {

// Pad rays: the pad's centre and the middles of its four sides, in units of half the pad (y, z).
constexpr double kPadRays[5][2] = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};
// Approaches tried around a sampled closing axis before the pair is given up.
constexpr int kApproachTries = 8;
// A re-seat turns the closing axis to the contacts' mean normal only when that is this close to the carried
// axis: a larger turn means the fingers met other surfaces than the grasp was made for.
constexpr double kLargestReseatTurnDegrees = 30.0;
// Observed points under a pad that move a re-seated contact: fewer are too few to tell noise from surface.
constexpr int kLeastObservedPerPad = 3;

double degrees(double radians) { return radians * 180.0 / M_PI; }

double cone_degrees(const core::Gripper& gripper) { return degrees(std::atan(gripper.friction)); }

}  // namespace

struct MeshRays::Scene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  core::Mesh mesh;
  ~Scene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

MeshRays::MeshRays(const core::Mesh& mesh) : scene_(std::make_unique<Scene>()) {
  if (mesh.faces.rows() == 0) throw InputError("the gripper test needs a mesh with faces");
  if (!mesh.vertices.allFinite()) throw InputError("the gripper test's mesh has non-finite vertices");
  if (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.vertices.rows())
    throw InputError("the gripper test's mesh has faces that name missing vertices");
  scene_->mesh = mesh;
  const std::string config = "threads=" + std::to_string(core::thread_budget());
  scene_->device = rtcNewDevice(config.c_str());
  if (!scene_->device) throw std::runtime_error("Embree could not create a device");
  scene_->scene = rtcNewScene(scene_->device);
  RTCGeometry geometry = detail::triangle_geometry(scene_->device, mesh);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_->scene);
  if (rtcGetDeviceError(scene_->device) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree failed while building the gripper test's scene");
}

MeshRays::~MeshRays() = default;
MeshRays::MeshRays(MeshRays&&) noexcept = default;
MeshRays& MeshRays::operator=(MeshRays&&) noexcept = default;

const core::Mesh& MeshRays::mesh() const { return scene_->mesh; }

std::optional<MeshRays::Hit> MeshRays::first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                                 double max_distance) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit hit{};
  hit.ray.org_x = float(origin.x()), hit.ray.org_y = float(origin.y()), hit.ray.org_z = float(origin.z());
  hit.ray.dir_x = float(direction.x()), hit.ray.dir_y = float(direction.y()), hit.ray.dir_z = float(direction.z());
  hit.ray.tnear = 0.0f;
  hit.ray.tfar = float(max_distance);
  hit.ray.mask = ~0u;
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_->scene, &context, &hit);
  if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  Eigen::Vector3d normal(hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z);
  if (!(normal.norm() > 0.0)) return std::nullopt;  // a degenerate triangle: no surface to push on
  normal.normalize();
  if (normal.dot(direction) > 0.0) normal = -normal;  // meshes of either winding: the side the ray meets
  return Hit{double(hit.ray.tfar), normal};
}

GraspCheck check_grasp(const MeshRays& object, const core::Grasp& grasp, const core::Gripper& gripper) {
  core::validate(gripper);
  GraspCheck check;
  const Eigen::Vector3d x = grasp.closing_axis(), y = grasp.rotation.col(1), z = grasp.approach_axis();
  const double half = 0.5 * gripper.max_aperture, pad = 0.5 * gripper.pad_size;
  double travel[2] = {0.0, 0.0};
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? -1.0 : 1.0;
    const Eigen::Vector3d start = grasp.position + sign * half * x, inward = -sign * x;
    // A finger travels at most the whole aperture; the pad stops at its first touch.
    for (const auto& offset : kPadRays) {
      const Eigen::Vector3d origin = start + pad * (offset[0] * y + offset[1] * z);
      const auto hit = object.first_hit(origin, inward, gripper.max_aperture);
      if (!hit || (check.touched[side] && hit->distance >= travel[side])) continue;
      check.touched[side] = true;
      travel[side] = hit->distance;
      check.contacts[side] = origin + hit->distance * inward;
      check.normals[side] = hit->normal;
      check.angles_degrees[side] = degrees(std::acos(std::clamp(hit->normal.dot(-inward), -1.0, 1.0)));
    }
    // The finger's body trails its pad back along the approach: object there is met on the way in.
    if (object.first_hit(start, -z, gripper.finger_depth)) check.collides = true;
  }
  check.width = gripper.max_aperture - travel[0] - travel[1];
  const double cone = cone_degrees(gripper);
  if (!check.touched[0] || !check.touched[1])
    check.reason = "a finger closes on nothing";
  else if (!(check.width > 0.0))
    check.reason = "the fingers pass each other";
  else if (check.collides)
    check.reason = "a finger meets the object on its way in";
  else if (std::max(check.angles_degrees[0], check.angles_degrees[1]) > cone)
    check.reason = "a contact slips: its normal is " +
                   std::to_string(int(std::round(std::max(check.angles_degrees[0], check.angles_degrees[1])))) +
                   " degrees off the closing axis (friction cone " + std::to_string(int(std::round(cone))) + ")";
  check.holds = check.reason.empty();
  return check;
}

double grasp_quality(const GraspCheck& check, const core::Gripper& gripper) {
  if (!check.holds) return 0.0;
  const double cone = cone_degrees(gripper);
  if (!(cone > 0.0)) return 1.0;  // a frictionless gripper holds only exact antipodal pairs
  return std::clamp(1.0 - std::max(check.angles_degrees[0], check.angles_degrees[1]) / cone, 0.0, 1.0);
}

namespace {

// A surface point drawn by area (on allowed faces) with its face's unit normal.
struct SurfaceSample {
  Eigen::Vector3d point, normal;
};

class AreaSampler {
 public:
  AreaSampler(const core::Mesh& mesh, const std::vector<bool>& allowed) : mesh_(mesh) {
    std::vector<double> areas(static_cast<std::size_t>(mesh.faces.rows()), 0.0);
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
      if (allowed.empty() || allowed[static_cast<std::size_t>(f)]) areas[static_cast<std::size_t>(f)] = area(f);
    if (std::accumulate(areas.begin(), areas.end(), 0.0) <= 0.0)
      throw InputError("no surface to sample grasps on (no allowed face has an area)");
    faces_ = std::discrete_distribution<Eigen::Index>(areas.begin(), areas.end());
  }
  SurfaceSample draw(std::mt19937_64& random) {
    const Eigen::Index f = faces_(random);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double a = unit(random), b = unit(random);
    if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
    const Eigen::Vector3d p0 = vertex(f, 0), p1 = vertex(f, 1), p2 = vertex(f, 2);
    return {p0 + a * (p1 - p0) + b * (p2 - p0), (p1 - p0).cross(p2 - p0).normalized()};
  }

 private:
  Eigen::Vector3d vertex(Eigen::Index f, int k) const { return mesh_.vertices.row(mesh_.faces(f, k)).transpose(); }
  double area(Eigen::Index f) const { return 0.5 * (vertex(f, 1) - vertex(f, 0)).cross(vertex(f, 2) - vertex(f, 0)).norm(); }
  const core::Mesh& mesh_;
  std::discrete_distribution<Eigen::Index> faces_;
};

// The first antipodal partner of `sample` along its normal, either way, within the aperture.
std::optional<Eigen::Vector3d> antipodal_partner(const MeshRays& rays, const SurfaceSample& sample,
                                                 const core::Gripper& gripper, double nudge) {
  const double cos_cone = std::cos(std::atan(gripper.friction));
  for (const double sign : {-1.0, 1.0}) {
    const Eigen::Vector3d direction = sign * sample.normal;
    const auto hit = rays.first_hit(sample.point + nudge * direction, direction, gripper.max_aperture);
    if (hit && std::abs(hit->normal.dot(direction)) >= cos_cone)
      return Eigen::Vector3d(sample.point + (nudge + hit->distance) * direction);
  }
  return std::nullopt;
}

bool near_a_kept_grasp(const std::vector<core::Grasp>& kept, const core::Grasp& grasp, double distance) {
  for (const core::Grasp& other : kept)
    if ((other.position - grasp.position).norm() < distance &&
        std::abs(other.closing_axis().dot(grasp.closing_axis())) > std::cos(M_PI / 12.0))
      return true;
  return false;
}

void rank(std::vector<core::Grasp>& grasps) {
  std::stable_sort(grasps.begin(), grasps.end(),
                   [](const core::Grasp& a, const core::Grasp& b) { return a.quality > b.quality; });
}

}  // namespace

std::vector<core::Grasp> sample_grasps(const core::Mesh& mesh, const core::Gripper& gripper, int count,
                                       std::uint64_t seed, const std::vector<bool>& allowed) {
  core::validate(gripper);
  if (count < 1) throw UsageError("the grasp count must be at least 1");
  if (!allowed.empty() && allowed.size() != static_cast<std::size_t>(mesh.faces.rows()))
    throw UsageError("the allowed faces must be one flag per face");
  const MeshRays rays(mesh);
  AreaSampler sampler(mesh, allowed);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> turn(0.0, 2.0 * M_PI);
  const double diagonal = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
  const double nudge = 1e-6 * diagonal;  // off the surface the ray starts on
  std::vector<core::Grasp> kept;
  for (long tries = 0; tries < 200L * count && static_cast<int>(kept.size()) < count; ++tries) {
    const SurfaceSample sample = sampler.draw(random);
    const auto partner = antipodal_partner(rays, sample, gripper, nudge);
    if (!partner) continue;
    const Eigen::Vector3d closing = *partner - sample.point;
    const Eigen::Vector3d u = closing.normalized().unitOrthogonal(), v = closing.normalized().cross(u);
    const double first = turn(random);
    for (int a = 0; a < kApproachTries; ++a) {
      const double angle = first + 2.0 * M_PI * a / kApproachTries;
      core::Grasp grasp;
      grasp.position = 0.5 * (sample.point + *partner);
      grasp.rotation = core::grasp_axes(closing, std::cos(angle) * u + std::sin(angle) * v);
      const GraspCheck check = check_grasp(rays, grasp, gripper);
      if (!check.holds) continue;
      // Centred between the contacts along the closing axis; across it the pads stay where they touched.
      const Eigen::Vector3d middle = 0.5 * (check.contacts[0] + check.contacts[1]);
      grasp.position += (middle - grasp.position).dot(grasp.closing_axis()) * grasp.closing_axis();
      grasp.width = check.width;
      grasp.quality = grasp_quality(check, gripper);
      if (!near_a_kept_grasp(kept, grasp, 0.5 * gripper.pad_size)) kept.push_back(grasp);
      break;
    }
  }
  rank(kept);
  for (std::size_t g = 0; g < kept.size(); ++g) kept[g].name = "grasp_" + std::to_string(g);
  return kept;
}

namespace {

// Where the observed points under each pad put the contacts, as offsets along the closing axis from the
// grasp's origin (negative side first); unset where fewer than kLeastObservedPerPad lie under a pad.
std::array<std::optional<double>, 2> observed_contacts(const core::Points& observed, const core::Grasp& grasp,
                                                       const core::Gripper& gripper) {
  const Eigen::Vector3d x = grasp.closing_axis();
  const double half = 0.5 * gripper.max_aperture, pad = 0.5 * gripper.pad_size;
  std::array<std::vector<double>, 2> along;
  for (Eigen::Index i = 0; i < observed.rows(); ++i) {
    const Eigen::Vector3d offset = observed.row(i).transpose() - grasp.position;
    const double t = offset.dot(x);
    if (std::abs(t) > half || (offset - t * x).norm() > pad) continue;
    along[t < 0.0 ? 0 : 1].push_back(t);
  }
  std::array<std::optional<double>, 2> contacts;
  for (int side = 0; side < 2; ++side) {
    auto& values = along[static_cast<std::size_t>(side)];
    if (static_cast<int>(values.size()) < kLeastObservedPerPad) continue;
    // The pad stops at the outermost surface on its side; the third outermost point ignores lone noise.
    std::sort(values.begin(), values.end());
    const std::size_t k = kLeastObservedPerPad - 1;
    contacts[static_cast<std::size_t>(side)] = side == 0 ? values[k] : values[values.size() - 1 - k];
  }
  return contacts;
}

}  // namespace

std::vector<core::Grasp> reseat_grasps(const MeshRays& believed, const core::Points* observed,
                                       const std::vector<core::Grasp>& grasps, const core::Gripper& gripper) {
  core::validate(gripper);
  std::vector<core::Grasp> seated;
  seated.reserve(grasps.size());
  for (const core::Grasp& carried : grasps) {
    core::Grasp grasp = carried;
    GraspCheck check = check_grasp(believed, grasp, gripper);
    if (check.touched[0] && check.touched[1]) {
      const Eigen::Vector3d mean_normal = (check.normals[1] - check.normals[0]).normalized();
      if (degrees(std::acos(std::clamp(mean_normal.dot(grasp.closing_axis()), -1.0, 1.0))) <=
          kLargestReseatTurnDegrees)
        grasp.rotation = core::grasp_axes(mean_normal, grasp.approach_axis());
      check = check_grasp(believed, grasp, gripper);
    }
    std::array<std::optional<double>, 2> contact;
    for (int side = 0; side < 2; ++side)
      if (check.touched[side])
        contact[static_cast<std::size_t>(side)] = (check.contacts[side] - grasp.position).dot(grasp.closing_axis());
    if (observed) {
      const auto seen = observed_contacts(*observed, grasp, gripper);
      for (int side = 0; side < 2; ++side)
        if (seen[static_cast<std::size_t>(side)]) contact[static_cast<std::size_t>(side)] = seen[static_cast<std::size_t>(side)];
    }
    if (contact[0] && contact[1] && *contact[1] > *contact[0]) {
      grasp.position += 0.5 * (*contact[0] + *contact[1]) * grasp.closing_axis();
      grasp.width = *contact[1] - *contact[0];
    }
    grasp.quality = grasp_quality(check_grasp(believed, grasp, gripper), gripper);
    // The move is kept only where the believed object holds the grasp at least as well after it.
    const double carried_quality = grasp_quality(check_grasp(believed, carried, gripper), gripper);
    if (carried_quality > grasp.quality) {
      grasp = carried;
      grasp.quality = carried_quality;
    }
    seated.push_back(grasp);
  }
  rank(seated);
  return seated;
}

}  // namespace partreg::eval
