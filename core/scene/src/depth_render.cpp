#include "partreg/scene/depth_render.hpp"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "partreg/core/errors.hpp"

namespace partreg::scene {
namespace {

// One Embree device and scene holding every mesh as its own geometry (geomID = mesh index).
class Caster {
 public:
  explicit Caster(const std::vector<core::Mesh>& meshes) {
    device_ = rtcNewDevice("threads=1");
    if (!device_) throw std::runtime_error("Embree could not create a device");
    scene_ = rtcNewScene(device_);
    for (const core::Mesh& mesh : meshes) attach(mesh);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree failed to build the scene");
    rtcInitIntersectContext(&context_);
  }
  ~Caster() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  Caster(const Caster&) = delete;
  Caster& operator=(const Caster&) = delete;

  /// The first hit along origin + t direction, t in (near, far): geometry index (-1 none), t, unit normal.
  int hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double near, double far, double& t,
          Eigen::Vector3d& normal) {
    RTCRayHit ray{};
    ray.ray.org_x = float(origin.x()), ray.ray.org_y = float(origin.y()), ray.ray.org_z = float(origin.z());
    ray.ray.dir_x = float(direction.x()), ray.ray.dir_y = float(direction.y()), ray.ray.dir_z = float(direction.z());
    ray.ray.tnear = float(near), ray.ray.tfar = float(far), ray.ray.mask = ~0u;
    ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context_, &ray);
    if (ray.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
    t = ray.ray.tfar;
    normal = Eigen::Vector3d(ray.hit.Ng_x, ray.hit.Ng_y, ray.hit.Ng_z).normalized();
    return static_cast<int>(ray.hit.geomID);
  }

  /// Whether anything lies between origin + near direction and origin + far direction.
  bool blocked(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double near, double far) {
    RTCRay ray{};
    ray.org_x = float(origin.x()), ray.org_y = float(origin.y()), ray.org_z = float(origin.z());
    ray.dir_x = float(direction.x()), ray.dir_y = float(direction.y()), ray.dir_z = float(direction.z());
    ray.tnear = float(near), ray.tfar = float(far), ray.mask = ~0u;
    rtcOccluded1(scene_, &context_, &ray);
    return ray.tfar < 0.0f;  // Embree marks an occluded ray with tfar = -inf
  }

 private:
  void attach(const core::Mesh& mesh) {
    if (mesh.faces.rows() == 0) throw InputError("cannot render a mesh without faces");
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.rows()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.faces.rows()));
    for (Eigen::Index i = 0; i < mesh.vertices.size(); ++i) vertices[i] = float(mesh.vertices.data()[i]);
    for (Eigen::Index i = 0; i < mesh.faces.size(); ++i) indices[i] = unsigned(mesh.faces.data()[i]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  RTCIntersectContext context_;
};

void check(const SensorSettings& s) {
  if (!(s.noise >= 0 && s.baseline > 0 && s.disparity_step >= 0 && s.grazing_degrees > 0 &&
        s.grazing_degrees <= 90 && s.edge_jump > 0))
    throw UsageError("sensor settings out of range (noise and disparity step >= 0, baseline and edge jump > 0, "
                     "grazing angle in (0, 90] degrees)");
}

// A pixel beside a depth jump (or beside nothing) is lost: the sensor's pattern breaks up at edges.
bool at_edge(const DepthImage& clean, int u, int v, double jump) {
  const float z = clean.at(u, v);
  for (const auto& [du, dv] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
    const int nu = u + du, nv = v + dv;
    if (nu < 0 || nv < 0 || nu >= clean.width || nv >= clean.height) continue;
    const float n = clean.at(nu, nv);
    if (n == 0.0f || std::abs(n - z) > jump) return true;
  }
  return false;
}

// Noise growing with z^2, then the depth a disparity quantised to `step` pixels gives.
double measured(double z, const Intrinsics& k, const SensorSettings& s, std::mt19937_64& random) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  z += s.noise * z * z * gauss(random);
  if (s.disparity_step <= 0.0) return z;
  const double fb = k.fx * s.baseline;
  const double disparity = std::round(fb / z / s.disparity_step) * s.disparity_step;
  return disparity > 0 ? fb / disparity : 0.0;
}

}  // namespace

RenderedDepth render_depth(const std::vector<core::Mesh>& meshes, const Intrinsics& k,
                           const SensorSettings& sensor) {
  check(sensor);
  k.validate();
  Caster caster(meshes);
  const std::size_t pixels = static_cast<std::size_t>(k.width) * k.height;
  RenderedDepth out;
  out.clean = {k.width, k.height, std::vector<float>(pixels, 0.0f)};
  out.depth = out.clean;
  out.surface.assign(pixels, -1);
  std::vector<std::uint8_t> lost(pixels, 0);
  const double cos_grazing = std::cos(sensor.grazing_degrees * M_PI / 180.0);
  const Eigen::Vector3d projector(sensor.baseline, 0, 0);
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const Eigen::Vector3d direction((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);  // t along it is z
      double t = 0;
      Eigen::Vector3d normal;
      const int index = caster.hit(Eigen::Vector3d::Zero(), direction, 1e-3, 1e3, t, normal);
      if (index < 0) continue;
      const std::size_t i = static_cast<std::size_t>(v) * k.width + u;
      out.surface[i] = index;
      out.clean.metres[i] = static_cast<float>(t);
      const Eigen::Vector3d point = t * direction;
      const bool grazing = std::abs(normal.dot(direction.normalized())) < cos_grazing;
      const bool shadowed = sensor.projector_shadows && caster.blocked(point, projector - point, 1e-4, 1.0 - 1e-4);
      lost[i] = grazing || shadowed;
    }
  std::mt19937_64 random(sensor.seed);
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * k.width + u;
      const double z = out.clean.metres[i];
      if (z == 0.0 || lost[i] || at_edge(out.clean, u, v, sensor.edge_jump)) continue;
      out.depth.metres[i] = static_cast<float>(measured(z, k, sensor, random));
    }
  return out;
}

PixelMask surface_mask(const RenderedDepth& rendered, int index) {
  PixelMask mask{rendered.clean.width, rendered.clean.height,
                 std::vector<std::uint8_t>(rendered.surface.size(), 0)};
  for (std::size_t i = 0; i < rendered.surface.size(); ++i) mask.selected[i] = rendered.surface[i] == index;
  return mask;
}

}  // namespace partreg::scene
