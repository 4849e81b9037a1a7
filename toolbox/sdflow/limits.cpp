#include "sdflow/limits.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <unistd.h>

namespace sdflow {
namespace {

//! Physical memory of this machine in bytes (0 when unknown).
double physical_memory()
{
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

std::string gigabytes(double bytes) { return fmt::format("{:.3g} GB", bytes / 1e9); }

} // namespace

double estimated_vertices(double area, double edge_length)
{
  const double triangle = std::sqrt(3.0) / 4.0 * edge_length * edge_length;
  return triangle > 0 ? area / triangle / 2.0 : std::numeric_limits<double>::infinity();
}

double estimated_vertices_in_box(const Eigen::AlignedBox3d& box, double edge_length)
{
  if (box.isEmpty())
    return 0;
  const Eigen::Vector3d d = box.sizes();
  return estimated_vertices((d.x() * d.y() + d.y() * d.z() + d.z() * d.x()), edge_length);
}

void check_surface_size(double vertices, std::string_view what, const SizeLimits& limits, bool check_minimum)
{
  if (limits.force)
    return;
  const double bytes = vertices * limits.bytes_per_vertex;
  const double memory = physical_memory();
  if (!(vertices <= limits.max_vertices))
    throw InvalidParameter(fmt::format("{}: the surface would have about {:.3g} vertices (some {} of memory), more "
                                       "than the limit of {:.3g}; choose a coarser resolution{}",
                                       what, vertices, gigabytes(bytes), limits.max_vertices, or_force(limits)));
  if (memory > 0 && bytes > memory / 2)
    throw InvalidParameter(fmt::format("{}: the surface would have about {:.3g} vertices and need some {}, more "
                                       "than half of this machine's {}; choose a coarser resolution{}",
                                       what, vertices, gigabytes(bytes), gigabytes(memory), or_force(limits)));
  if (check_minimum && vertices < limits.min_vertices)
    throw InvalidParameter(fmt::format("{}: the surface would have about {:.3g} vertices, fewer than the {:g} it "
                                       "needs to keep its shape: the edge length is too long for the surface; "
                                       "choose a shorter one{}", what, vertices, limits.min_vertices, or_force(limits)));
}

void check_remeshed_size(const Mesh& mesh, double edge_length, std::string_view what, const SizeLimits& limits)
{
  if (!(edge_length > 0))
    return; // the default: the mesh's own mean edge length
  check_surface_size(estimated_vertices(surface_area(mesh), edge_length), what, limits);
}

std::string or_force(const SizeLimits& limits)
{
  return limits.force_option.empty() ? std::string() : ", or " + limits.force_option;
}

void check_end_time(const Mesh& mesh, double end_time, double constant_tau, const SizeLimits& limits,
                    const UserTerms& terms)
{
  if (limits.force || !std::isfinite(end_time))
    return;
  Eigen::AlignedBox3d box;
  for (const auto v : mesh.vertices())
    box.extend(to_eigen(mesh.point(v)));
  const double diagonal = box.isEmpty() ? 0.0 : box.diagonal().norm();
  const double latest = limits.max_end_time_scales * std::pow(diagonal, 4);
  if (std::isfinite(diagonal) && end_time > latest)
    throw InvalidParameter(fmt::format("{} is more than {:g} times D⁴ = {:.3g} for the surface's "
                                       "bounding-box diagonal D = {:.3g}: surface diffusion brings a body of that "
                                       "size to rest long before (its slowest shape mode decays within about D⁴ / "
                                       "3500), so the run would step through its equilibrium to no purpose; give an "
                                       "end time up to {:.3g}{}",
                                       terms.setting("end_time", fmt::format("{:g}", end_time)),
                                       limits.max_end_time_scales, std::pow(diagonal, 4), diagonal, latest,
                                       or_force(limits)));
  if (constant_tau > 0 && end_time / constant_tau > static_cast<double>(limits.max_steps))
    throw InvalidParameter(fmt::format("{} with {} takes {:.3g} steps, more than the limit of {} (it would run for "
                                       "a very long time); use a larger τ, adaptive time steps ({}), an earlier "
                                       "end{}",
                                       terms.setting("end_time", fmt::format("{:g}", end_time)),
                                       terms.setting("tau", fmt::format("{:g}", constant_tau)),
                                       end_time / constant_tau, limits.max_steps, terms.adaptive, or_force(limits)));
}

void check_count(long count, long limit, std::string_view what, const SizeLimits& limits)
{
  if (!limits.force && count > limit)
    throw InvalidParameter(fmt::format("{} {} is more than the limit of {} (it would run for a very long time to "
                                       "no purpose); use fewer{}", what, count, limit, or_force(limits)));
}

} // namespace sdflow
