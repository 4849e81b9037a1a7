//! `sdflow render MESH -o OUT.png [--view ROT_X,ROT_Z] [--size W,H] [--colour curvature|none]
//! [--title TEXT]`: a shaded picture of a triangulated surface drawn by gnuplot (pngcairo), each
//! triangle coloured by the mean of its vertices' mean curvature H (eq. 9 with the normals of eq. 8).

#include "common_options.h"
#include "gnuplot.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/io/io.h"
#include "sdflow/log.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

namespace sdflow::cli {
namespace {

namespace fs = std::filesystem;

struct RenderArguments {
  std::string input;
  std::string output;
  std::vector<double> view{60, 30};
  std::vector<int> size{800, 600};
  std::string colouring = "curvature"; //!< curvature | none
  std::string title;
  bool json = false;
};

//! The colour range covers the 1st to 99th percentile of the triangles' H, so that a few extreme
//! triangles (a pinching neck, a sealing hole) do not wash out the rest; beyond it the end colours.
constexpr double colour_range_percentile = 0.01;
constexpr const char* viridis = "(0 '#440154', 1 '#3b528b', 2 '#21908d', 3 '#5dc963', 4 '#fde725')";
constexpr const char* plain_colour = "'#9db9d8'";
//! gnuplot's view scale 1 leaves most of the picture empty; at 1.3 a cube-shaped surface still fits
//! a 4:3 picture with its long diagonal upright (view 54.7,45), the worst case.
constexpr double view_scale = 1.3;

//! A private directory under the system's temporary folder, removed with everything in it.
class TemporaryDirectory {
public:
  TemporaryDirectory()
  {
    std::string pattern = (fs::temp_directory_path() / "sdflow-render-XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw IoError(fmt::format("cannot create a temporary directory {} ({})", pattern, std::strerror(errno)));
    path_ = pattern;
  }
  ~TemporaryDirectory()
  {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

std::string read_whole_file(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

//! Check the options before reading the mesh, so a typo costs nothing.
void check_arguments(RenderArguments& a)
{
  const fs::path out = a.output;
  std::string extension = out.extension().string();
  for (char& c : extension)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".png")
    throw InvalidParameter(fmt::format("{}: the picture is a PNG; name it with the extension .png", a.output));
  const fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(folder))
    throw IoError(fmt::format("{}: the folder {} does not exist", a.output, folder.string()));
  for (double& angle : a.view) {
    if (!std::isfinite(angle))
      throw InvalidParameter(fmt::format("--view: the angles must be finite numbers of degrees, not {}", angle));
    // gnuplot takes both angles in [0, 360].
    angle = std::fmod(angle, 360.0);
    if (angle < 0)
      angle += 360.0;
  }
  for (int pixels : a.size)
    if (pixels < 16 || pixels > 8192)
      throw InvalidParameter(fmt::format("--size: {} pixels is outside [16, 8192]", pixels));
}

//! Colour value per triangle: the mean of its corners' H (eq. 9), or 0 for a single colour.
std::vector<double> triangle_colours(const Mesh& mesh, bool by_curvature)
{
  std::vector<double> value(mesh.n_faces(), 0.0);
  if (!by_curvature)
    return value;
  const Eigen::VectorXd H = mean_curvature(mesh, vertex_normals(mesh));
  for (auto f : mesh.faces()) {
    double sum = 0;
    for (auto v : mesh.fv_range(f))
      sum += H[v.idx()];
    value[f.idx()] = sum / 3.0;
  }
  return value;
}

//! [low, high] of the colour scale: the percentiles above, widened to at least 0.2% of the larger
//! of |H| and 1/(bounding box diagonal) when H is (nearly) constant (a sphere; a plane, where the
//! computed H is round-off that should not span the palette).
std::pair<double, double> colour_range(const Mesh& mesh, std::vector<double> values)
{
  if (values.empty())
    return {0.0, 1.0};
  const std::size_t last = values.size() - 1;
  const auto low_at = values.begin() + static_cast<long>(std::floor(colour_range_percentile * last));
  const auto high_at = values.begin() + static_cast<long>(std::ceil((1 - colour_range_percentile) * last));
  std::nth_element(values.begin(), low_at, values.end());
  const double low = *low_at;
  std::nth_element(values.begin(), high_at, values.end());
  const double high = *high_at;
  Eigen::AlignedBox3d box;
  for (auto v : mesh.vertices())
    box.extend(to_eigen(mesh.point(v)));
  const double half_width = 1e-3 * std::max({std::abs(low), std::abs(high), 1 / box.diagonal().norm()});
  if (high - low < 2 * half_width) {
    const double middle = 0.5 * (low + high);
    return {middle - half_width, middle + half_width};
  }
  return {low, high};
}

//! Each triangle (p0, p1, p2) as its own pm3d surface of two scans, p0 p1 / p2 p1, separated from
//! the next by two blank lines. gnuplot 5.4.4's (Debian 12) `with polygons` ignores per-polygon
//! colours (palette and rgb variable alike) and its lighting leaves dark, jagged patches on a
//! smooth torus, so the triangles go through `with pm3d`, whose palette and lighting work. The lighting normal comes from the first scan's two
//! points and the second scan's first, in whichever order gnuplot takes the scans: p0 p1 / p2 p1
//! gives three distinct points either way (p0 p1 / p2 p2 would not).
void write_triangles(const Mesh& mesh, const std::vector<double>& colour, const fs::path& file)
{
  std::ofstream out(file, std::ios::binary);
  fmt::memory_buffer buffer;
  auto flush = [&] {
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
  };
  for (auto f : mesh.faces()) {
    const TriangleCorners t = triangle_corners(mesh, f);
    const double c = colour[f.idx()];
    const auto& p = t.point;
    fmt::format_to(std::back_inserter(buffer),
                   "{:.9g} {:.9g} {:.9g} {:.9g}\n{:.9g} {:.9g} {:.9g} {:.9g}\n\n"
                   "{:.9g} {:.9g} {:.9g} {:.9g}\n{:.9g} {:.9g} {:.9g} {:.9g}\n\n\n",
                   p[0].x(), p[0].y(), p[0].z(), c, p[1].x(), p[1].y(), p[1].z(), c, p[2].x(), p[2].y(), p[2].z(), c,
                   p[1].x(), p[1].y(), p[1].z(), c);
    if (buffer.size() > (1u << 20))
      flush();
  }
  flush();
  out.close();
  if (!out)
    throw IoError(fmt::format("{}: cannot write the temporary data file ({})", file.string(), std::strerror(errno)));
}

//! Five labelled tics from `low` to `high`, with just enough digits to tell them apart.
std::string colour_tics(double low, double high)
{
  const double step = (high - low) / 4;
  const double largest = std::max(std::abs(low), std::abs(high));
  const int digits = std::max(2, static_cast<int>(std::ceil(std::log10(largest / step))) + 1);
  std::string tics;
  for (int i = 0; i <= 4; ++i) {
    double value = i == 4 ? high : low + i * step;
    if (std::abs(value) < 1e-9 * step) // round-off beside a zero crossing
      value = 0;
    tics += fmt::format("{}'{:.{}g}' {:.17g}", i == 0 ? "" : ", ", value, digits, value);
  }
  return "(" + tics + ")";
}

std::string gnuplot_script(const RenderArguments& a, const fs::path& data, const fs::path& picture,
                           std::pair<double, double> range)
{
  // `set samples 2,2`: gnuplot allocates that many points for every scan it reads, and every
  // triangle is two scans of two points (the default of 100 costs 5x the memory and time).
  std::string s = fmt::format("set terminal pngcairo size {},{} font ',11'\nset output {}\nset encoding utf8\n"
                              "set samples 2,2\n",
                              a.size[0], a.size[1], gnuplot_quoted(picture.string()));
  s += fmt::format("unset key\nunset border\nunset tics\nset view {},{},{}\nset view equal xyz\n"
                   "set xyplane relative 0\nset pm3d depthorder\nset pm3d lighting primary 0.5 specular 0.2\n",
                   a.view[0], a.view[1], view_scale);
  if (!a.title.empty())
    s += fmt::format("set title {} noenhanced\n", gnuplot_quoted(a.title));
  if (a.colouring == "curvature") {
    // A strip on the right holds the colour box, its tic labels (up to 8 characters of an 11 pt
    // font, about 70 pixels) and 'H' above it; the surface keeps the rest of the picture.
    const double width = a.size[0], box_width = std::max(10.0, 0.025 * width);
    const double box_left = 1 - (70 + box_width + 6) / width;
    s += fmt::format("set palette defined {}\nset cbrange [{:.17g}:{:.17g}]\n", viridis, range.first, range.second);
    // A picture too narrow for the strip (under about 180 pixels) keeps the colours without the scale.
    if (box_left < 0.5)
      s += "unset colorbox\n";
    else
      s += fmt::format("set cbtics {}\nset size {:.4f},1\n"
                       "set colorbox vertical user origin screen {:.4f},0.2 size screen {:.4f},0.6\n"
                       "set label 'H' at screen {:.4f},0.84 center\n",
                       colour_tics(range.first, range.second), box_left - 0.02, box_left, box_width / width,
                       box_left + 0.5 * box_width / width);
  } else {
    s += fmt::format("set palette defined (0 {0}, 1 {0})\nset cbrange [0:1]\nunset colorbox\n", plain_colour);
  }
  s += fmt::format("splot {} using 1:2:3:4 with pm3d\n", gnuplot_quoted(data.string()));
  return s;
}

void render(RenderArguments a)
{
  check_arguments(a);
  WorkProgress progress("render");
  progress.stage("reading " + a.input);
  const BuiltMesh input = read_mesh(a.input);
  const Mesh& mesh = input.mesh;
  const bool by_curvature = a.colouring == "curvature";
  if (by_curvature)
    progress.stage("mean curvature");
  const std::vector<double> colour = triangle_colours(mesh, by_curvature);
  const auto range = by_curvature ? colour_range(mesh, colour) : std::pair{0.0, 1.0};

  const TemporaryDirectory work;
  const fs::path data = work.path() / "triangles.dat", picture = work.path() / "picture.png";
  const fs::path script = work.path() / "render.gnuplot", log = work.path() / "gnuplot.log";
  progress.stage(fmt::format("writing {} triangles for gnuplot", mesh.n_faces()));
  write_triangles(mesh, colour, data);
  {
    std::ofstream out(script, std::ios::binary);
    out << gnuplot_script(a, data, picture, range);
    if (!out)
      throw IoError(fmt::format("{}: cannot write the gnuplot script", script.string()));
  }
  progress.stage(fmt::format("gnuplot drawing {} triangles", mesh.n_faces()));
  run_gnuplot(script, log);
  progress.finish();
  const std::string png = read_whole_file(picture);
  if (png.empty())
    throw std::runtime_error(fmt::format("gnuplot wrote no picture: {}", read_whole_file(log)));
  if (const std::string warnings = read_whole_file(log); !warnings.empty())
    logger().debug("gnuplot: {}", warnings);
  write_atomically(a.output, [&](std::ostream& s) { s.write(png.data(), static_cast<std::streamsize>(png.size())); });

  if (a.json) {
    toml::table root{{"input", a.input},
                     {"output", a.output},
                     {"vertices", static_cast<int64_t>(mesh.n_vertices())},
                     {"faces", static_cast<int64_t>(mesh.n_faces())},
                     {"width", a.size[0]},
                     {"height", a.size[1]},
                     {"view", toml::array{a.view[0], a.view[1]}},
                     {"colour", a.colouring}};
    if (by_curvature)
      root.insert("curvature_range", toml::array{range.first, range.second});
    print_json(std::move(root));
    return;
  }
  std::cout << fmt::format("{}: {} vertices, {} triangles -> {} ({}x{} pixels, view {},{}", a.input, mesh.n_vertices(),
                           mesh.n_faces(), a.output, a.size[0], a.size[1], a.view[0], a.view[1]);
  if (by_curvature)
    std::cout << fmt::format(", H from {:.4g} to {:.4g}", range.first, range.second);
  std::cout << ")\n";
}

} // namespace

void add_render_verb(CLI::App& app)
{
  auto args = std::make_shared<RenderArguments>();
  CLI::App* verb =
      app.add_subcommand("render", "A shaded PNG picture of a surface (gnuplot), coloured by mean curvature");
  verb->add_option("input", args->input, fmt::format("Mesh ({})", mesh_formats))->required();
  add_output_option(*verb, args->output, "Picture to write (.png)")->required();
  verb->add_option("--view", args->view, "View angles in degrees, rotation about x then z (gnuplot's set view)")
      ->delimiter(',')
      ->expected(2)
      ->option_text("ROT_X,ROT_Z (default: 60,30)");
  verb->add_option("--size", args->size, "Picture width and height in pixels")
      ->delimiter(',')
      ->expected(2)
      ->option_text("W,H (default: 800,600)");
  verb->add_option("--colour", args->colouring,
                   "curvature: each triangle by the mean of its vertices' H (eq. 9; the scale spans H's 1st to "
                   "99th percentile); none: one colour")
      ->check(CLI::IsMember({"curvature", "none"}))
      ->capture_default_str();
  verb->add_option("--title", args->title, "Title above the picture");
  add_json_flag(*verb, args->json);
  verb->callback([args] { render(*args); });
}

} // namespace sdflow::cli
