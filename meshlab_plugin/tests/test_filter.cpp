//! Tests of the filter plugin in process: its declarations, its parameters, and what applying it
//! does to a MeshLab document (failures leave the mesh alone and say why in the log).

#include "filter_sdflow.h"

#include <vcg/complex/algorithms/create/platonic.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

constexpr double curvature_tolerance = 0.02; // relative, eq. (9) on a subdivided icosahedron
constexpr double normal_tolerance = 1e-3;    // radial unit normals on the same sphere

class FilterTest : public ::testing::Test {
protected:
  void SetUp() override { plugin.setLog(&log); }

  QAction* action() { return plugin.AC(FilterSdflowPlugin::FP_SURFACE_DIFFUSION); }

  //! The filter's default parameters for the current mesh, with `steps` steps.
  RichParameterList parameters(int steps)
  {
    RichParameterList list;
    plugin.initParameterSet(action(), *document.mm(), list);
    list.setValue("Steps", IntValue(steps));
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
  const RichParameterList list = parameters(2);
  EXPECT_FALSE(plugin.applyFilter(action(), document, list, nullptr));
  EXPECT_TRUE(plugin.errorMsg().contains("fins")) << plugin.errorMsg().toStdString(); // names the mesh
  EXPECT_TRUE(log_text().contains("non-manifold-edge")) << log_text().toStdString(); // the finding's code
  EXPECT_EQ(model->cm.vn, 5);
  EXPECT_EQ(model->cm.fn, 3);
  EXPECT_EQ(model->cm.vert[4].cP(), before);
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
