// SPDX-License-Identifier: MIT
#include "io/block_results.hpp"

#include "mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace nmm {

namespace {

double cross(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

double triangle_area(const Point2& a, const Point2& b, const Point2& c) {
  return 0.5 * cross(b - a, c - a);
}

/// Calls @p visit(element, loop now, first point index of the loop, sign) for every loop of
/// every element polygon in step_points() order; sign is +1 for an outer loop and -1 for a
/// hole, so that sign times a loop's area at the start is the area it adds (holes subtract),
/// whatever the orientation the loops are stored in.
template <typename Visit>
void for_each_loop(const Model& model, std::span<const Point2> initial_points, Visit visit) {
  std::size_t first = 0;
  for (int e = 0; e < model.n_elements(); ++e) {
    for (const Polygon& polygon : model.elements[static_cast<std::size_t>(e)].polygons) {
      const auto one = [&](const Loop& loop, double side) {
        const std::span<const Point2> start = initial_points.subspan(first, loop.size());
        const double sign = signed_area(start) >= 0.0 ? side : -side;
        visit(e, std::span<const Point2>(loop), first, sign);
        first += loop.size();
      };
      one(polygon.outer, 1.0);
      for (const Loop& hole : polygon.holes)
        one(hole, -1.0);
    }
  }
  NMM_ASSERT(first == initial_points.size(), "the initial points are step_points() of the model");
}

/// The integrals over a block of the products of two fields linear on each fan triangle:
/// int f g dA = A / 12 (sum f_i g_i + sum f_i sum g_i) over a triangle.
struct FanSums {
  double area = 0.0;
  Point2 first = Point2::Zero();                   ///< int a dA
  Point2 second = Point2::Zero();                  ///< int b dA
  Eigen::Matrix2d outer = Eigen::Matrix2d::Zero(); ///< int a b^T dA

  void add(double weight, const std::array<Point2, 3>& a, const std::array<Point2, 3>& b) {
    const Point2 sum_a = a[0] + a[1] + a[2];
    const Point2 sum_b = b[0] + b[1] + b[2];
    area += weight;
    first += weight / 3.0 * sum_a;
    second += weight / 3.0 * sum_b;
    Eigen::Matrix2d products = sum_a * sum_b.transpose();
    for (int i = 0; i < 3; ++i)
      products += a[static_cast<std::size_t>(i)] * b[static_cast<std::size_t>(i)].transpose();
    outer += weight / 12.0 * products;
  }
  /// int (a - a_mean) (b - b_mean)^T dA.
  [[nodiscard]] Eigen::Matrix2d central() const {
    return outer - first * second.transpose() / area;
  }
};

} // namespace

const char* block_state_name(BlockState state) {
  switch (state) {
  case BlockState::resting:
    return "resting";
  case BlockState::sliding:
    return "sliding";
  case BlockState::rotating:
    return "rotating";
  case BlockState::free:
    return "free";
  case BlockState::excavated:
    return "excavated";
  }
  return "resting";
}

BlockTracker::BlockTracker(const Model& model, std::vector<Point2> initial_points)
    : initial_points_(std::move(initial_points)) {
  const std::size_t n_blocks = model.blocks.size();
  area_.assign(n_blocks, 0.0);
  initial_centroid_.assign(n_blocks, Point2::Zero());
  origin_.assign(n_blocks, Point2::Zero());
  last_.assign(n_blocks, Fit{});
  rate_.assign(n_blocks, Point2::Zero());
  angular_rate_.assign(n_blocks, 0.0);
  std::vector<bool> has_origin(n_blocks, false);
  std::vector<std::vector<double>> region_area(n_blocks);
  for_each_loop(model, initial_points_,
                [&](int e, std::span<const Point2> loop, std::size_t first, double sign) {
                  const ModelElement& element = model.elements[static_cast<std::size_t>(e)];
                  const auto b = static_cast<std::size_t>(element.block);
                  NMM_ASSERT(b < n_blocks, "every element lies in a block");
                  if (!has_origin[b] && !loop.empty()) {
                    origin_[b] = initial_points_[first];
                    has_origin[b] = true;
                  }
                  const Point2& o = origin_[b];
                  double loop_area = 0.0;
                  for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
                    const Point2 a = initial_points_[first] - o;
                    const Point2 p = initial_points_[first + k] - o;
                    const Point2 q = initial_points_[first + k + 1] - o;
                    const double w = sign * triangle_area(a, p, q);
                    loop_area += w;
                    initial_centroid_[b] += w / 3.0 * (a + p + q);
                  }
                  area_[b] += loop_area;
                  std::vector<double>& by_region = region_area[b];
                  const auto region = static_cast<std::size_t>(element.material);
                  if (by_region.size() <= region)
                    by_region.resize(region + 1, 0.0);
                  by_region[region] += loop_area;
                });
  regions_.assign(n_blocks, 0);
  for (std::size_t b = 0; b < n_blocks; ++b) {
    initial_centroid_[b] =
        origin_[b] + (area_[b] > 0.0 ? Point2(initial_centroid_[b] / area_[b]) : Point2::Zero());
    last_[b].centroid = initial_centroid_[b];
    const std::vector<double>& by_region = region_area[b];
    if (!by_region.empty())
      regions_[b] = static_cast<int>(std::max_element(by_region.begin(), by_region.end()) -
                                     by_region.begin());
  }
}

std::vector<BlockTracker::Fit> BlockTracker::fit(const Model& model) const {
  const std::size_t n_blocks = area_.size();
  std::vector<FanSums> sums(n_blocks);
  std::vector<Point2> vertex_sum(n_blocks, Point2::Zero());
  std::vector<double> vertices(n_blocks, 0.0);
  for_each_loop(model, initial_points_,
                [&](int e, std::span<const Point2> loop, std::size_t first, double sign) {
                  const auto b =
                      static_cast<std::size_t>(model.elements[static_cast<std::size_t>(e)].block);
                  const Point2& o = origin_[b];
                  for (const Point2& x : loop)
                    vertex_sum[b] += x - o;
                  vertices[b] += static_cast<double>(loop.size());
                  for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
                    const std::array<Point2, 3> start{initial_points_[first] - o,
                                                      initial_points_[first + k] - o,
                                                      initial_points_[first + k + 1] - o};
                    const std::array<Point2, 3> now{loop[0] - o, loop[k] - o, loop[k + 1] - o};
                    sums[b].add(sign * triangle_area(start[0], start[1], start[2]), start, now);
                  }
                });
  std::vector<Fit> fits(n_blocks);
  for (std::size_t b = 0; b < n_blocks; ++b) {
    const FanSums& s = sums[b];
    if (!(s.area > 0.0)) { // no area: the mean vertex, no rotation of its own
      fits[b].centroid = origin_[b] + vertex_sum[b] / std::max(1.0, vertices[b]);
      fits[b].rotation = last_[b].rotation;
      continue;
    }
    fits[b].centroid = origin_[b] + s.second / s.area;
    const Eigen::Matrix2d h = s.central();
    const double angle = std::atan2(h(0, 1) - h(1, 0), h(0, 0) + h(1, 1));
    const double last = last_[b].rotation;
    fits[b].rotation = last + std::remainder(angle - last, 2.0 * std::numbers::pi);
  }
  return fits;
}

void BlockTracker::update(const Model& model, double dt) {
  std::vector<Fit> now = fit(model);
  for (std::size_t b = 0; b < now.size(); ++b) {
    rate_[b] = dt > 0.0 ? Point2((now[b].centroid - last_[b].centroid) / dt) : Point2::Zero();
    angular_rate_[b] = dt > 0.0 ? (now[b].rotation - last_[b].rotation) / dt : 0.0;
  }
  last_ = std::move(now);
}

std::vector<BlockMotion>
BlockTracker::motions(const Model& model, const Eigen::VectorXd& velocity, bool step_rates) const {
  const std::size_t n_blocks = area_.size();
  std::vector<BlockMotion> motions(n_blocks);
  for (std::size_t b = 0; b < n_blocks; ++b) {
    motions[b].centroid = last_[b].centroid;
    motions[b].displacement = last_[b].centroid - initial_centroid_[b];
    motions[b].rotation = last_[b].rotation;
    motions[b].velocity = rate_[b];
    motions[b].angular_velocity = angular_rate_[b];
  }
  // The velocity fit over the material now: int x . v and int x x v, x about the block's origin.
  std::vector<FanSums> sums(n_blocks);
  std::vector<double> spin(n_blocks, 0.0);    // int x x v dA
  std::vector<double> inertia(n_blocks, 0.0); // int |x|^2 dA
  for_each_loop(model, initial_points_,
                [&](int e, std::span<const Point2> loop, std::size_t /*first*/, double sign) {
                  const auto b =
                      static_cast<std::size_t>(model.elements[static_cast<std::size_t>(e)].block);
                  const Point2& c = last_[b].centroid;
                  for (const Point2& x : loop)
                    motions[b].radius = std::max(motions[b].radius, (x - c).norm());
                  if (step_rates)
                    return;
                  std::vector<Point2> v(loop.size());
                  for (std::size_t k = 0; k < loop.size(); ++k)
                    v[k] = model.displacement(e, loop[k], velocity);
                  for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
                    const std::array<Point2, 3> x{loop[0] - c, loop[k] - c, loop[k + 1] - c};
                    const std::array<Point2, 3> vk{v[0], v[k], v[k + 1]};
                    const double w = sign * triangle_area(x[0], x[1], x[2]);
                    sums[b].add(w, x, vk);
                    const Point2 sx = x[0] + x[1] + x[2];
                    const Point2 sv = vk[0] + vk[1] + vk[2];
                    double s = cross(sx, sv);
                    double i = sx.squaredNorm();
                    for (std::size_t j = 0; j < 3; ++j) {
                      s += cross(x[j], vk[j]);
                      i += x[j].squaredNorm();
                    }
                    spin[b] += w / 12.0 * s;
                    inertia[b] += w / 12.0 * i;
                  }
                });
  if (step_rates)
    return motions;
  for (std::size_t b = 0; b < n_blocks; ++b) {
    const FanSums& s = sums[b];
    if (!(s.area > 0.0))
      continue;
    const Point2 x_mean = s.first / s.area;
    const Point2 v_mean = s.second / s.area;
    motions[b].velocity = v_mean;
    const double polar = inertia[b] - s.area * x_mean.squaredNorm();
    motions[b].angular_velocity =
        polar > 0.0 ? (spin[b] - s.area * cross(x_mean, v_mean)) / polar : 0.0;
  }
  return motions;
}

std::vector<Point2> BlockTracker::displacements() const {
  std::vector<Point2> out(last_.size());
  for (std::size_t b = 0; b < out.size(); ++b)
    out[b] = last_[b].centroid - initial_centroid_[b];
  return out;
}

Eigen::VectorXd BlockTracker::state() const {
  Eigen::VectorXd out(static_cast<Eigen::Index>(6 * last_.size()));
  for (std::size_t b = 0; b < last_.size(); ++b) {
    out.segment<6>(static_cast<Eigen::Index>(6 * b)) << last_[b].centroid.x(),
        last_[b].centroid.y(), last_[b].rotation, rate_[b].x(), rate_[b].y(), angular_rate_[b];
  }
  return out;
}

void BlockTracker::restore(const Eigen::VectorXd& state) {
  if (state.size() != static_cast<Eigen::Index>(6 * last_.size()))
    throw InputError("the checkpoint's block motions are of " + std::to_string(state.size() / 6) +
                     " blocks, the case has " + std::to_string(last_.size()) +
                     "; run the case from the start without --restart");
  for (std::size_t b = 0; b < last_.size(); ++b) {
    const auto i = static_cast<Eigen::Index>(6 * b);
    last_[b].centroid = Point2(state[i], state[i + 1]);
    last_[b].rotation = state[i + 2];
    rate_[b] = Point2(state[i + 3], state[i + 4]);
    angular_rate_[b] = state[i + 5];
  }
}

std::vector<BlockState> block_states(const Model& model,
                                     const ContactSystem* contact,
                                     const Scene& scene,
                                     std::span<const BlockMotion> motions,
                                     double speed_tolerance) {
  const std::size_t n_blocks = motions.size();
  std::vector<bool> supported(n_blocks, false);
  for (const SupportPoint& support : scene.supports) {
    if (support.point.element >= 0)
      supported[static_cast<std::size_t>(
          model.elements[static_cast<std::size_t>(support.point.element)].block)] = true;
  }
  std::vector<bool> closed(n_blocks, false);
  std::vector<bool> sliding(n_blocks, false);
  if (contact != nullptr) {
    for (const ContactPoint& point : contact->points()) {
      if (point.mode == ContactMode::open)
        continue;
      for (const int edge : {point.slave_edge, point.master}) {
        const int block = contact->edge_block(edge);
        const auto b = static_cast<std::size_t>(block);
        if (block < 0 || b >= n_blocks)
          continue;
        closed[b] = true;
        if (point.mode == ContactMode::slide)
          sliding[b] = true;
      }
    }
  }
  std::vector<BlockState> states(n_blocks, BlockState::resting);
  for (std::size_t b = 0; b < n_blocks; ++b) {
    const BlockMotion& m = motions[b];
    const double turning = std::abs(m.angular_velocity) * m.radius;
    const double speed = m.velocity.norm();
    if (speed + turning <= speed_tolerance)
      states[b] = BlockState::resting;
    else if (!closed[b] && !supported[b])
      states[b] = BlockState::free;
    else if (speed < turning)
      states[b] = BlockState::rotating;
    else if (sliding[b])
      states[b] = BlockState::sliding;
  }
  const std::vector<char> excavated = model.excavated_blocks();
  for (std::size_t b = 0; b < n_blocks && b < excavated.size(); ++b) {
    if (excavated[b] != 0)
      states[b] = BlockState::excavated;
  }
  return states;
}

namespace {

/// A CSV field: as it is, or quoted (quotes doubled) when it holds a comma, quote or newline.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos)
    return text;
  std::string out = "\"";
  for (const char c : text) {
    out += c;
    if (c == '"')
      out += '"';
  }
  return out + '"';
}

} // namespace

BlocksWriter::BlocksWriter(std::filesystem::path file, std::vector<std::string> materials)
    : materials_(std::move(materials)),
      rows_(std::move(file), std::string(blocks_header) + '\n', true) {}

BlocksWriter::BlocksWriter(std::filesystem::path file,
                           std::vector<std::string> materials,
                           std::uintmax_t keep_bytes)
    : materials_(std::move(materials)),
      rows_(std::move(file), std::string(blocks_header) + '\n', "that of blocks.csv", keep_bytes) {}

void BlocksWriter::write_step(long step,
                              double time,
                              std::span<const BlockMotion> motions,
                              std::span<const BlockState> states) {
  NMM_ASSERT(motions.size() == materials_.size() && states.size() == materials_.size(),
             "one motion and one state per block");
  std::string rows;
  char field[64];
  const auto add = [&](int length) {
    rows.append(field, static_cast<std::size_t>(std::clamp(length, 0, int{sizeof field} - 1)));
  };
  const auto number = [&](double value) {
    add(std::snprintf(field, sizeof field, ",%.17g", value));
  };
  for (std::size_t b = 0; b < motions.size(); ++b) {
    const BlockMotion& m = motions[b];
    add(std::snprintf(field, sizeof field, "%ld", step));
    number(time);
    add(std::snprintf(field, sizeof field, ",%zu,", b));
    rows += csv_field(materials_[b]);
    for (const double value :
         {m.centroid.x(), m.centroid.y(), m.displacement.x(), m.displacement.y(), m.rotation,
          m.velocity.x(), m.velocity.y(), m.angular_velocity})
      number(value);
    rows += ',';
    rows += block_state_name(states[b]);
    rows += '\n';
  }
  rows_.append(rows, "the rows of step " + std::to_string(step) + " (the steps before it stay)");
}

namespace {

std::vector<std::string> block_materials(const BlockTracker& tracker,
                                         const std::vector<std::string>& region_names) {
  std::vector<std::string> names;
  for (const int region : tracker.block_regions())
    names.push_back(static_cast<std::size_t>(region) < region_names.size()
                        ? region_names[static_cast<std::size_t>(region)]
                        : std::string());
  return names;
}

} // namespace

BlockOutput::BlockOutput(const Model& model,
                         std::vector<Point2> initial_points,
                         const std::vector<std::string>& region_names,
                         const std::filesystem::path& file,
                         std::optional<std::uintmax_t> keep_bytes,
                         bool step_rates,
                         double speed_tolerance)
    : tracker_(model, std::move(initial_points)),
      materials_(block_materials(tracker_, region_names)),
      writer_(keep_bytes ? BlocksWriter(file, materials_, *keep_bytes)
                         : BlocksWriter(file, materials_)),
      step_rates_(step_rates), speed_tolerance_(speed_tolerance) {}

void BlockOutput::write_step(long step,
                             double time,
                             const Model& model,
                             const TimeStepper& stepper) {
  const std::vector<BlockMotion> motions = tracker_.motions(model, stepper.velocity(), step_rates_);
  const std::vector<BlockState> states =
      block_states(model, stepper.contact(), stepper.scene(), motions, speed_tolerance_);
  writer_.write_step(step, time, motions, states);
}

std::vector<MovedBlock> BlockOutput::moved_blocks(double threshold) const {
  std::vector<MovedBlock> moved;
  const std::vector<Point2> displacements = tracker_.displacements();
  for (std::size_t b = 0; b < displacements.size(); ++b) {
    const double length = displacements[b].norm();
    if (length > threshold)
      moved.push_back(MovedBlock{static_cast<int>(b), materials_[b], length});
  }
  return moved;
}

} // namespace nmm
