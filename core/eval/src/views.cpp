#include "partreg/eval/views.hpp"

#include "embree_mesh.hpp"

#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <unordered_set>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/parallel.hpp"

namespace partreg::eval {
namespace {

// Subdividing each triangle into four adds one vertex per edge: 12 -> 42 -> 162 -> ... vertices.
std::vector<Eigen::Vector3d> icosahedron(std::vector<Eigen::Vector3i>& faces) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                           {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                           {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Eigen::Vector3d& vertex : vertices) vertex.normalize();
  faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
           {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
           {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  return vertices;
}

void subdivide(std::vector<Eigen::Vector3d>& vertices, std::vector<Eigen::Vector3i>& faces) {
  std::map<std::pair<int, int>, int> midpoint_of_edge;
  auto midpoint = [&](int a, int b) {
    const std::pair<int, int> edge = std::minmax(a, b);
    auto [found, inserted] = midpoint_of_edge.try_emplace(edge, static_cast<int>(vertices.size()));
    if (inserted) vertices.push_back((vertices[a] + vertices[b]).normalized());
    return found->second;
  };
  std::vector<Eigen::Vector3i> finer;
  for (const Eigen::Vector3i& f : faces) {
    const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
    finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
  }
  faces = std::move(finer);
}

void check_device(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree failed while ") + what + " (error " +
                             std::to_string(static_cast<int>(error)) + ")");
}

// The median distance from a point to its nearest neighbour, over up to 2000 points.
double median_spacing(const core::Points& cloud) {
  if (cloud.rows() < 2) return 0.0;
  const core::KdTree tree(cloud);
  const Eigen::Index step = std::max<Eigen::Index>(1, cloud.rows() / 2000);
  std::vector<double> spacing;
  for (Eigen::Index i = 0; i < cloud.rows(); i += step)
    spacing.push_back(std::sqrt(tree.nearest_k(cloud.row(i).transpose(), 2).back().second));
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  return spacing[spacing.size() / 2];
}

}  // namespace

std::vector<Eigen::Vector3d> sphere_directions(int count) {
  std::vector<Eigen::Vector3i> faces;
  std::vector<Eigen::Vector3d> vertices = icosahedron(faces);
  while (static_cast<int>(vertices.size()) < count) subdivide(vertices, faces);
  if (static_cast<int>(vertices.size()) != count)
    throw UsageError("view count " + std::to_string(count) +
                     " is not a tessellated sphere's vertex count (12, 42, 162, 642, ...)");
  return vertices;
}

// Embree objects are released in reverse order of creation; the scene is immutable after commit, which is
// what makes cast() safe to call from many threads.
struct ViewCaster::Scene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  bool is_cloud = false;
  core::Points cloud;  // the points of a cloud scene (views return them, not the sphere surface)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;  // half the bounding-box diagonal

  explicit Scene(const core::Points& points) {
    if (points.rows() == 0) throw InputError("cannot cast views of an empty object");
    const Eigen::Vector3d low = points.colwise().minCoeff(), high = points.colwise().maxCoeff();
    centre = (low + high) / 2;
    radius = (high - low).norm() / 2;
    // Embree builds its BVH on threads of its own: give it the caller's budget (core/parallel.hpp).
    const std::string config = "threads=" + std::to_string(core::thread_budget());
    device = rtcNewDevice(config.c_str());
    if (!device) throw std::runtime_error("Embree could not create a device");
    scene = rtcNewScene(device);
  }
  ~Scene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  void attach(RTCGeometry geometry) {
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene);
    check_device(device, "building the scene");
  }
};

ViewCaster::ViewCaster(const core::Mesh& mesh) {
  if (mesh.faces.rows() == 0) throw InputError("cannot cast views of a mesh without faces");
  scene_ = std::make_unique<Scene>(mesh.vertices);
  RTCGeometry geometry = detail::triangle_geometry(scene_->device, mesh);
  scene_->attach(geometry);
}

ViewCaster::ViewCaster(const core::Points& cloud, double radius) {
  scene_ = std::make_unique<Scene>(cloud);
  scene_->is_cloud = true;
  scene_->cloud = cloud;
  if (radius <= 0.0) radius = 1.5 * median_spacing(cloud);
  if (!(radius > 0.0)) radius = 1e-3 * scene_->radius;
  RTCGeometry geometry = rtcNewGeometry(scene_->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  check_device(scene_->device, "creating point geometry (is Embree built with point support?)");
  auto* spheres = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), cloud.rows()));
  for (Eigen::Index i = 0; i < cloud.rows(); ++i) {
    for (int k = 0; k < 3; ++k) spheres[4 * i + k] = static_cast<float>(cloud(i, k));
    spheres[4 * i + 3] = static_cast<float>(radius);
  }
  scene_->attach(geometry);
}

ViewCaster::~ViewCaster() = default;
ViewCaster::ViewCaster(ViewCaster&&) noexcept = default;
ViewCaster& ViewCaster::operator=(ViewCaster&&) noexcept = default;

void check_camera(const CameraSettings& camera) {
  using C = CameraSettings;
  if (camera.width < 1 || camera.height < 1 || camera.width > C::kMaxPixelsPerSide ||
      camera.height > C::kMaxPixelsPerSide)
    throw UsageError("camera size must be 1 to " + std::to_string(C::kMaxPixelsPerSide) + " pixels a side");
  if (!(camera.fov_degrees >= C::kMinFovDegrees && camera.fov_degrees <= C::kMaxFovDegrees))
    throw UsageError("field of view must be " + std::to_string(C::kMinFovDegrees) + " to " +
                     std::to_string(C::kMaxFovDegrees) + " degrees");
  if (!(camera.margin >= 1.0 && camera.margin <= C::kMaxMargin))
    throw UsageError("camera margin must be 1 to " + std::to_string(C::kMaxMargin));
}

View ViewCaster::cast(const Eigen::Vector3d& direction, const CameraSettings& camera) const {
  check_camera(camera);
  View view;
  view.direction = direction.normalized();
  const double half_fov = camera.fov_degrees * M_PI / 360.0;
  view.viewpoint = scene_->centre + view.direction * (camera.margin * scene_->radius / std::sin(half_fov));
  // Camera basis: looking at the centre, "up" as close to +y as the direction allows.
  const Eigen::Vector3d forward = -view.direction;
  const Eigen::Vector3d hint =
      std::abs(forward.y()) > 0.99 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d right = forward.cross(hint).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const double tan_half = std::tan(half_fov), aspect = double(camera.width) / camera.height;

  std::vector<Eigen::Vector3d> hits, normals;
  std::unordered_set<unsigned> seen;  // a cloud point is reported once, however many rays hit it
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int row = 0; row < camera.height; ++row) {
    for (int column = 0; column < camera.width; ++column) {
      const double x = ((column + 0.5) / camera.width * 2 - 1) * tan_half * aspect;
      const double y = (1 - (row + 0.5) / camera.height * 2) * tan_half;
      const Eigen::Vector3d ray = (forward + x * right + y * up).normalized();
      RTCRayHit hit{};
      hit.ray.org_x = float(view.viewpoint.x()), hit.ray.org_y = float(view.viewpoint.y());
      hit.ray.org_z = float(view.viewpoint.z());
      hit.ray.dir_x = float(ray.x()), hit.ray.dir_y = float(ray.y()), hit.ray.dir_z = float(ray.z());
      hit.ray.tnear = 0.0f;
      hit.ray.tfar = std::numeric_limits<float>::infinity();
      hit.ray.mask = ~0u;
      hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene_->scene, &context, &hit);
      if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      if (scene_->is_cloud) {
        if (seen.insert(hit.hit.primID).second) hits.push_back(scene_->cloud.row(hit.hit.primID).transpose());
        continue;
      }
      hits.push_back(view.viewpoint + double(hit.ray.tfar) * ray);
      Eigen::Vector3d normal(hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z);
      normal.normalize();
      if (normal.dot(ray) > 0) normal = -normal;  // open meshes: the side the camera sees
      normals.push_back(normal);
    }
  }
  view.points.resize(static_cast<Eigen::Index>(hits.size()), 3);
  for (std::size_t i = 0; i < hits.size(); ++i) view.points.row(static_cast<Eigen::Index>(i)) = hits[i];
  view.normals.resize(static_cast<Eigen::Index>(normals.size()), 3);
  for (std::size_t i = 0; i < normals.size(); ++i)
    view.normals.row(static_cast<Eigen::Index>(i)) = normals[i];
  return view;
}

}  // namespace partreg::eval
