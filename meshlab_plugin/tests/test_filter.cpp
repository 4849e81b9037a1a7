//! Tests of the filter plugin in process: its declarations, its parameters, and what applying it
//! does to a MeshLab document (failures leave the mesh alone and say why in the log).

#include "filter_sdflow.h"
#include "toolbox_bridge.h"

#include <vcg/complex/algorithms/clean.h>
#include <vcg/complex/algorithms/create/platonic.h>
#include <vcg/complex/append.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

namespace {

constexpr double curvature_tolerance = 0.02; // relative, on a subdivided icosahedron
constexpr double normal_tolerance = 1e-3;    // radial unit normals on the same sphere
// A coordinate difference far above float rounding (3.6e-7 at 3): each scheme option moves the
// ellipsoid's 3 steps by 5e-5 (volume-gradient areas) to 2e-3 (cotangent H).
constexpr double least_option_effect = 1e-5;

class FilterTest : public ::testing::Test {
protected:
  void SetUp() override { plugin.setLog(&log); }

  QAction* action() { return plugin.AC(FilterSdflowPlugin::FP_SURFACE_DIFFUSION); }
  QAction* retriangulate_action() { return plugin.AC(FilterSdflowPlugin::FP_RETRIANGULATE); }
  QAction* anisotropic_action() { return plugin.AC(FilterSdflowPlugin::FP_ANISOTROPIC_DIFFUSION); }
  QAction* substrate_action() { return plugin.AC(FilterSdflowPlugin::FP_SUBSTRATE_DIFFUSION); }

  //! The default parameters of `filter` (the flow's unless given) for the current mesh, with `steps` steps.
  RichParameterList parameters(int steps, QAction* filter = nullptr)
  {
    RichParameterList list;
    plugin.initParameterSet(filter ? filter : action(), *document.mm(), list);
    list.setValue("Steps", IntValue(steps));
    return list;
  }

  //! The re-triangulation filter's default parameters for the current mesh.
  RichParameterList retriangulation_parameters()
  {
    RichParameterList list;
    plugin.initParameterSet(retriangulate_action(), *document.mm(), list);
    return list;
  }

  QString log_text()
  {
    QStringList lines;
    log.print(lines);
    return lines.join('\n');
  }

  //! Three triangles on the edge (0, 1): not a manifold.
  MeshModel* add_fin_mesh()
  {
    MeshModel* model = document.addNewMesh("", "fins");
    auto v = vcg::tri::Allocator<CMeshO>::AddVertices(model->cm, 5);
    const Point3m points[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    for (const Point3m& p : points)
      (v++)->P() = p;
    vcg::tri::Allocator<CMeshO>::AddFace(model->cm, &model->cm.vert[0], &model->cm.vert[1], &model->cm.vert[2]);
    vcg::tri::Allocator<CMeshO>::AddFace(model->cm, &model->cm.vert[1], &model->cm.vert[0], &model->cm.vert[3]);
    vcg::tri::Allocator<CMeshO>::AddFace(model->cm, &model->cm.vert[0], &model->cm.vert[1], &model->cm.vert[4]);
    return model;
  }

  //! A sphere of radius 2 (a subdivided icosahedron, 642 vertices).
  MeshModel* add_sphere()
  {
    MeshModel* model = document.addNewMesh("", "sphere");
    vcg::tri::Sphere(model->cm, 3);
    for (auto& v : model->cm.vert)
      v.P() *= 2;
    return model;
  }

  //! An ellipsoid with semi-axes 3, 2, 2 (a stretched subdivided icosahedron, 642 vertices).
  MeshModel* add_ellipsoid()
  {
    MeshModel* model = add_sphere();
    for (auto& v : model->cm.vert)
      v.P()[0] *= 1.5f;
    return model;
  }

  //! The vertex positions after 3 steps of the flow on a new ellipsoid, with parameter `name` set to `value`.
  std::vector<Point3m> flowed_ellipsoid(const QString& name, const Value& value)
  {
    add_ellipsoid();
    RichParameterList list = parameters(3);
    list.setValue("Retriangulate", BoolValue(false)); // the same vertices whatever the option
    list.setValue(name, value);
    EXPECT_TRUE(plugin.applyFilter(action(), document, list, nullptr)) << log_text().toStdString();
    std::vector<Point3m> positions;
    for (const CVertexO& v : document.mm()->cm.vert)
      positions.push_back(v.cP());
    return positions;
  }

  //! A unit hemisphere standing on z = 0, open at the bottom, its rim the unit circle on the plane
  //! (exactly: z = 0): a pole and `rings` rings of 6k vertices at the polar angles (π/2) k / rings,
  //! each ring joined to the one above it by walking both in angle; normals out of the material.
  MeshModel* add_hemisphere(int rings = 8)
  {
    MeshModel* model = document.addNewMesh("", "hemisphere");
    CMeshO& m = model->cm;
    vcg::tri::Allocator<CMeshO>::AddVertices(m, 1 + 3 * rings * (rings + 1));
    std::vector<std::vector<int>> ring(rings + 1);
    int next = 0;
    for (int k = 0; k <= rings; ++k) {
      const double polar = M_PI / 2 * k / rings;
      const int count = k == 0 ? 1 : 6 * k;
      for (int j = 0; j < count; ++j) {
        const double azimuth = 2 * M_PI * j / count;
        const double z = k == rings ? 0.0 : std::cos(polar);
        m.vert[next].P() = Point3m(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), z);
        ring[k].push_back(next++);
      }
    }
    const auto face = [&m](int a, int b, int c) {
      vcg::tri::Allocator<CMeshO>::AddFace(m, &m.vert[a], &m.vert[b], &m.vert[c]);
    };
    for (int k = 1; k <= rings; ++k) {
      const std::vector<int>&inner = ring[k - 1], &outer = ring[k];
      const int n0 = static_cast<int>(inner.size()), n1 = static_cast<int>(outer.size());
      if (n0 == 1) { // the pole's fan
        for (int j = 0; j < n1; ++j)
          face(inner[0], outer[j], outer[(j + 1) % n1]);
        continue;
      }
      // Both rings start at azimuth 0; advance along the one whose next vertex comes first.
      for (int i = 0, j = 0; i < n0 || j < n1;) {
        if (j < n1 && (i == n0 || double(j + 1) / n1 <= double(i + 1) / n0)) {
          face(inner[i % n0], outer[j], outer[(j + 1) % n1]);
          ++j;
        } else {
          face(inner[i], outer[j % n1], inner[(i + 1) % n0]);
          ++i;
        }
      }
    }
    return model;
  }

  //! The volume the current mesh encloses with the plane z = 0 (∫ z n_z dA: the plane adds nothing).
  double volume_on_plane()
  {
    double volume = 0;
    for (const CFaceO& f : document.mm()->cm.face) {
      const vcg::Point3d a = vcg::Point3d::Construct(f.cP(0)), b = vcg::Point3d::Construct(f.cP(1)),
                         c = vcg::Point3d::Construct(f.cP(2));
      volume += (a[2] + b[2] + c[2]) / 3 * ((b - a) ^ (c - a))[2] / 2;
    }
    return volume;
  }

  //! Boundary vertices of the current mesh (on an edge of one triangle only), as positions.
  std::vector<Point3m> rim()
  {
    MeshModel* model = document.mm();
    model->updateDataMask(MeshModel::MM_FACEFACETOPO);
    vcg::tri::UpdateTopology<CMeshO>::FaceFace(model->cm);
    vcg::tri::UpdateFlags<CMeshO>::VertexBorderFromFaceAdj(model->cm);
    std::vector<Point3m> points;
    for (const CVertexO& v : model->cm.vert)
      if (v.IsB())
        points.push_back(v.cP());
    return points;
  }

  //! Two unit spheres centred at (±0.6, 0, 0): two components that intersect each other.
  MeshModel* add_overlapping_spheres()
  {
    MeshModel* model = document.addNewMesh("", "two spheres");
    vcg::tri::Sphere(model->cm, 3);
    CMeshO other;
    vcg::tri::Sphere(other, 3);
    for (auto& v : model->cm.vert)
      v.P()[0] -= 0.6f;
    for (auto& v : other.vert)
      v.P()[0] += 0.6f;
    vcg::tri::Append<CMeshO, CMeshO>::Mesh(model->cm, other);
    return model;
  }

  //! Connected components of the current mesh (through faces sharing an edge).
  int component_count()
  {
    MeshModel* model = document.mm();
    model->updateDataMask(MeshModel::MM_FACEFACETOPO);
    vcg::tri::UpdateTopology<CMeshO>::FaceFace(model->cm);
    return vcg::tri::Clean<CMeshO>::CountConnectedComponents(model->cm);
  }

  FilterSdflowPlugin plugin;
  GLLogStream log;
  MeshDocument document;
};

std::vector<int> progress_seen;

bool record_progress(const int percent, const char*)
{
  progress_seen.push_back(percent);
  return true;
}

//! The largest coordinate difference between two surfaces with the same vertices.
double largest_difference(const std::vector<Point3m>& a, const std::vector<Point3m>& b)
{
  EXPECT_EQ(a.size(), b.size());
  double largest = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    for (int c = 0; c < 3; ++c)
      largest = std::max(largest, std::abs(double(a[i][c]) - double(b[i][c])));
  return largest;
}

TEST_F(FilterTest, every_parameter_has_a_label_and_a_tooltip)
{
  add_sphere();
  for (QAction* a : plugin.actions()) {
    SCOPED_TRACE(plugin.filterName(a).toStdString());
    RichParameterList list;
    plugin.initParameterSet(a, *document.mm(), list);
    EXPECT_GT(list.size(), 0u);
    for (const RichParameter& p : list) {
      SCOPED_TRACE(p.name().toStdString());
      EXPECT_FALSE(p.fieldDescription().trimmed().isEmpty());
      EXPECT_GT(p.toolTip().trimmed().size(), 20);
    }
  }
}

TEST_F(FilterTest, is_a_smoothing_filter_on_one_mesh_with_faces)
{
  EXPECT_EQ(plugin.filterName(action()), QString("Surface diffusion N steps"));
  EXPECT_EQ(plugin.getClass(action()), MeshFilterInterface::Smoothing);
  EXPECT_EQ(plugin.filterArity(action()), MeshFilterInterface::SINGLE_MESH);
  EXPECT_TRUE(plugin.getPreConditions(action()) & MeshModel::MM_FACENUMBER);
  EXPECT_TRUE(plugin.postCondition(action()) & MeshModel::MM_VERTQUALITY);
}

TEST_F(FilterTest, retriangulation_sits_beside_the_flow_on_one_mesh_with_faces)
{
  EXPECT_EQ(plugin.filterName(retriangulate_action()), QString("Surface diffusion: re-triangulate"));
  EXPECT_EQ(plugin.getClass(retriangulate_action()), plugin.getClass(action()));
  EXPECT_EQ(plugin.filterArity(retriangulate_action()), MeshFilterInterface::SINGLE_MESH);
  EXPECT_TRUE(plugin.getPreConditions(retriangulate_action()) & MeshModel::MM_FACENUMBER);
  EXPECT_TRUE(plugin.postCondition(retriangulate_action()) & MeshModel::MM_VERTNORMAL);
}

TEST_F(FilterTest, default_edge_lengths_are_the_mean_edge_length)
{
  constexpr double relative_tolerance = 1e-5; // float parameters, float coordinates
  MeshModel* model = add_sphere();
  // On a closed surface every edge is a side of exactly two triangles.
  double sum = 0;
  for (const CFaceO& f : model->cm.face)
    for (int i = 0; i < 3; ++i)
      sum += vcg::Distance(f.cP(i), f.cP((i + 1) % 3));
  const double mean = sum / (3.0 * model->cm.fn);
  EXPECT_NEAR(parameters(1).getFloat("EdgeLength"), mean, relative_tolerance * mean);
  EXPECT_NEAR(retriangulation_parameters().getFloat("EdgeLength"), mean, relative_tolerance * mean);
  EXPECT_TRUE(parameters(1).getBool("Retriangulate")); // on by default, as in `sdflow run`
}

TEST_F(FilterTest, scheme_options_offer_the_command_line_names_and_default_to_the_command_lines)
{
  add_sphere();
  const RichParameterList list = parameters(1);
  EXPECT_EQ(dynamic_cast<const RichEnum&>(list.getParameterByName("Curvature")).enumvalues,
            QStringList({"cotangent", "normal_integral", "normal_integral_angle_sum"}));
  EXPECT_EQ(dynamic_cast<const RichEnum&>(list.getParameterByName("Mass")).enumvalues,
            QStringList({"voronoi", "volume_gradient"}));
  EXPECT_EQ(list.getEnum("Curvature"), 0);
  EXPECT_EQ(list.getEnum("Mass"), 0);
  EXPECT_FALSE(list.getBool("Extrapolate"));
}

TEST_F(FilterTest, diffusion_parameters_are_the_run_schemas_and_each_is_taken)
{
  using Kind = sdflow::meshlab::DialogParameter::Kind;
  add_sphere();
  const RichParameterList list = parameters(2);
  const std::vector<sdflow::meshlab::DialogParameter> expected = sdflow::meshlab::diffusion_parameters(1.0);
  ASSERT_EQ(list.size(), expected.size());
  // The .mlx names are an interface (users' filter scripts name every parameter).
  std::vector<std::string> names;
  for (const sdflow::meshlab::DialogParameter& d : expected)
    names.push_back(d.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"AutomaticTau", "Beta", "ConserveVolume", "Curvature", "EdgeLength",
                                             "Extrapolate", "FixedBoundary", "Mass", "Retriangulate", "Steps",
                                             "Tau"}));
  for (const sdflow::meshlab::DialogParameter& d : expected) {
    SCOPED_TRACE(d.name);
    const QString name = QString::fromStdString(d.name);
    ASSERT_TRUE(list.hasParameter(name));
    const RichParameter& p = list.getParameterByName(name);
    EXPECT_EQ(p.fieldDescription().toStdString(), d.label);
    EXPECT_FALSE(p.toolTip().isEmpty());
    // Another value than the default runs: the bridge maps every parameter onto the run.
    RichParameterList changed = parameters(2);
    switch (d.kind) {
    case Kind::integer: changed.setValue(name, IntValue(static_cast<int>(d.number) + 1)); break;
    case Kind::real: changed.setValue(name, FloatValue(changed.getFloat(name) * 0.5f)); break;
    case Kind::boolean: changed.setValue(name, BoolValue(!d.flag)); break;
    case Kind::choice: changed.setValue(name, EnumValue(static_cast<int>(d.choices.size()) - 1)); break;
    case Kind::text: ADD_FAILURE() << "the isotropic flow has no text parameter"; break;
    }
    if (d.name == "Tau") // used only with a constant τ
      changed.setValue("AutomaticTau", BoolValue(false));
    EXPECT_TRUE(plugin.applyFilter(action(), document, changed, nullptr)) << log_text().toStdString();
  }
}

TEST_F(FilterTest, the_anisotropic_flow_has_the_flows_parameters_and_the_surface_energys)
{
  using Kind = sdflow::meshlab::DialogParameter::Kind;
  add_sphere();
  EXPECT_EQ(plugin.filterName(anisotropic_action()), QString("Anisotropic surface diffusion N steps"));
  EXPECT_EQ(plugin.getClass(anisotropic_action()), plugin.getClass(action()));
  std::vector<std::string> isotropic, anisotropic;
  for (const sdflow::meshlab::DialogParameter& d : sdflow::meshlab::diffusion_parameters(1.0))
    isotropic.push_back(d.name);
  const std::vector<sdflow::meshlab::DialogParameter> expected =
      sdflow::meshlab::diffusion_parameters(1.0, sdflow::MeshlabFilter::anisotropic);
  for (const sdflow::meshlab::DialogParameter& d : expected)
    anisotropic.push_back(d.name);
  std::sort(isotropic.begin(), isotropic.end());
  std::sort(anisotropic.begin(), anisotropic.end());
  std::vector<std::string> added;
  std::set_difference(anisotropic.begin(), anisotropic.end(), isotropic.begin(), isotropic.end(),
                      std::back_inserter(added));
  EXPECT_EQ(added, (std::vector<std::string>{"Energy", "EnergyFormula", "EnergyG"}));
  EXPECT_EQ(anisotropic.size(), isotropic.size() + added.size()) << "every parameter of the flow, and these";
  const RichParameterList list = parameters(2, anisotropic_action());
  ASSERT_EQ(list.size(), expected.size());
  EXPECT_EQ(dynamic_cast<const RichEnum&>(list.getParameterByName("Energy")).enumvalues,
            QStringList({"isotropic", "ellipsoidal", "sum", "formula"}));
  EXPECT_EQ(list.getEnum("Energy"), 0); // the isotropic flow unless chosen
  for (const sdflow::meshlab::DialogParameter& d : expected) {
    if (d.kind != Kind::text)
      continue;
    SCOPED_TRACE(d.name);
    EXPECT_EQ(list.getString(QString::fromStdString(d.name)).toStdString(), d.text);
    EXPECT_FALSE(d.text.empty()) << "a default that runs when its energy is chosen";
  }
}

// The surface energy's parameters reach the flow: an ellipsoidal γ with g = (4, 1, 1), whose Wulff
// shape has semi-axes ∝ √g = (2, 1, 1), lengthens the sphere along x; the same γ written as a
// formula gives the same surface; text that is not numbers is refused, naming the parameter, with
// the mesh left as it was.
TEST_F(FilterTest, the_surface_energy_reaches_the_flow_from_the_dialog)
{
  const auto extent = [this](int axis) {
    float low = 1e9f, high = -1e9f;
    for (const CVertexO& v : document.mm()->cm.vert) {
      low = std::min(low, v.cP()[axis]);
      high = std::max(high, v.cP()[axis]);
    }
    return double(high - low);
  };
  const auto flowed = [this](const std::vector<std::pair<QString, Value*>>& settings) {
    add_sphere();
    RichParameterList list = parameters(10, anisotropic_action());
    list.setValue("Retriangulate", BoolValue(false));
    list.setValue("AutomaticTau", BoolValue(false));
    list.setValue("Tau", FloatValue(1e-2f));
    for (const auto& [name, value] : settings)
      list.setValue(name, *value);
    const bool applied = plugin.applyFilter(anisotropic_action(), document, list, nullptr);
    std::vector<Point3m> positions;
    for (const CVertexO& v : document.mm()->cm.vert)
      positions.push_back(v.cP());
    return std::make_pair(applied, positions);
  };
  EnumValue ellipsoidal(1), formula(3);
  StringValue g("4, 1, 1"), written_out("sqrt(4*nx^2 + ny^2 + nz^2)");
  const auto [ellipsoid_applied, ellipsoid] = flowed({{"Energy", &ellipsoidal}, {"EnergyG", &g}});
  ASSERT_TRUE(ellipsoid_applied) << log_text().toStdString();
  EXPECT_GT(extent(0), 1.002 * extent(1)) << "the Wulff shape is longer along x";
  const auto [formula_applied, by_formula] = flowed({{"Energy", &formula}, {"EnergyFormula", &written_out}});
  ASSERT_TRUE(formula_applied) << log_text().toStdString();
  EXPECT_LT(largest_difference(ellipsoid, by_formula), 1e-5) << "the same γ, written out";
  const auto [isotropic_applied, isotropic] = flowed({});
  ASSERT_TRUE(isotropic_applied) << log_text().toStdString();
  EXPECT_GT(largest_difference(ellipsoid, isotropic), 1e-3);

  MeshModel* model = add_sphere();
  const Point3m before = model->cm.vert[7].cP();
  RichParameterList list = parameters(3, anisotropic_action());
  list.setValue("Energy", EnumValue(1));
  list.setValue("EnergyG", StringValue("4, one, 1"));
  EXPECT_FALSE(plugin.applyFilter(anisotropic_action(), document, list, nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains("(EnergyG) must be numbers separated by commas, got \"one\""))
      << plugin.errorMsg().toStdString();
  EXPECT_EQ(model->cm.vert[7].cP(), before);
}

TEST_F(FilterTest, the_substrate_flow_has_the_flows_parameters_less_the_boundary_and_the_substrates)
{
  using Kind = sdflow::meshlab::DialogParameter::Kind;
  add_hemisphere();
  EXPECT_EQ(plugin.filterName(substrate_action()), QString("Surface diffusion on a substrate N steps"));
  EXPECT_EQ(plugin.getClass(substrate_action()), plugin.getClass(action()));
  std::vector<std::string> anisotropic, substrate;
  for (const sdflow::meshlab::DialogParameter& d :
       sdflow::meshlab::diffusion_parameters(1.0, sdflow::MeshlabFilter::anisotropic))
    anisotropic.push_back(d.name);
  const std::vector<sdflow::meshlab::DialogParameter> expected =
      sdflow::meshlab::diffusion_parameters(1.0, sdflow::MeshlabFilter::substrate);
  for (const sdflow::meshlab::DialogParameter& d : expected)
    substrate.push_back(d.name);
  std::sort(anisotropic.begin(), anisotropic.end());
  std::sort(substrate.begin(), substrate.end());
  std::vector<std::string> added, left_out;
  std::set_difference(substrate.begin(), substrate.end(), anisotropic.begin(), anisotropic.end(),
                      std::back_inserter(added));
  std::set_difference(anisotropic.begin(), anisotropic.end(), substrate.begin(), substrate.end(),
                      std::back_inserter(left_out));
  // The .mlx names are an interface: the flags in CamelCase.
  EXPECT_EQ(added, (std::vector<std::string>{"ContactAngle", "ContactLineMobility", "SubstrateZ"}));
  EXPECT_EQ(left_out, (std::vector<std::string>{"FixedBoundary"})) << "the boundary is the substrate";
  // Every default is the schema's (diffusion_parameters reads it), none typed in the plugin.
  const RichParameterList list = parameters(2, substrate_action());
  ASSERT_EQ(list.size(), expected.size());
  for (const sdflow::meshlab::DialogParameter& d : expected) {
    SCOPED_TRACE(d.name);
    const QString name = QString::fromStdString(d.name);
    ASSERT_TRUE(list.hasParameter(name));
    EXPECT_EQ(list.getParameterByName(name).fieldDescription().toStdString(), d.label);
    if (d.kind == Kind::real && name != "Tau" && name != "EdgeLength") { // those two: this mesh's
      EXPECT_EQ(list.getFloat(name), static_cast<float>(d.number));
    }
  }
  // The substrate filter's own parameters are not the other filters'.
  for (QAction* other : {action(), anisotropic_action()}) {
    RichParameterList others;
    plugin.initParameterSet(other, *document.mm(), others);
    EXPECT_FALSE(others.hasParameter("ContactAngle"));
  }
}

// A hemisphere (contact angle 90°) on z = 0 relaxes toward Young's angle: with θ_Y = 60° its
// contact line spreads, with θ_Y = 120° it retracts; either way every rim vertex stays exactly on
// the plane and the volume enclosed with the substrate is kept.
TEST_F(FilterTest, an_island_on_the_substrate_moves_its_contact_line_toward_youngs_angle)
{
  constexpr double volume_tolerance = 1e-4; // relative; ConserveVolume restores it each step
  constexpr double least_rim_motion = 0.03; // of the unit radius in 10 steps at η = 10 (0.07 measured)
  const auto mean_rim_radius = [this] {
    const std::vector<Point3m> points = rim();
    double sum = 0;
    for (const Point3m& p : points)
      sum += std::hypot(double(p[0]), double(p[1]));
    return points.empty() ? 0.0 : sum / static_cast<double>(points.size());
  };
  for (const float young : {60.0f, 120.0f}) {
    SCOPED_TRACE(young);
    add_hemisphere();
    const double volume = volume_on_plane();
    ASSERT_NEAR(mean_rim_radius(), 1.0, 1e-6);
    RichParameterList list = parameters(10, substrate_action());
    list.setValue("ContactAngle", FloatValue(young));
    list.setValue("ContactLineMobility", FloatValue(10));
    list.setValue("ConserveVolume", BoolValue(true));
    ASSERT_TRUE(plugin.applyFilter(substrate_action(), document, list, nullptr)) << log_text().toStdString();
    const std::vector<Point3m> points = rim();
    ASSERT_FALSE(points.empty());
    for (const Point3m& p : points)
      EXPECT_EQ(p[2], 0.0f);
    for (const CVertexO& v : document.mm()->cm.vert)
      EXPECT_GE(v.cP()[2], 0.0f);
    EXPECT_NEAR(volume_on_plane(), volume, volume_tolerance * volume);
    if (young < 90)
      EXPECT_GT(mean_rim_radius(), 1 + least_rim_motion);
    else
      EXPECT_LT(mean_rim_radius(), 1 - least_rim_motion);
  }
}

// The substrate's check of `sdflow run` (SubstrateBoundary::check_surface): a rim off the plane
// z₀, or a vertex below it, is refused before any step with the loop or vertex and the dialog's
// parameter named, the mesh left as it was.
TEST_F(FilterTest, a_surface_off_the_substrate_is_refused_naming_the_loop_and_left_unchanged)
{
  MeshModel* model = add_hemisphere();
  const Point3m before = model->cm.vert[7].cP();
  RichParameterList list = parameters(3, substrate_action());
  list.setValue("SubstrateZ", FloatValue(0.25f));
  EXPECT_FALSE(plugin.applyFilter(substrate_action(), document, list, nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains("boundary loop 0")) << plugin.errorMsg().toStdString();
  // In the dialog's words, not the scenario key's.
  EXPECT_TRUE(plugin.errorMsg().contains("is not on the plane (Substrate plane z₀ (SubstrateZ) = 0.25)"))
      << plugin.errorMsg().toStdString();
  EXPECT_FALSE(plugin.errorMsg().contains("substrate.z")) << plugin.errorMsg().toStdString();
  EXPECT_TRUE(log_text().contains("boundary loop 0")) << log_text().toStdString();
  EXPECT_EQ(model->cm.vert[7].cP(), before);

  model = add_sphere(); // radius 2 about the origin: no boundary, half of it below z = 0
  const Point3m sphere_before = model->cm.vert[7].cP();
  EXPECT_FALSE(plugin.applyFilter(substrate_action(), document, parameters(3, substrate_action()), nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains("below the substrate")) << plugin.errorMsg().toStdString();
  EXPECT_EQ(model->cm.vert[7].cP(), sphere_before);
}

TEST_F(FilterTest, each_scheme_option_changes_the_flow)
{
  const std::vector<Point3m> defaults = flowed_ellipsoid("Curvature", EnumValue(0));
  EXPECT_GT(largest_difference(defaults, flowed_ellipsoid("Curvature", EnumValue(1))), least_option_effect);
  EXPECT_GT(largest_difference(defaults, flowed_ellipsoid("Curvature", EnumValue(2))), least_option_effect);
  EXPECT_GT(largest_difference(defaults, flowed_ellipsoid("Mass", EnumValue(1))), least_option_effect);
  EXPECT_GT(largest_difference(defaults, flowed_ellipsoid("Extrapolate", BoolValue(true))), least_option_effect);
}

TEST_F(FilterTest, default_time_step_scales_like_the_fourth_power_of_edge_length)
{
  constexpr double scale = 3;
  constexpr double ratio_tolerance = 1e-4;
  add_sphere();
  const double tau = parameters(1).getFloat("Tau");
  for (auto& v : document.mm()->cm.vert)
    v.P() *= scale;
  const double scaled_tau = parameters(1).getFloat("Tau");
  EXPECT_GT(tau, 0);
  EXPECT_NEAR(scaled_tau / tau, std::pow(scale, 4), ratio_tolerance * std::pow(scale, 4));
}

TEST_F(FilterTest, non_manifold_mesh_fails_with_the_reason_and_stays_unchanged)
{
  MeshModel* model = add_fin_mesh();
  const Point3m before = model->cm.vert[4].cP();
  for (QAction* a : plugin.actions()) {
    SCOPED_TRACE(plugin.filterName(a).toStdString());
    log.Clear();
    RichParameterList list;
    plugin.initParameterSet(a, *model, list);
    EXPECT_FALSE(plugin.applyFilter(a, document, list, nullptr));
    EXPECT_TRUE(plugin.errorMsg().contains("fins")) << plugin.errorMsg().toStdString(); // names the mesh
    EXPECT_TRUE(log_text().contains("non-manifold-edge")) << log_text().toStdString(); // the finding's code
    EXPECT_EQ(model->cm.vn, 5);
    EXPECT_EQ(model->cm.fn, 3);
    EXPECT_EQ(model->cm.vert[4].cP(), before);
  }
}

TEST_F(FilterTest, bad_parameter_fails_and_leaves_the_mesh_unchanged)
{
  MeshModel* model = add_sphere();
  const Point3m before = model->cm.vert[7].cP();
  RichParameterList list = parameters(3);
  list.setValue("AutomaticTau", BoolValue(false));
  list.setValue("Tau", FloatValue(-1.0f));
  EXPECT_FALSE(plugin.applyFilter(action(), document, list, nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains("τ")) << plugin.errorMsg().toStdString();
  EXPECT_EQ(model->cm.vert[7].cP(), before);

  list = retriangulation_parameters();
  list.setValue("EdgeLength", FloatValue(-1.0f));
  EXPECT_FALSE(plugin.applyFilter(retriangulate_action(), document, list, nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains("edge length")) << plugin.errorMsg().toStdString();
  EXPECT_EQ(model->cm.vert[7].cP(), before);
}

TEST_F(FilterTest, choice_out_of_range_fails_naming_the_choices_and_leaves_the_mesh_unchanged)
{
  MeshModel* model = add_sphere();
  const Point3m before = model->cm.vert[7].cP();
  RichParameterList list = parameters(3);
  list.setValue("Curvature", EnumValue(3)); // meshlabserver takes any index from a script
  EXPECT_FALSE(plugin.applyFilter(action(), document, list, nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains(
      "Curvature must be 0 (cotangent), 1 (normal_integral) or 2 (normal_integral_angle_sum), got 3"))
      << plugin.errorMsg().toStdString();
  EXPECT_TRUE(log_text().contains("Curvature must be")) << log_text().toStdString();
  EXPECT_EQ(model->cm.vert[7].cP(), before);

  list = parameters(3);
  list.setValue("Mass", EnumValue(-1));
  EXPECT_FALSE(plugin.applyFilter(action(), document, list, nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains("Mass must be 0 (voronoi) or 1 (volume_gradient), got -1"))
      << plugin.errorMsg().toStdString();
  EXPECT_EQ(model->cm.vert[7].cP(), before);
}

TEST_F(FilterTest, retriangulation_leaving_nothing_fails_with_the_reason_and_leaves_the_mesh_unchanged)
{
  MeshModel* model = add_sphere();
  const int vertices = model->cm.vn;
  const Point3m before = model->cm.vert[7].cP();
  RichParameterList list = retriangulation_parameters();
  list.setValue("MinComponentFaces", IntValue(1000000));
  EXPECT_FALSE(plugin.applyFilter(retriangulate_action(), document, list, nullptr));
  EXPECT_TRUE(log_text().contains("nothing is left")) << log_text().toStdString();
  EXPECT_EQ(model->cm.vn, vertices);
  EXPECT_EQ(model->cm.vert[7].cP(), before);
}

// The filter makes the run's checks before step 1 (check_run_input, sdflow/run/run_input.h) and
// says what to do in the dialog's words: bodies that overlap are joined by the re-triangulate
// filter first; a part thinner than the re-triangulation resolves names the EdgeLength that does.
TEST_F(FilterTest, run_input_is_refused_before_step_1_in_the_dialogs_words)
{
  MeshModel* spheres = add_overlapping_spheres();
  const Point3m first = spheres->cm.vert[7].cP();
  EXPECT_FALSE(plugin.applyFilter(action(), document, parameters(3), nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains("overlap")) << plugin.errorMsg().toStdString();
  EXPECT_TRUE(plugin.errorMsg().contains("\"Surface diffusion: re-triangulate\"")) << plugin.errorMsg().toStdString();
  EXPECT_EQ(spheres->cm.vert[7].cP(), first);

  MeshModel* pancake = add_sphere(); // radius 2, flattened to 0.02 thick: edges about 0.3 long
  for (auto& v : pancake->cm.vert)
    v.P()[2] *= 0.005f;
  const Point3m second = pancake->cm.vert[7].cP();
  // EdgeLength 0 asks for the automatic ℓ, which the run refuses to collapse the pancake with.
  RichParameterList automatic = parameters(3);
  automatic.setValue("EdgeLength", FloatValue(0.0f));
  EXPECT_FALSE(plugin.applyFilter(action(), document, automatic, nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains(" thick at (")) << plugin.errorMsg().toStdString();
  EXPECT_TRUE(plugin.errorMsg().contains("(EdgeLength) = ")) << plugin.errorMsg().toStdString();
  EXPECT_EQ(pancake->cm.vert[7].cP(), second);
  // The dialog's default EdgeLength (the mean edge length) is one the user gave: a warning in the
  // log, in the dialog's words, and the run goes on.
  log.Clear();
  EXPECT_TRUE(plugin.applyFilter(action(), document, parameters(1), nullptr)) << plugin.errorMsg().toStdString();
  EXPECT_TRUE(log_text().contains("running with the Re-triangulation edge length ℓ (EdgeLength) given"))
      << log_text().toStdString();
}

TEST_F(FilterTest, retriangulation_joins_overlapping_spheres_into_one_outward_surface)
{
  add_overlapping_spheres();
  ASSERT_EQ(component_count(), 2);
  ASSERT_TRUE(plugin.applyFilter(retriangulate_action(), document, retriangulation_parameters(), nullptr))
      << log_text().toStdString();
  EXPECT_EQ(component_count(), 1);
  const MeshModel* model = document.mm();
  EXPECT_TRUE(model->hasDataMask(MeshModel::MM_VERTQUALITY));
  for (const CVertexO& v : model->cm.vert) {
    const Point3m centre(v.cP()[0] < 0 ? -0.6f : 0.6f, 0, 0);
    EXPECT_GT(v.cN() * (v.cP() - centre), 0); // away from the nearer centre
  }
  EXPECT_TRUE(log_text().contains("1 intersecting components joined")) << log_text().toStdString();
}

TEST_F(FilterTest, flow_with_retriangulation_remeshes_to_the_given_edge_length)
{
  MeshModel* model = add_sphere();
  const int vertices = model->cm.vn;
  RichParameterList list = parameters(1); // re-triangulation on by default
  list.setValue("EdgeLength", FloatValue(list.getFloat("EdgeLength") / 2));
  ASSERT_TRUE(plugin.applyFilter(action(), document, list, nullptr)) << log_text().toStdString();
  EXPECT_GT(model->cm.vn, 2 * vertices); // about four times: a quarter of the area per triangle
  EXPECT_TRUE(log_text().contains("re-triangulated")) << log_text().toStdString();
}

TEST_F(FilterTest, sphere_result_carries_curvature_as_quality_and_outward_normals)
{
  MeshModel* model = add_sphere();
  const int vertices = model->cm.vn;
  progress_seen.clear();
  ASSERT_TRUE(plugin.applyFilter(action(), document, parameters(3), record_progress)) << log_text().toStdString();
  EXPECT_EQ(model->cm.vn, vertices);
  EXPECT_TRUE(model->hasDataMask(MeshModel::MM_VERTQUALITY));
  for (const CVertexO& v : model->cm.vert) {
    const double radius = v.cP().Norm();
    SCOPED_TRACE(radius);
    EXPECT_NEAR(v.cQ(), -1 / radius, curvature_tolerance / radius); // H = -1/R with outward normals
    EXPECT_NEAR(v.cN() * (v.cP() / radius), 1.0, normal_tolerance);
  }
  ASSERT_FALSE(progress_seen.empty());
  EXPECT_EQ(progress_seen.back(), 100);
  EXPECT_TRUE(log_text().contains("Surface diffusion N steps")) << log_text().toStdString();
}

} // namespace
