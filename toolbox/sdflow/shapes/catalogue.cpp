#include "sdflow/shapes/catalogue.h"

#include "sdflow/errors.h"
#include "sdflow/shapes/packing.h"
#include "sdflow/shapes/smooth_union.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <utility>

namespace sdflow {
namespace {

//! Cylinder of `radius` about the segment a–b, capped flat: max(distance to the axis − radius,
//! distance beyond the caps). The caps sit inside the pieces the cylinder joins, so only the
//! lateral surface is ever part of the zero set.
Sample cylinder_piece(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius)
{
  const Eigen::Vector3d axis = (b - a).normalized();
  const double half = 0.5 * (b - a).norm();
  const Eigen::Vector3d d = p - 0.5 * (a + b);
  const double along = d.dot(axis);
  const Eigen::Vector3d radial = d - along * axis;
  const double r = radial.norm();
  const Sample side{r - radius, r > 0 ? Eigen::Vector3d(radial / r) : Eigen::Vector3d(axis.unitOrthogonal())};
  const Sample cap{std::abs(along) - half, along >= 0 ? axis : Eigen::Vector3d(-axis)};
  return side.value >= cap.value ? side : cap;
}

//! The solid pieces of a union: balls, capped cylinders and the half-space z ≤ plane_height.
struct PieceUnion {
  struct Ball {
    Eigen::Vector3d centre;
    double radius;
  };
  struct Rod {
    Eigen::Vector3d a, b;
    double radius;
  };
  std::vector<Ball> balls;
  std::vector<Rod> rods;
  bool has_plane = false;
  double plane_height = 0;
  double blend = 0;

  Sample evaluate(const Eigen::Vector3d& p) const
  {
    Sample s{std::numeric_limits<double>::infinity(), Eigen::Vector3d::UnitZ()};
    if (has_plane)
      s = {p.z() - plane_height, Eigen::Vector3d::UnitZ()};
    for (const auto& ball : balls)
      s = smooth_union(s, sphere_piece(p, ball.centre, ball.radius), blend);
    for (const auto& rod : rods)
      s = smooth_union(s, cylinder_piece(p, rod.a, rod.b, rod.radius), blend);
    return s;
  }
};

void attach(ImplicitSurface& surface, std::shared_ptr<const PieceUnion> pieces)
{
  surface.value = [pieces](const Eigen::Vector3d& p) { return pieces->evaluate(p).value; };
  surface.gradient = [pieces](const Eigen::Vector3d& p) { return pieces->evaluate(p).gradient; };
}

void require_positive(std::string_view shape, std::string_view what, double value)
{
  if (!(value > 0) || !std::isfinite(value))
    throw InvalidParameter(fmt::format("{}: {} must be a positive number, got {}", shape, what, value));
}

void require_blend(std::string_view shape, double blend, double limit)
{
  if (!(blend >= 0) || !(blend < limit))
    throw InvalidParameter(fmt::format("{}: blend {} must be in [0, {}) (below the smallest neck radius)", shape,
                                       blend, limit));
}

Eigen::AlignedBox3d padded_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double margin)
{
  return {lo - Eigen::Vector3d::Constant(margin), hi + Eigen::Vector3d::Constant(margin)};
}

} // namespace

ImplicitSurface sphere_shape(const SphereParameters& parameters)
{
  require_positive("sphere", "radius", parameters.radius);
  if (!parameters.centre.allFinite())
    throw InvalidParameter("sphere: centre must be finite");
  const double r = parameters.radius;
  const Eigen::Vector3d c = parameters.centre;
  ImplicitSurface s;
  s.name = "sphere";
  s.value = [c, r](const Eigen::Vector3d& p) { return (p - c).norm() - r; };
  s.gradient = [c](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - c;
    return d.norm() > 0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitZ();
  };
  s.box = padded_box(c - Eigen::Vector3d::Constant(r), c + Eigen::Vector3d::Constant(r), 0.1 * r);
  s.feature_size = r;
  return s;
}

ImplicitSurface ellipsoid_shape(const EllipsoidParameters& parameters)
{
  const double a = parameters.a, b = parameters.b, c = parameters.c;
  require_positive("ellipsoid", "semi-axis a", a);
  require_positive("ellipsoid", "semi-axis b", b);
  require_positive("ellipsoid", "semi-axis c", c);
  const Eigen::Vector3d inverse(1 / a, 1 / b, 1 / c);
  const double scale = std::min({a, b, c});
  ImplicitSurface s;
  s.name = "ellipsoid";
  s.value = [inverse, scale](const Eigen::Vector3d& p) { return scale * (p.cwiseProduct(inverse).norm() - 1); };
  s.gradient = [inverse, scale](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = p.cwiseProduct(inverse);
    const double n = q.norm();
    return n > 0 ? Eigen::Vector3d(scale * q.cwiseProduct(inverse) / n) : Eigen::Vector3d::UnitZ();
  };
  const Eigen::Vector3d half(a, b, c);
  s.box = padded_box(-half, half, 0.1 * scale);
  s.feature_size = scale;
  return s;
}

ImplicitSurface torus_shape(const TorusParameters& parameters)
{
  const double R = parameters.major, r = parameters.minor;
  require_positive("torus", "major radius", R);
  require_positive("torus", "minor radius", r);
  if (!(r < R))
    throw InvalidParameter(fmt::format("torus: minor radius {} must be less than the major radius {} (a horn or "
                                       "spindle torus is not a smooth surface)", r, R));
  ImplicitSurface s;
  s.name = "torus";
  s.value = [R, r](const Eigen::Vector3d& p) { return std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r; };
  s.gradient = [R](const Eigen::Vector3d& p) {
    const double rho = std::hypot(p.x(), p.y());
    const Eigen::Vector3d radial = rho > 0 ? Eigen::Vector3d(p.x() / rho, p.y() / rho, 0) : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d d = (rho - R) * radial + p.z() * Eigen::Vector3d::UnitZ();
    return d.norm() > 0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitZ();
  };
  s.box = padded_box(Eigen::Vector3d(-R - r, -R - r, -r), Eigen::Vector3d(R + r, R + r, r), 0.1 * r);
  s.feature_size = std::min(r, R - r);
  return s;
}

ImplicitSurface dumbbell_shape(const DumbbellParameters& parameters)
{
  const auto profile = std::make_shared<const DumbbellProfile>(parameters);
  ImplicitSurface s;
  s.name = "dumbbell";
  s.value = [profile](const Eigen::Vector3d& p) { return profile->signed_distance(p.x(), std::hypot(p.y(), p.z())); };
  s.gradient = [profile](const Eigen::Vector3d& p) {
    const double r = std::hypot(p.y(), p.z());
    double gx = 0, gr = 0;
    profile->signed_distance(p.x(), r, &gx, &gr);
    const Eigen::Vector2d radial = r > 0 ? Eigen::Vector2d(p.y() / r, p.z() / r) : Eigen::Vector2d(1, 0);
    return Eigen::Vector3d(gx, gr * radial.x(), gr * radial.y());
  };
  const double half = profile->half_length(), R = parameters.radius;
  s.box = padded_box(Eigen::Vector3d(-half, -R, -R), Eigen::Vector3d(half, R, R), 0.1 * R);
  s.feature_size = parameters.neck_width; // the isthmus diameter; the octree refines around it
  return s;
}

ImplicitSurface sintering_cluster_shape(const SinteringParameters& parameters)
{
  const double R = parameters.radius, rho = parameters.neck_radius;
  require_positive("sintering", "sphere radius", R);
  require_positive("sintering", "neck radius", rho);
  if (!(rho < R))
    throw InvalidParameter(fmt::format("sintering: neck radius {} must be less than the sphere radius {}", rho, R));
  require_blend("sintering", parameters.blend, rho);
  auto pieces = std::make_shared<PieceUnion>();
  pieces->blend = parameters.blend;
  for (int i = 0; i < 8; ++i)
    pieces->balls.push_back({R * Eigen::Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1), R});
  // Touching pairs differ in exactly one coordinate sign: the 12 edges of the cube.
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis)
      if (!(i & (1 << axis)))
        pieces->rods.push_back({pieces->balls[i].centre, pieces->balls[i | (1 << axis)].centre, rho});
  ImplicitSurface s;
  s.name = "sintering";
  attach(s, pieces);
  s.box = padded_box(Eigen::Vector3d::Constant(-2 * R), Eigen::Vector3d::Constant(2 * R), 0.1 * R);
  // The neck and the hole in the middle of each cube face (radius (√2 − 1) R).
  s.feature_size = std::min(rho, (std::numbers::sqrt2 - 1) * R);
  return s;
}

ImplicitSurface spheres_on_plane_shape(const SpheresOnPlaneParameters& parameters)
{
  const double R = parameters.radius, plane_neck = parameters.plane_neck_radius,
               sphere_neck = parameters.sphere_neck_radius, disk = parameters.disk_radius;
  const std::string_view name = "spheres-on-plane";
  require_positive(name, "sphere radius", R);
  require_positive(name, "plane neck radius", plane_neck);
  require_positive(name, "sphere neck radius", sphere_neck);
  require_positive(name, "disk radius", disk);
  if (!(plane_neck < R) || !(sphere_neck < R))
    throw InvalidParameter(fmt::format("{}: neck radii ({}, {}) must be less than the sphere radius {}", name,
                                       plane_neck, sphere_neck, R));
  // Centres on the circle of radius 2R/√3 about the z axis: mutually touching.
  const double ring = 2 * R / std::numbers::sqrt3;
  if (!(disk > ring + R))
    throw InvalidParameter(fmt::format("{}: disk radius {} must exceed {} so the spheres stand inside the disk",
                                       name, disk, ring + R));
  require_blend(name, parameters.blend, std::min(plane_neck, sphere_neck));
  auto pieces = std::make_shared<PieceUnion>();
  pieces->blend = parameters.blend;
  pieces->has_plane = true;
  pieces->plane_height = -R;
  for (int i = 0; i < 3; ++i) {
    const double angle = std::numbers::pi / 2 + 2 * std::numbers::pi * i / 3;
    const Eigen::Vector3d centre(ring * std::cos(angle), ring * std::sin(angle), 0);
    pieces->balls.push_back({centre, R});
    // Down to well inside the half-space, so the cap is hidden.
    pieces->rods.push_back({centre, centre - Eigen::Vector3d(0, 0, 2 * R), plane_neck});
  }
  for (int i = 0; i < 3; ++i)
    pieces->rods.push_back({pieces->balls[i].centre, pieces->balls[(i + 1) % 3].centre, sphere_neck});
  ImplicitSurface s;
  s.name = std::string(name);
  attach(s, pieces);
  s.clip = [disk](const Eigen::Vector3d& p) { return std::hypot(p.x(), p.y()) - disk; };
  s.clip_gradient = [](const Eigen::Vector3d& p) {
    const double rho = std::hypot(p.x(), p.y());
    return rho > 0 ? Eigen::Vector3d(p.x() / rho, p.y() / rho, 0) : Eigen::Vector3d::UnitX();
  };
  s.box = padded_box(Eigen::Vector3d(-disk, -disk, -R), Eigen::Vector3d(disk, disk, R), 0.1 * R);
  // Necks, and the hole between the three spheres (radius 2R/√3 − R).
  s.feature_size = std::min({plane_neck, sphere_neck, ring - R});
  return s;
}

ImplicitSurface cuboid_island_shape(const CuboidIslandParameters& parameters)
{
  const auto [a, b, c, r] = parameters;
  const std::string_view name = "cuboid-island";
  require_positive(name, "length a", a);
  require_positive(name, "length b", b);
  require_positive(name, "height c", c);
  require_positive(name, "rounding radius", r);
  if (!(r < std::min({a / 2, b / 2, c})))
    throw InvalidParameter(fmt::format("{}: rounding radius {} must be less than min(a/2, b/2, c) = {}", name, r,
                                       std::min({a / 2, b / 2, c})));
  // The rounded box's signed distance: q = |p| − (h − r), f = |max(q, 0)| + min(max_i q_i, 0) − r.
  const Eigen::Vector3d inner = Eigen::Vector3d(a / 2, b / 2, c) - Eigen::Vector3d::Constant(r);
  const auto excess = [inner](const Eigen::Vector3d& p) { return Eigen::Vector3d(p.cwiseAbs() - inner); };
  ImplicitSurface s;
  s.name = std::string(name);
  s.value = [excess, radius = r](const Eigen::Vector3d& p) { // a structured binding is named by an init-capture (C++20)
    const Eigen::Vector3d q = excess(p);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - radius;
  };
  s.gradient = [excess](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = excess(p), outside = q.cwiseMax(0.0);
    const Eigen::Vector3d sign(p.x() < 0 ? -1 : 1, p.y() < 0 ? -1 : 1, p.z() < 0 ? -1 : 1);
    if (outside.norm() > 0)
      return Eigen::Vector3d(sign.cwiseProduct(outside) / outside.norm());
    Eigen::Index axis = 0;
    q.maxCoeff(&axis);
    return Eigen::Vector3d(sign[axis] * Eigen::Vector3d::Unit(axis));
  };
  s.clip = [](const Eigen::Vector3d& p) { return -p.z(); };
  s.clip_gradient = [](const Eigen::Vector3d&) { return Eigen::Vector3d(-Eigen::Vector3d::UnitZ()); };
  s.box = padded_box(Eigen::Vector3d(-a / 2, -b / 2, 0), Eigen::Vector3d(a / 2, b / 2, c), 0.1 * std::min({a, b, c}));
  s.feature_size = std::min({a, b, c});
  return s;
}

ImplicitSurface film_with_hole_shape(const FilmWithHoleParameters& parameters)
{
  const auto [side, h, hole, r] = parameters;
  const std::string_view name = "film-with-hole";
  require_positive(name, "side", side);
  require_positive(name, "thickness", h);
  require_positive(name, "hole radius", hole);
  require_positive(name, "rounding radius", r);
  if (!(r < h))
    throw InvalidParameter(fmt::format("{}: rounding radius {} must be less than the thickness {}", name, r, h));
  if (!(hole + 2 * r < side / 2))
    throw InvalidParameter(
        fmt::format("{}: the hole radius {} plus twice the rounding {} must be less than half the side {}", name, hole,
                    r, side / 2));
  const ImplicitSurface film = cuboid_island_shape({side, side, h, r});
  ImplicitSurface s;
  s.name = std::string(name);
  // The film less the cylinder: the smooth maximum max(f, g) = −smin(−f, −g), g = hole − ρ.
  const auto sample = [film, hole = hole, r = r](const Eigen::Vector3d& p) {
    const double rho = std::hypot(p.x(), p.y());
    const Eigen::Vector3d radial = rho > 0 ? Eigen::Vector3d(p.x() / rho, p.y() / rho, 0) : Eigen::Vector3d::UnitX();
    const Sample outside = smooth_union({-film.value(p), -film.gradient(p)}, {rho - hole, radial}, r);
    return Sample{-outside.value, -outside.gradient};
  };
  s.value = [sample](const Eigen::Vector3d& p) { return sample(p).value; };
  s.gradient = [sample](const Eigen::Vector3d& p) { return sample(p).gradient; };
  s.clip = film.clip;
  s.clip_gradient = film.clip_gradient;
  s.box = film.box;
  s.feature_size = std::min({h, hole, side});
  return s;
}

namespace {

struct Entry {
  ShapeDescription description;
  std::function<ImplicitSurface(const std::function<double(const std::string&)>&)> make;
};

const std::vector<Entry>& entries()
{
  static const std::vector<Entry> list = [] {
    std::vector<Entry> e;
    const SphereParameters sp;
    e.push_back({{"sphere", "sphere (unit sphere of §4.4)",
                  {{"radius", sp.radius, "radius"},
                   {"cx", 0, "centre x"},
                   {"cy", 0, "centre y"},
                   {"cz", 0, "centre z"}}},
                 [](const auto& get) {
                   return sphere_shape({get("radius"), Eigen::Vector3d(get("cx"), get("cy"), get("cz"))});
                 }});
    const EllipsoidParameters ep;
    e.push_back({{"ellipsoid", "ellipsoid x²/a² + y²/b² + z²/c² = 1 (§4.5)",
                  {{"a", ep.a, "semi-axis along x"}, {"b", ep.b, "semi-axis along y"}, {"c", ep.c, "semi-axis along z"}}},
                 [](const auto& get) { return ellipsoid_shape({get("a"), get("b"), get("c")}); }});
    const TorusParameters tp;
    e.push_back({{"torus", "torus about the z axis (§4.1)",
                  {{"major", tp.major, "radius R of the centre circle"}, {"minor", tp.minor, "tube radius r < R"}}},
                 [](const auto& get) { return torus_shape({get("major"), get("minor")}); }});
    const DumbbellParameters dp;
    e.push_back({{"dumbbell", "two spheres joined by a parabolic isthmus, C¹ profile, axis x (§3.2.2)",
                  {{"radius", dp.radius, "radius R of the end circles"},
                   {"neck-width", dp.neck_width, "width of the isthmus at its narrowest"},
                   {"separation", dp.separation, "distance between the end-circle centres (> 2R)"}}},
                 [](const auto& get) { return dumbbell_shape({get("radius"), get("neck-width"), get("separation")}); }});
    const SinteringParameters sintering;
    e.push_back({{"sintering", "8 touching spheres at (±r, ±r, ±r) joined by contact cylinders, genus 5 (§4.2)",
                  {{"radius", sintering.radius, "sphere radius r"},
                   {"neck-radius", sintering.neck_radius, "radius of the contact cylinders (√59/10)"},
                   {"blend", sintering.blend, "smooth-union width (0 = sharp creases)"}}},
                 [](const auto& get) { return sintering_cluster_shape({get("radius"), get("neck-radius"), get("blend")}); }});
    const SpheresOnPlaneParameters plane;
    e.push_back({{"spheres-on-plane",
                  "3 touching spheres on the plane z = -r, joined by contact cylinders, plane cut to a disk: "
                  "genus 3, one boundary loop (§4.3)",
                  {{"radius", plane.radius, "sphere radius r"},
                   {"plane-neck-radius", plane.plane_neck_radius, "radius of the sphere-plane cylinders"},
                   {"sphere-neck-radius", plane.sphere_neck_radius, "radius of the sphere-sphere cylinders"},
                   {"disk-radius", plane.disk_radius, "radius of the disk the plane is cut to"},
                   {"blend", plane.blend, "smooth-union width (0 = sharp creases)"}}},
                 [](const auto& get) {
                   return spheres_on_plane_shape({get("radius"), get("plane-neck-radius"), get("sphere-neck-radius"),
                                            get("disk-radius"), get("blend")});
                 }});
    const CuboidIslandParameters island;
    e.push_back({{"cuboid-island",
                  "a rounded box standing on the substrate z = 0, open at the bottom, its boundary loop on the plane "
                  "(for boundary = \"substrate\")",
                  {{"a", island.a, "length along x"},
                   {"b", island.b, "length along y"},
                   {"c", island.c, "height above z = 0"},
                   {"radius", island.radius, "rounding radius of the edges and corners"}}},
                 [](const auto& get) {
                   return cuboid_island_shape({get("a"), get("b"), get("c"), get("radius")});
                 }});
    const FilmWithHoleParameters film;
    e.push_back({{"film-with-hole",
                  "a square film of thickness h on the substrate z = 0 with a circular hole down to it; its outer edges "
                  "and the hole's rim are both contact lines (for boundary = \"substrate\")",
                  {{"side", film.side, "the film's side along x and y"},
                   {"thickness", film.thickness, "its thickness h"},
                   {"hole", film.hole, "the radius of the hole"},
                   {"radius", film.radius, "rounding radius of the outer edges and of the hole's top rim"}}},
                 [](const auto& get) {
                   return film_with_hole_shape({get("side"), get("thickness"), get("hole"), get("radius")});
                 }});
    const LatticePacking lattice;
    const RandomPacking random;
    e.push_back({{"packing",
                  "spheres joined where they overlap (a powder compact): an nx × ny × nz lattice, or with count > 0 "
                  "a seeded random cluster (a tree, or with contacts = 2 loops); from a CSV of x,y,z,r with `sdflow shape packing --spheres FILE`",
                  {{"nx", static_cast<double>(lattice.nx), "lattice spheres along x"},
                   {"ny", static_cast<double>(lattice.ny), "lattice spheres along y"},
                   {"nz", static_cast<double>(lattice.nz), "lattice spheres along z"},
                   {"count", 0, "random spheres instead of the lattice (0: the lattice)"},
                   {"radius", lattice.radius, "sphere radius"},
                   {"spacing", lattice.spacing, "distance between the centres of touching spheres (< 2 radius: a neck)"},
                   {"min-distance", random.min_distance,
                    "random: least distance from a new sphere's centre to all but the one it grew from"},
                   {"seed", static_cast<double>(random.seed), "random: seed of the generator"},
                   {"contacts", static_cast<double>(random.contacts),
                    "random: spheres each new one touches, 1 (a tree) or 2 (it bridges two: loops, pore channels)"},
                   {"candidates", static_cast<double>(random.candidates),
                    "random: placements drawn for each sphere, the one nearest the centroid kept (> 1: a compact cluster)"},
                   {"blend", PackingSurfaceOptions{}.blend, "smooth-union width (0 = sharp creases)"}}},
                 [](const auto& get) {
                   const auto whole = [&](const char* name, double low) {
                     const double v = get(name);
                     if (!(v >= low) || v != std::floor(v) || v > 1e9)
                       throw InvalidParameter(fmt::format("packing: {} must be a whole number ≥ {}, got {}", name,
                                                          low, v));
                     return v;
                   };
                   const int count = static_cast<int>(whole("count", 0));
                   const std::vector<PackedSphere> spheres =
                       count > 0 ? random_packing({.count = count,
                                                   .radius = get("radius"),
                                                   .spacing = get("spacing"),
                                                   .min_distance = get("min-distance"),
                                                   .seed = static_cast<std::uint64_t>(whole("seed", 0)),
                                                   .contacts = static_cast<int>(whole("contacts", 1)),
                                                   .candidates = static_cast<int>(whole("candidates", 1))})
                                 : lattice_packing({.nx = static_cast<int>(whole("nx", 1)),
                                                    .ny = static_cast<int>(whole("ny", 1)),
                                                    .nz = static_cast<int>(whole("nz", 1)),
                                                    .radius = get("radius"),
                                                    .spacing = get("spacing")});
                   return packing_surface(spheres, {.blend = get("blend")});
                 }});
    return e;
  }();
  return list;
}

} // namespace

const std::vector<ShapeDescription>& shape_catalogue()
{
  static const std::vector<ShapeDescription> list = [] {
    std::vector<ShapeDescription> d;
    for (const auto& e : entries())
      d.push_back(e.description);
    return d;
  }();
  return list;
}

ImplicitSurface make_shape(std::string_view name, const std::map<std::string, double>& parameters)
{
  const auto& list = entries();
  const auto entry = std::find_if(list.begin(), list.end(), [&](const Entry& e) { return e.description.name == name; });
  if (entry == list.end()) {
    std::string names;
    for (const auto& e : list)
      names += (names.empty() ? "" : ", ") + e.description.name;
    throw InvalidParameter(fmt::format("unknown shape '{}'; the shapes are: {}", name, names));
  }
  const auto& known = entry->description.parameters;
  for (const auto& [key, value] : parameters) {
    if (std::none_of(known.begin(), known.end(), [&key = key](const ShapeParameter& p) { return p.name == key; })) {
      std::string names;
      for (const auto& p : known)
        names += (names.empty() ? "" : ", ") + p.name;
      throw InvalidParameter(fmt::format("shape '{}' has no parameter '{}'; its parameters are: {}", name, key, names));
    }
  }
  const auto get = [&](const std::string& key) {
    if (const auto it = parameters.find(key); it != parameters.end())
      return it->second;
    return std::find_if(known.begin(), known.end(), [&](const ShapeParameter& p) { return p.name == key; })->default_value;
  };
  return entry->make(get);
}

} // namespace sdflow
