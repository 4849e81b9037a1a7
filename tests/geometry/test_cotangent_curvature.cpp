//! Mean curvature from the cotangent mean-curvature normal (cotangent_curvature.h) against analytic
//! surfaces, under refinement.
#include "sdflow/errors.h"
#include "sdflow/geometry/cotangent_curvature.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/mesher.h"
#include "support/analytic_meshes.h"
#include "support/convergence.h"
#include "support/curvature_errors.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace sdflow {
namespace {

constexpr CurvatureOptions kCotangent{.method = CurvatureMethod::cotangent};
using analytic::kSecondOrder;

using Errors = analytic::CurvatureErrors;

Errors cotangent_errors(const Mesh& mesh, const std::function<double(const Eigen::Vector3d&)>& exact)
{
  return analytic::curvature_errors(mesh, exact, kCotangent);
}

double torus_curvature(const Eigen::Vector3d& p, double major, double minor)
{
  return analytic::torus_mean_curvature(major, minor, std::atan2(p.z(), std::hypot(p.x(), p.y()) - major));
}

// On a mesh inscribed in a sphere, (x_j - x_i)·x_i = -|e_ij|²/2, so N·(LX)_i = -2 A_i/R exactly when
// the triangles are non-obtuse (mixed area = Voronoi area) and N is radial (eq. 8 is, by symmetry, on
// icospheres): H = -1/R at every level, not just in the limit.
TEST(CotangentCurvature, icosphere_is_minus_inverse_radius_at_every_level)
{
  constexpr double exact = 1e-12; // relative to 1/R
  for (double radius : {1.0, 3.0}) {
    for (int level = 1; level <= 5; ++level) {
      SCOPED_TRACE(::testing::Message() << "R = " << radius << ", level " << level);
      const Errors e = cotangent_errors(analytic::icosphere(level, radius), [&](const Eigen::Vector3d&) { return -1.0 / radius; });
      EXPECT_LT(e.max * radius, exact);
    }
  }
}

TEST(CotangentCurvature, tori_converge_to_second_order)
{
  constexpr double major = 6, minor = 3;
  struct Case {
    const char* name;
    std::function<Mesh(int)> mesh;
    double finest_max; // max |H - H_exact| at n = 128 (measured 3.3e-5 and 7.5e-5)
  };
  const Case cases[] = {{"conformal", [&](int n) { return analytic::conformal_torus(n, major, minor); }, 5e-5},
                        {"angle grid", [&](int n) { return analytic::torus(2 * n, n, major, minor); }, 1e-4}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::vector<double> h, max_err, rms_err;
    for (int n : {16, 32, 64, 128}) {
      const Errors e = cotangent_errors(c.mesh(n), [&](const Eigen::Vector3d& p) { return torus_curvature(p, major, minor); });
      h.push_back(1.0 / n);
      max_err.push_back(e.max);
      rms_err.push_back(e.rms);
    }
    EXPECT_GT(analytic::observed_order(h, max_err), kSecondOrder);
    EXPECT_GT(analytic::observed_order(h, rms_err), kSecondOrder);
    EXPECT_LT(max_err.back(), c.finest_max);
  }
}

// The stretched icosphere's stars stay affinely distorted at every level, so the pointwise error
// settles to a plateau (as for eq. 9, test_curvature.cpp; lower here: 0.0165 against 0.045), while
// the mean-square error still converges, about first order (4.4e-3 → 3.9e-4 over levels 2..5).
TEST(CotangentCurvature, ellipsoid_converges_in_mean_square_with_a_bounded_plateau)
{
  constexpr double a = 5, b = 4, c = 3;
  constexpr double plateau = 0.02; // |H| ranges over [0.10, 0.30] on this ellipsoid
  std::vector<double> h, max_err, rms_err;
  for (int level = 2; level <= 5; ++level) {
    const Errors e = cotangent_errors(analytic::ellipsoid(level, a, b, c), [&](const Eigen::Vector3d& p) {
      return analytic::ellipsoid_mean_curvature(a, b, c, p);
    });
    h.push_back(std::pow(0.5, level));
    max_err.push_back(e.max);
    rms_err.push_back(e.rms);
  }
  EXPECT_GT(analytic::observed_order(h, rms_err), 1.0);
  for (std::size_t i = 1; i < max_err.size(); ++i)
    EXPECT_LE(max_err[i], max_err[i - 1] * 1.001);
  EXPECT_LT(max_err.back(), plateau);
}

TEST(CotangentCurvature, sign_follows_orientation_and_boundary_and_plane_give_zero)
{
  const Mesh sphere = analytic::icosphere(3, 2.0);
  const Eigen::VectorXd outward = mean_curvature(sphere, vertex_normals(sphere), kCotangent);
  EXPECT_LT(outward.maxCoeff(), 0.0);
  const Eigen::VectorXd inward = mean_curvature(sphere, -vertex_normals(sphere), kCotangent);
  EXPECT_LT((outward + inward).cwiseAbs().maxCoeff(), 1e-14);
  const Mesh flat = analytic::disk(6, 2.0);
  EXPECT_LT(mean_curvature(flat, vertex_normals(flat), kCotangent).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(CotangentCurvature, refuses_operators_of_another_size)
{
  const Mesh mesh = analytic::icosphere(1);
  const Mesh other = analytic::icosphere(2);
  EXPECT_THROW(cotangent_mean_curvature(mesh, vertex_normals(mesh), cotangent_laplacian(other), mixed_voronoi_areas(mesh)),
               InvalidParameter);
}

//! The largest area-weighted mean of H − H_exact over bands of the tube angle v (12 bands): the part
//! of the error that survives local averaging, which is what the flow, through ΔH, responds to.
double band_bias(const Mesh& torus, const Eigen::VectorXd& h, double major, double minor)
{
  constexpr int bands = 12;
  std::vector<double> sum(bands, 0.0), area(bands, 0.0);
  const Eigen::VectorXd a = mixed_voronoi_areas(torus);
  for (auto v : torus.vertices()) {
    const Eigen::Vector3d p = to_eigen(torus.point(v));
    const double angle = std::atan2(p.z(), std::hypot(p.x(), p.y()) - major);
    const int band = std::min(bands - 1, static_cast<int>((angle + std::numbers::pi) / (2 * std::numbers::pi) * bands));
    sum[band] += a[v.idx()] * (h[v.idx()] - torus_curvature(p, major, minor));
    area[band] += a[v.idx()];
  }
  double worst = 0;
  for (int b = 0; b < bands; ++b)
    worst = std::max(worst, std::abs(sum[b] / area[b]));
  return worst;
}

TEST(CotangentCurvature, its_error_averages_out_on_remeshed_tori_where_eq9_is_biased)
{
  // Why the flow's default H is the cotangent one. On the isotropically remeshed surfaces runs use
  // (R = 3, r = 1.5, edge lengths 0.2, 0.1, 0.05) neither H converges pointwise: the RMS errors stay
  // near 0.0045 (eq. 9) and 0.0087 (cotangent). But the cotangent error is noise that averages
  // out over a band of the tube, and that part falls at second order (measured 1.7e-3, 4.2e-4,
  // 9.4e-5); eq. (9)'s error carries a bias that depends on where on the tube a star sits, and it
  // barely falls (1.9e-3, 1.7e-3, 1.2e-3), so the flow's ΔH inherits it. The errors are
  // recorded as test properties (scripts/validation.sh puts them in docs/validation.md).
  constexpr double major = 3, minor = 1.5;
  std::vector<double> paper, cotangent;
  for (const double edge : {0.2, 0.1, 0.05}) {
    const Mesh torus =
        mesh_implicit_surface(torus_shape({.major = major, .minor = minor}), {.edge_length = edge}).mesh;
    const VertexVectors normals = vertex_normals(torus);
    paper.push_back(band_bias(torus, mean_curvature(torus, normals), major, minor));
    cotangent.push_back(band_bias(torus, mean_curvature(torus, normals, kCotangent), major, minor));
    const std::string key = fmt::format("edge_{}_vertices_{}", edge, torus.n_vertices());
    RecordProperty(key + "_eq9_band_bias", fmt::format("{:.3g}", paper.back()));
    RecordProperty(key + "_cotangent_band_bias", fmt::format("{:.3g}", cotangent.back()));
  }
  EXPECT_LT(cotangent[2], 0.35 * cotangent[0]) << "the cotangent H's local average must converge";
  EXPECT_GT(paper[2], 0.5 * paper[0]) << "eq. (9)'s bias was expected to stay, roughly";
  EXPECT_LT(cotangent[2], 0.5 * paper[2]);
}

} // namespace
} // namespace sdflow
