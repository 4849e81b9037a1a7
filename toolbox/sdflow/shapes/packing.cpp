#include "sdflow/shapes/packing.h"

#include "sdflow/errors.h"
#include "sdflow/shapes/smooth_union.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>

namespace sdflow {
namespace {

void require_positive(std::string_view what, double value)
{
  if (!(value > 0) || !std::isfinite(value))
    throw InvalidParameter(fmt::format("packing: {} must be a positive number, got {}", what, value));
}

//! A uniform double in [0, 1) from the generator's top 53 bits: the same numbers on every
//! standard library, unlike std::uniform_real_distribution.
double unit_uniform(std::mt19937_64& generator) { return static_cast<double>(generator() >> 11) * 0x1.0p-53; }

Eigen::Vector3d random_direction(std::mt19937_64& generator)
{
  const double z = 2 * unit_uniform(generator) - 1, phi = 2 * std::numbers::pi * unit_uniform(generator);
  const double rho = std::sqrt(std::max(0.0, 1 - z * z));
  return {rho * std::cos(phi), rho * std::sin(phi), z};
}

//! The spheres in a uniform grid of cells at least as wide as the largest reach, for the union's
//! evaluation: only the spheres of the 27 cells around a point can be nearest to it.
class SphereGrid {
public:
  explicit SphereGrid(const std::vector<PackedSphere>& spheres) : spheres_(spheres)
  {
    double largest = 0;
    for (const auto& s : spheres)
      largest = std::max(largest, s.radius);
    cell_ = 2 * largest;
    for (const auto& s : spheres)
      box_.extend(s.centre);
    const Eigen::Vector3d extent = box_.sizes() / cell_;
    for (int a = 0; a < 3; ++a)
      size_[a] = static_cast<int>(std::floor(extent[a])) + 1;
    cells_.resize(static_cast<std::size_t>(size_[0]) * size_[1] * size_[2]);
    for (std::size_t i = 0; i < spheres.size(); ++i)
      cells_[index(cell_of(spheres[i].centre))].push_back(static_cast<int>(i));
  }

  //! The union's value and gradient at p: the (smooth) minimum over the spheres whose distance
  //! can be the least (all of them when p is far from the packing).
  Sample evaluate(const Eigen::Vector3d& p, double blend) const
  {
    Sample s{std::numeric_limits<double>::infinity(), Eigen::Vector3d::UnitZ()};
    const Eigen::Array3i c = cell_of(p);
    const Eigen::Vector3d clamped = p.cwiseMax(box_.min()).cwiseMin(box_.max());
    if ((p - clamped).norm() > cell_) {
      for (const auto& sphere : spheres_)
        s = smooth_union(s, sphere_piece(p, sphere.centre, sphere.radius), blend);
      return s;
    }
    for (int i = std::max(0, c[0] - 1); i <= std::min(size_[0] - 1, c[0] + 1); ++i)
      for (int j = std::max(0, c[1] - 1); j <= std::min(size_[1] - 1, c[1] + 1); ++j)
        for (int k = std::max(0, c[2] - 1); k <= std::min(size_[2] - 1, c[2] + 1); ++k)
          for (int n : cells_[index({i, j, k})])
            s = smooth_union(s, sphere_piece(p, spheres_[n].centre, spheres_[n].radius), blend);
    if (!std::isfinite(s.value)) // near the packing but with no sphere in reach: any will do
      s = sphere_piece(p, spheres_[0].centre, spheres_[0].radius);
    return s;
  }

private:
  Eigen::Array3i cell_of(const Eigen::Vector3d& p) const
  {
    Eigen::Array3i c;
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp(static_cast<int>(std::floor((p[a] - box_.min()[a]) / cell_)), 0, size_[a] - 1);
    return c;
  }
  std::size_t index(const Eigen::Array3i& c) const
  {
    return (static_cast<std::size_t>(c[0]) * size_[1] + c[1]) * size_[2] + c[2];
  }

  std::vector<PackedSphere> spheres_;
  Eigen::AlignedBox3d box_;
  double cell_ = 1;
  int size_[3] = {1, 1, 1};
  std::vector<std::vector<int>> cells_;
};

} // namespace

std::vector<PackedSphere> lattice_packing(const LatticePacking& l)
{
  if (l.nx < 1 || l.ny < 1 || l.nz < 1 || static_cast<long>(l.nx) * l.ny * l.nz > 100000)
    throw InvalidParameter(fmt::format("packing: the lattice {} × {} × {} must have 1 to 100000 spheres", l.nx, l.ny,
                                       l.nz));
  require_positive("radius", l.radius);
  require_positive("spacing", l.spacing);
  std::vector<PackedSphere> spheres;
  for (int i = 0; i < l.nx; ++i)
    for (int j = 0; j < l.ny; ++j)
      for (int k = 0; k < l.nz; ++k)
        spheres.push_back({l.spacing * Eigen::Vector3d(i, j, k), l.radius});
  return spheres;
}

namespace {

//! True when `centre` is at least min_distance from every sphere but those it was placed to touch.
bool has_room(const std::vector<PackedSphere>& spheres, const Eigen::Vector3d& centre, std::size_t touched_a,
              std::size_t touched_b, double min_distance)
{
  for (std::size_t k = 0; k < spheres.size(); ++k)
    if (k != touched_a && k != touched_b && (spheres[k].centre - centre).norm() < min_distance)
      return false;
  return true;
}

//! One try at a sphere touching spheres[a] only: at `spacing` in a uniform direction.
std::optional<PackedSphere> grow_from_one(const std::vector<PackedSphere>& spheres, const RandomPacking& r,
                                          std::mt19937_64& generator)
{
  const auto a = std::min(spheres.size() - 1, static_cast<std::size_t>(unit_uniform(generator) * spheres.size()));
  const Eigen::Vector3d centre = spheres[a].centre + r.spacing * random_direction(generator);
  if (!has_room(spheres, centre, a, a, r.min_distance))
    return std::nullopt;
  return PackedSphere{centre, r.radius};
}

//! One try at a sphere bridging two spheres a, b that do not touch (min_distance ≤ |ab| < 2 spacing):
//! its centre on the circle of points at `spacing` from both, at a uniform angle.
std::optional<PackedSphere> bridge_two(const std::vector<PackedSphere>& spheres, const RandomPacking& r,
                                       std::mt19937_64& generator)
{
  const auto a = std::min(spheres.size() - 1, static_cast<std::size_t>(unit_uniform(generator) * spheres.size()));
  std::vector<std::size_t> partners;
  for (std::size_t b = 0; b < spheres.size(); ++b) {
    const double d = (spheres[b].centre - spheres[a].centre).norm();
    if (b != a && d >= r.min_distance && d < 2 * r.spacing)
      partners.push_back(b);
  }
  if (partners.empty())
    return std::nullopt;
  const auto b = partners[std::min(partners.size() - 1, static_cast<std::size_t>(unit_uniform(generator) * partners.size()))];
  const Eigen::Vector3d axis = spheres[b].centre - spheres[a].centre;
  const double half = axis.norm() / 2;
  const Eigen::Vector3d u = axis / (2 * half);
  Eigen::Vector3d e1 = random_direction(generator);
  e1 -= e1.dot(u) * u;
  if (e1.norm() < 1e-6)
    return std::nullopt;
  e1.normalize();
  const Eigen::Vector3d e2 = u.cross(e1);
  const double phi = 2 * std::numbers::pi * unit_uniform(generator);
  const double rho = std::sqrt(r.spacing * r.spacing - half * half);
  const Eigen::Vector3d centre = spheres[a].centre + half * u + rho * (std::cos(phi) * e1 + std::sin(phi) * e2);
  if (!has_room(spheres, centre, a, b, r.min_distance))
    return std::nullopt;
  return PackedSphere{centre, r.radius};
}

} // namespace

std::vector<PackedSphere> random_packing(const RandomPacking& r)
{
  if (r.count < 1 || r.count > 100000)
    throw InvalidParameter(fmt::format("packing: the number of random spheres must be in [1, 100000], got {}", r.count));
  require_positive("radius", r.radius);
  require_positive("spacing", r.spacing);
  if (!(r.min_distance >= r.spacing) || !std::isfinite(r.min_distance))
    throw InvalidParameter(fmt::format("packing: min-distance {} must be at least the spacing {}", r.min_distance,
                                       r.spacing));
  if (r.contacts != 1 && r.contacts != 2)
    throw InvalidParameter(fmt::format("packing: contacts must be 1 (a tree) or 2 (loops), got {}", r.contacts));
  if (r.candidates < 1 || r.candidates > 1000)
    throw InvalidParameter(fmt::format("packing: candidates must be in [1, 1000], got {}", r.candidates));
  std::mt19937_64 generator(r.seed);
  std::vector<PackedSphere> spheres{{Eigen::Vector3d::Zero(), r.radius}};
  Eigen::Vector3d centre_sum = Eigen::Vector3d::Zero();
  while (static_cast<int>(spheres.size()) < r.count) {
    const auto place = [&]() {
      std::optional<PackedSphere> next;
      for (int attempt = 0; attempt < r.attempts_per_sphere && !next && r.contacts == 2; ++attempt)
        next = bridge_two(spheres, r, generator);
      for (int attempt = 0; attempt < r.attempts_per_sphere && !next; ++attempt)
        next = grow_from_one(spheres, r, generator);
      return next;
    };
    const Eigen::Vector3d centroid = centre_sum / static_cast<double>(spheres.size());
    std::optional<PackedSphere> next = place();
    for (int candidate = 1; candidate < r.candidates && next; ++candidate)
      if (const auto other = place(); other && (other->centre - centroid).norm() < (next->centre - centroid).norm())
        next = other;
    if (!next)
      throw InvalidParameter(fmt::format("packing: no place found for sphere {} of {} in {} attempts (spacing {}, "
                                         "min-distance {}): lower min-distance or the count",
                                         spheres.size() + 1, r.count, r.attempts_per_sphere, r.spacing,
                                         r.min_distance));
    spheres.push_back(*next);
    centre_sum += next->centre;
  }
  return spheres;
}

std::vector<PackedSphere> read_packing_csv(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in)
    throw IoError(fmt::format("{}: cannot open the sphere list", file.string()));
  std::vector<PackedSphere> spheres;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#')
      continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');)
      fields.push_back(f);
    std::array<double, 4> values{};
    bool numeric = fields.size() == 4;
    for (std::size_t i = 0; numeric && i < 4; ++i) {
      std::size_t used = 0;
      try {
        values[i] = std::stod(fields[i], &used);
      } catch (const std::exception&) {
        numeric = false;
        break;
      }
      numeric = fields[i].find_first_not_of(" \t", used) == std::string::npos;
    }
    if (!numeric) {
      if (spheres.empty() && line.find_first_of("0123456789") == std::string::npos)
        continue; // a header of names
      throw IoError(fmt::format("{}:{}: expected x,y,z,r (four numbers), got '{}'", file.string(), number, line));
    }
    const PackedSphere s{{values[0], values[1], values[2]}, values[3]};
    if (!s.centre.allFinite() || !(s.radius > 0) || !std::isfinite(s.radius))
      throw InvalidParameter(fmt::format("{}:{}: a sphere needs a finite centre and a radius > 0, got '{}'",
                                         file.string(), number, line));
    spheres.push_back(s);
  }
  if (spheres.empty())
    throw IoError(fmt::format("{}: no sphere (one line x,y,z,r per sphere)", file.string()));
  return spheres;
}

double packing_feature_size(const std::vector<PackedSphere>& spheres)
{
  double size = std::numeric_limits<double>::infinity();
  for (const auto& s : spheres)
    size = std::min(size, s.radius);
  // O(n²) over pairs: packings meshed on a grid are far smaller than where this would matter.
  for (std::size_t i = 0; i < spheres.size(); ++i)
    for (std::size_t j = i + 1; j < spheres.size(); ++j) {
      const double d = (spheres[i].centre - spheres[j].centre).norm();
      const double ri = spheres[i].radius, rj = spheres[j].radius;
      if (d >= ri + rj) {
        if (d - ri - rj < std::min(ri, rj))
          size = std::min(size, d - ri - rj);
      } else if (d > std::abs(ri - rj)) {
        // The circle where the spheres meet lies at x = (d² + ri² − rj²)/(2d) from centre i.
        const double x = (d * d + ri * ri - rj * rj) / (2 * d);
        size = std::min(size, std::sqrt(std::max(0.0, ri * ri - x * x)));
      }
    }
  return size;
}

ImplicitSurface packing_surface(const std::vector<PackedSphere>& spheres, const PackingSurfaceOptions& options)
{
  if (spheres.empty())
    throw InvalidParameter("packing: no sphere");
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    if (!spheres[i].centre.allFinite())
      throw InvalidParameter(fmt::format("packing: sphere {} has a centre that is not finite", i + 1));
    require_positive(fmt::format("the radius of sphere {}", i + 1), spheres[i].radius);
  }
  for (std::size_t i = 0; i < spheres.size(); ++i)
    for (std::size_t j = i + 1; j < spheres.size(); ++j)
      if ((spheres[i].centre - spheres[j].centre).norm() <= std::abs(spheres[i].radius - spheres[j].radius))
        throw InvalidParameter(fmt::format("packing: sphere {} lies inside sphere {} (or they coincide)",
                                           spheres[i].radius < spheres[j].radius ? i + 1 : j + 1,
                                           spheres[i].radius < spheres[j].radius ? j + 1 : i + 1));
  const double feature = packing_feature_size(spheres);
  if (!(feature > 0))
    throw InvalidParameter("packing: two spheres touch at a single point (a neck or gap of zero width): move them "
                           "apart or together");
  if (!(options.blend >= 0) || !(options.blend < feature))
    throw InvalidParameter(fmt::format("packing: blend {} must be in [0, {:.4g}) (below the thinnest neck or gap)",
                                       options.blend, feature));
  auto grid = std::make_shared<const SphereGrid>(spheres);
  const double blend = options.blend;
  ImplicitSurface s;
  s.name = fmt::format("packing of {} spheres", spheres.size());
  s.value = [grid, blend](const Eigen::Vector3d& p) { return grid->evaluate(p, blend).value; };
  s.gradient = [grid, blend](const Eigen::Vector3d& p) { return grid->evaluate(p, blend).gradient; };
  Eigen::AlignedBox3d box;
  double largest = 0;
  for (const auto& sphere : spheres) {
    box.extend(sphere.centre - Eigen::Vector3d::Constant(sphere.radius));
    box.extend(sphere.centre + Eigen::Vector3d::Constant(sphere.radius));
    largest = std::max(largest, sphere.radius);
  }
  s.box = {box.min() - Eigen::Vector3d::Constant(0.1 * largest), box.max() + Eigen::Vector3d::Constant(0.1 * largest)};
  s.feature_size = feature;
  return s;
}

} // namespace sdflow
