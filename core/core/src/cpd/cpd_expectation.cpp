#include "cpd_expectation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <unordered_map>

#include "partreg/core/errors.hpp"
#include "cpd_dense_kernel.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/parallel.hpp"

namespace partreg::core::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFloor = 1e-300;

// Partial sums over one piece of the target points (see summed()).
struct Partial {
  Eigen::VectorXd P1;
  Points PX;
  double nll = 0.0;
  explicit Partial(Eigen::Index m) : P1(Eigen::VectorXd::Zero(m)), PX(Points::Zero(m, 3)) {}
};

// The exact E-step over a range of target points: one target point at a time against every source point,
// held as coordinate arrays so that distances, exp and sums are vectorised.
void dense_range_exact(const Points& moved, const Points& target, Eigen::Index begin, Eigen::Index end,
                       double sigma2, double c, Partial& partial, Eigen::VectorXd& target_mass) {
  const Eigen::ArrayXd mx = moved.col(0), my = moved.col(1), mz = moved.col(2);
  Eigen::ArrayXd k(moved.rows());
  for (Eigen::Index n = begin; n < end; ++n) {
    const double x = target(n, 0), y = target(n, 1), z = target(n, 2);
    k = (((mx - x).square() + (my - y).square() + (mz - z).square()) * (-0.5 / sigma2)).exp();
    const double denominator = std::max(k.sum() + c, kFloor);
    k /= denominator;
    partial.P1 += k.matrix();
    partial.PX.col(0) += (k * x).matrix();
    partial.PX.col(1) += (k * y).matrix();
    partial.PX.col(2) += (k * z).matrix();
    target_mass[n] = k.sum();
    partial.nll -= std::log(denominator);
  }
}

// Integer coordinates on a grid of `edge` anchored at the origin, packed into one key (21 bits each, offset
// so that negative coordinates fit). A grid fixed in space keeps a point in its cell from one iteration to
// the next unless it moves across a face.
constexpr std::int64_t kGridOffset = 1 << 20;
using GridCoordinates = Eigen::Matrix<std::int64_t, 3, 1>;

GridCoordinates grid_coordinates(const Eigen::RowVector3d& point, double edge) {
  return (point.transpose() / edge).array().floor().cast<std::int64_t>();
}

std::uint64_t grid_key(const GridCoordinates& cell) {
  std::uint64_t key = 0;
  for (int d = 0; d < 3; ++d) key = (key << 21) | static_cast<std::uint64_t>(cell[d] + kGridOffset);
  return key;
}

// Whether every point's grid coordinates, and their neighbours', fit a key.
bool fits_grid(const Points& points, double edge) {
  return edge > 0.0 && points.cwiseAbs().maxCoeff() / edge < static_cast<double>(kGridOffset - 2);
}

// A point set merged into voxel cells: each cell stands for its points, all at their centroid.
struct Cells {
  Points centroids;
  Eigen::VectorXd counts;
  std::vector<int> of_point;  ///< the cell of every point
};

Cells one_cell_per_point(const Points& points) {
  Cells cells{points, Eigen::VectorXd::Ones(points.rows()), std::vector<int>(points.rows())};
  for (Eigen::Index i = 0; i < points.rows(); ++i) cells.of_point[static_cast<std::size_t>(i)] = int(i);
  return cells;
}

Cells merge_into_cells(const Points& points, double edge) {
  if (!fits_grid(points, edge)) return one_cell_per_point(points);
  std::unordered_map<std::uint64_t, int> index;
  index.reserve(static_cast<std::size_t>(points.rows()));
  Cells cells;
  cells.of_point.resize(static_cast<std::size_t>(points.rows()));
  Points sums(points.rows(), 3);
  Eigen::VectorXd counts(points.rows());
  int used = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const auto [found, inserted] = index.try_emplace(grid_key(grid_coordinates(points.row(i), edge)), used);
    if (inserted) {
      sums.row(used).setZero();
      counts[used++] = 0.0;
    }
    sums.row(found->second) += points.row(i);
    counts[found->second] += 1.0;
    cells.of_point[static_cast<std::size_t>(i)] = found->second;
  }
  if (used == points.rows()) return one_cell_per_point(points);  // same cells, in the points' own order
  cells.counts = counts.head(used);
  cells.centroids = sums.topRows(used).array().colwise() / cells.counts.array();
  return cells;
}

// Cells grouped into cubic blocks of `edge` (at least the truncation radius): a target cell's neighbours
// within the radius all lie in its own block and the 26 around it. Block b holds members[start[b] ..
// start[b + 1]).
struct Blocks {
  std::unordered_map<std::uint64_t, int> of_key;
  std::vector<GridCoordinates> coordinates;  ///< per block
  std::vector<int> start, members;
};

Blocks group_into_blocks(const Points& points, double edge) {
  Blocks blocks;
  std::vector<int> block_of(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const GridCoordinates cell = grid_coordinates(points.row(i), edge);
    const auto [found, inserted] = blocks.of_key.try_emplace(grid_key(cell), int(blocks.coordinates.size()));
    if (inserted) blocks.coordinates.push_back(cell);
    block_of[static_cast<std::size_t>(i)] = found->second;
  }
  blocks.start.assign(blocks.coordinates.size() + 1, 0);
  for (int b : block_of) ++blocks.start[static_cast<std::size_t>(b) + 1];
  for (std::size_t b = 0; b < blocks.coordinates.size(); ++b) blocks.start[b + 1] += blocks.start[b];
  blocks.members.resize(block_of.size());
  std::vector<int> next(blocks.start.begin(), blocks.start.end() - 1);
  for (std::size_t i = 0; i < block_of.size(); ++i)
    blocks.members[static_cast<std::size_t>(next[static_cast<std::size_t>(block_of[i])]++)] = int(i);
  return blocks;
}

// The source cells near one block of target cells, gathered into float arrays relative to the block's
// corner (so float resolves sigma wherever the block lies), with the sums the kernel accumulates. Every array
// starts on a 64-byte line: Eigen's vectorised sums begin at the first aligned element, so with arrays
// wherever the heap put them the order of their additions (and the last bits of the posterior) followed
// what the process had allocated before, and CPD was not repeatable from one process to the next.
struct Neighbourhood {
  static constexpr std::size_t kLine = 64 / sizeof(float);  // floats per 64-byte line
  std::vector<int> cells;
  std::vector<float> data;  // x, y, z, weight, work, p1, px, py, pz: 9 arrays of `stride` from `base`
  std::size_t stride = 0, base = 0;
  void gather(const Blocks& blocks, const GridCoordinates& centre, const Cells& source,
              const Eigen::RowVector3d& origin) {
    cells.clear();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = blocks.of_key.find(grid_key(centre + GridCoordinates(dx, dy, dz)));
          if (found == blocks.of_key.end()) continue;
          const auto b = static_cast<std::size_t>(found->second);
          cells.insert(cells.end(), blocks.members.begin() + blocks.start[b],
                       blocks.members.begin() + blocks.start[b + 1]);
        }
    const std::size_t count = cells.size();
    stride = (count + kLine - 1) / kLine * kLine;
    data.assign(9 * stride + kLine, 0.0f);
    const auto address = reinterpret_cast<std::uintptr_t>(data.data());
    base = (kLine - address / sizeof(float) % kLine) % kLine;  // malloc aligns floats, so this is exact
    for (std::size_t j = 0; j < count; ++j) {
      const Eigen::RowVector3d local = source.centroids.row(cells[j]) - origin;
      for (int d = 0; d < 3; ++d) array(d)[j] = static_cast<float>(local[d]);
      array(3)[j] = static_cast<float>(source.counts[cells[j]]);
    }
  }
  float* array(int which) { return data.data() + base + static_cast<std::size_t>(which) * stride; }
};

// The fast E-step for the target cells of blocks [begin, end): each block's cells against every source cell
// in the 27 blocks around it, vectorised (cpd_dense_kernel.cpp). Kernel values beyond the truncation
// radius are skipped whole blocks at a time; those that are computed anyway only add accuracy.
void blocked_range(const Blocks& target_blocks, const Blocks& source_blocks, const Cells& source,
                   const Cells& target, double edge, Eigen::Index begin, Eigen::Index end, double sigma2,
                   double c, Partial& partial, Eigen::VectorXd& cell_mass) {
  Neighbourhood near;
  std::vector<double> rows, weights, mass;
  for (Eigen::Index b = begin; b < end; ++b) {
    const GridCoordinates& centre = target_blocks.coordinates[static_cast<std::size_t>(b)];
    const Eigen::RowVector3d origin = centre.cast<double>().transpose() * edge;
    near.gather(source_blocks, centre, source, origin);
    const auto m = static_cast<std::ptrdiff_t>(near.cells.size());
    const int first = target_blocks.start[static_cast<std::size_t>(b)],
              last = target_blocks.start[static_cast<std::size_t>(b) + 1];
    rows.resize(3 * static_cast<std::size_t>(last - first));
    weights.resize(static_cast<std::size_t>(last - first));
    mass.resize(weights.size());
    for (int i = first; i < last; ++i) {
      const int t = target_blocks.members[static_cast<std::size_t>(i)];
      const Eigen::RowVector3d local = target.centroids.row(t) - origin;
      for (int d = 0; d < 3; ++d) rows[3 * static_cast<std::size_t>(i - first) + d] = local[d];
      weights[static_cast<std::size_t>(i - first)] = target.counts[t];
    }
    partial.nll -= dense_posterior_sums(near.array(0), near.array(1), near.array(2), near.array(3), m,
                                        rows.data(), weights.data(), last - first,
                                        static_cast<float>(-0.5 / sigma2), c, near.array(4), near.array(5),
                                        near.array(6), near.array(7), near.array(8), mass.data());
    for (int i = first; i < last; ++i)
      cell_mass[target_blocks.members[static_cast<std::size_t>(i)]] = mass[static_cast<std::size_t>(i - first)];
    // Back to the caller's frame: P X was summed over coordinates relative to the block's corner.
    for (std::ptrdiff_t j = 0; j < m; ++j) {
      const int s = near.cells[static_cast<std::size_t>(j)];
      const double p1 = near.array(5)[j];
      partial.P1[s] += p1;
      for (int d = 0; d < 3; ++d) partial.PX(s, d) += near.array(6 + d)[j] + p1 * origin[d];
    }
  }
}

// The cell edge for sigma2: cell_size sigma rounded down to a power of two, so that the cells (and with them
// the likelihood's small approximation error) stay the same over runs of iterations: EM's stopping test
// then compares likelihoods computed on the same cells.
double cell_edge(double sigma2, double cell_size) {
  if (!(cell_size > 0.0)) return 0.0;
  return std::exp2(std::floor(std::log2(cell_size * std::sqrt(sigma2))));
}

double truncation_radius(double sigma2, double truncation) {
  return std::sqrt(2.0 * sigma2 * std::log(1.0 / truncation));
}

// Runs `range(begin, end, partial)` over [0, count) in kPieces fixed pieces on the settings' threads and sums
// the pieces' partials in piece order. Pieces that do not follow the thread count, and a sum in a fixed
// order, give the same bits whatever the thread count and whichever thread finishes first (the memory is
// kPieces partials of 4 M doubles: 51 MB at M = 100,000).
constexpr Eigen::Index kPieces = 16;

template <typename Range>
Partial summed(Eigen::Index count, Eigen::Index sources, int threads, Range range) {
  const Eigen::Index pieces = std::min(kPieces, count);
  std::vector<Partial> partials(static_cast<std::size_t>(pieces), Partial(sources));
  parallel_for(
      pieces,
      [&](Eigen::Index first, Eigen::Index last) {
        for (Eigen::Index p = first; p < last; ++p)
          range(p * count / pieces, (p + 1) * count / pieces, partials[static_cast<std::size_t>(p)]);
      },
      threads, 1);
  Partial total(sources);
  for (const Partial& partial : partials) {
    total.P1 += partial.P1;
    total.PX += partial.PX;
    total.nll += partial.nll;
  }
  return total;
}

}  // namespace

Expectation expectation(const Points& moved, const Points& target, double sigma2,
                        const EStepSettings& settings) {
  const Eigen::Index m = moved.rows(), n = target.rows();
  const double w = settings.outlier_weight;
  // Uniform outlier term of the mixture, expressed in the kernel's scale (Myronenko & Song, Eq. 7), over
  // the outliers' volume when one is given, else over CPD's N.
  const double spread = settings.outlier_volume > 0.0 ? settings.outlier_volume : static_cast<double>(n);
  const double c = std::pow(2.0 * kPi * sigma2, 1.5) * w / (1.0 - w) * static_cast<double>(m) / spread;
  Expectation out;
  out.Pt1.resize(n);
  if (settings.exact) {
    const Partial total = summed(n, m, settings.threads, [&](Eigen::Index begin, Eigen::Index end, Partial& p) {
      dense_range_exact(moved, target, begin, end, sigma2, c, p, out.Pt1);
    });
    out.P1 = total.P1;
    out.PX = total.PX;
    out.negative_log_likelihood = total.nll;
  } else {
    // Only the target is merged. Merging the source too would be cheaper, but every source point then takes
    // its cell's posterior, which drops the first-order change of P X across the cell: on the densified
    // drill pairs EM then settled on a plateau at sigma ~ 0.05 that the exact E-step leaves (fit 3.2% of
    // the diagonal instead of 1.5%).
    const double edge = cell_edge(sigma2, settings.cell_size);
    const Cells source = one_cell_per_point(moved), cells = merge_into_cells(target, edge);
    const bool merged = cells.centroids.rows() < n;
    out.cell_edge = merged ? edge : 0.0;  // cells of one point each are exact
    // Blocks at least the truncation radius wide, and coarse enough for every coordinate to fit a key.
    const double scale = std::max(moved.cwiseAbs().maxCoeff(), target.cwiseAbs().maxCoeff());
    const double block = std::max(truncation_radius(sigma2, settings.truncation),
                                  scale / static_cast<double>(kGridOffset / 4));
    const Blocks source_blocks = group_into_blocks(source.centroids, block),
                 target_blocks = group_into_blocks(cells.centroids, block);
    Eigen::VectorXd cell_mass(cells.centroids.rows());
    const Partial total = summed(static_cast<Eigen::Index>(target_blocks.coordinates.size()),
                                 source.centroids.rows(), settings.threads,
                                 [&](Eigen::Index begin, Eigen::Index end, Partial& p) {
                                   blocked_range(target_blocks, source_blocks, source, cells, block, begin, end,
                                                 sigma2, c, p, cell_mass);
                                 });
    // Every point takes its cell's posterior: the M-steps sum these against smooth functions of the
    // points, where the first-order errors of a cell's points cancel around its centroid.
    out.P1.resize(m);
    out.PX.resize(m, 3);
    for (Eigen::Index i = 0; i < m; ++i) {
      const int cell = source.of_point[static_cast<std::size_t>(i)];
      out.P1[i] = total.P1[cell];
      out.PX.row(i) = total.PX.row(cell);
    }
    for (Eigen::Index i = 0; i < n; ++i) out.Pt1[i] = cell_mass[cells.of_point[static_cast<std::size_t>(i)]];
    out.negative_log_likelihood = total.nll;
  }
  out.Np = out.P1.sum();
  out.negative_log_likelihood += 1.5 * static_cast<double>(n) * std::log(sigma2);
  return out;
}

double initial_sigma2(const Points& source, const Points& target) {
  const double m = static_cast<double>(source.rows()), n = static_cast<double>(target.rows());
  const Eigen::RowVector3d source_sum = source.colwise().sum(), target_sum = target.colwise().sum();
  const double total = n * source.squaredNorm() + m * target.squaredNorm() - 2.0 * source_sum.dot(target_sum);
  return total / (3.0 * m * n);
}

std::vector<int> random_rows(Eigen::Index count, Eigen::Index wanted) {
  std::vector<int> rows(static_cast<std::size_t>(count));
  std::iota(rows.begin(), rows.end(), 0);
  if (wanted >= count) return rows;
  // A partial Fisher-Yates shuffle: the first `wanted` places end up a uniform sample without replacement.
  // The modulo's bias is below count / 2^64.
  std::mt19937_64 generator(20101);
  for (Eigen::Index i = 0; i < wanted; ++i) {
    const auto j = i + static_cast<Eigen::Index>(generator() % static_cast<std::uint64_t>(count - i));
    std::swap(rows[static_cast<std::size_t>(i)], rows[static_cast<std::size_t>(j)]);
  }
  rows.resize(static_cast<std::size_t>(wanted));
  std::sort(rows.begin(), rows.end());  // the input's order: neighbours in memory stay near
  return rows;
}

void check_cpd_points(const Points& points, const char* name) {
  if (points.rows() < 3)
    throw InputError(std::string("CPD needs at least 3 ") + name + " points, got " +
                     std::to_string(points.rows()));
  if (!points.allFinite())
    throw InputError(std::string("the ") + name + " points hold NaN or infinite values");
  // Normalisation squares coordinate differences: beyond 1e150 they overflow to infinity and every moved
  // point would come out NaN. 1e12 is the bound every other coordinate partreg reads has.
  if (points.cwiseAbs().maxCoeff() > 1e12)
    throw InputError(std::string("the ") + name +
                     " points hold coordinates beyond 1e12, not a sensible size");
}

void check_cpd_common(double outlier_weight, double tolerance, int max_iterations) {
  if (!(outlier_weight >= 0.0 && outlier_weight < 1.0))
    throw UsageError("the CPD outlier weight w must be in [0, 1), got " + std::to_string(outlier_weight));
  if (!(tolerance > 0.0 && tolerance <= 1.0)) throw UsageError("the CPD tolerance must be in (0, 1]");
  if (max_iterations < 1) throw UsageError("the CPD iteration cap must be at least 1");
}

void check_fast_e_step(double truncation, double cell_size) {
  if (!(truncation > 0.0 && truncation < 1.0))
    throw UsageError("the CPD truncation must be in (0, 1), got " + std::to_string(truncation));
  if (!(cell_size >= 0.0 && cell_size <= 1.0))
    throw UsageError("the CPD cell size must be in [0, 1] sigma, got " + std::to_string(cell_size));
}

}  // namespace partreg::core::detail
