#include "pcl_steps.hpp"

#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <algorithm>

namespace partreg::scene::detail {
namespace {

using PclCloud = pcl::PointCloud<pcl::PointXYZ>;

PclCloud::Ptr to_pcl(const core::Points& points) {
  PclCloud::Ptr cloud(new PclCloud);
  cloud->resize(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    (*cloud)[i] = pcl::PointXYZ(float(points(i, 0)), float(points(i, 1)), float(points(i, 2)));
  return cloud;
}

std::vector<int> as_rows(const pcl::Indices& indices) { return {indices.begin(), indices.end()}; }

}  // namespace

core::Points voxelised(const core::Points& points, double leaf) {
  if (leaf <= 0.0) return points;
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setInputCloud(to_pcl(points));
  grid.setLeafSize(float(leaf), float(leaf), float(leaf));
  PclCloud out;
  grid.filter(out);
  core::Points result(static_cast<Eigen::Index>(out.size()), 3);
  for (std::size_t i = 0; i < out.size(); ++i)
    result.row(static_cast<Eigen::Index>(i)) << out[i].x, out[i].y, out[i].z;
  return result;
}

std::vector<int> inlier_rows(const core::Points& points, const SegmentationSettings& settings) {
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> filter;
  filter.setInputCloud(to_pcl(points));
  filter.setMeanK(settings.outlier_neighbours);
  filter.setStddevMulThresh(settings.outlier_deviations);
  pcl::Indices kept;
  filter.filter(kept);
  return as_rows(kept);
}

PlaneFit fit_plane(const core::Points& points, const SegmentationSettings& settings) {
  pcl::SACSegmentation<pcl::PointXYZ> ransac;
  ransac.setOptimizeCoefficients(true);
  ransac.setModelType(pcl::SACMODEL_PLANE);
  ransac.setMethodType(pcl::SAC_RANSAC);
  ransac.setDistanceThreshold(settings.plane_distance);
  ransac.setMaxIterations(settings.plane_iterations);
  ransac.setInputCloud(to_pcl(points));
  pcl::PointIndices inliers;
  pcl::ModelCoefficients coefficients;
  ransac.segment(inliers, coefficients);
  PlaneFit fit;
  if (inliers.indices.empty() || coefficients.values.size() != 4) return fit;
  for (int k = 0; k < 4; ++k) fit.plane[k] = coefficients.values[k];
  fit.plane /= fit.plane.head<3>().norm();
  fit.inliers = as_rows(inliers.indices);
  return fit;
}

std::vector<std::vector<int>> euclidean_clusters(const core::Points& points, const std::vector<int>& rows,
                                                 const SegmentationSettings& settings) {
  if (rows.empty()) return {};
  const PclCloud::Ptr cloud = to_pcl(points);
  pcl::IndicesPtr subset(new pcl::Indices(rows.begin(), rows.end()));
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(cloud, subset);
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> extraction;
  extraction.setClusterTolerance(settings.cluster_tolerance);
  extraction.setMinClusterSize(settings.min_cluster_points);
  extraction.setMaxClusterSize(std::numeric_limits<int>::max());
  extraction.setSearchMethod(tree);
  extraction.setInputCloud(cloud);
  extraction.setIndices(subset);
  std::vector<pcl::PointIndices> found;
  extraction.extract(found);  // PCL sorts them largest first
  std::vector<std::vector<int>> clusters;
  for (const pcl::PointIndices& cluster : found) clusters.push_back(as_rows(cluster.indices));
  return clusters;
}

}  // namespace partreg::scene::detail
