#include "filter_sdflow.h"

#include "convert.h"
#include "toolbox_bridge.h"

#include "sdflow/errors.h"

#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using sdflow::meshlab::LogLevel;

//! The toolbox's log lines and progress, routed to MeshLab's log and progress bar.
sdflow::meshlab::Reporter reporter_for(MeshLabInterface& plugin, vcg::CallBackPos* progress)
{
  sdflow::meshlab::Reporter reporter;
  reporter.log = [&plugin](LogLevel level, const std::string& line) {
    plugin.Log(level == LogLevel::warning || level == LogLevel::error ? GLLogStream::WARNING : GLLogStream::FILTER,
               line);
  };
  if (progress)
    reporter.progress = [progress](int percent, const std::string& message) { progress(percent, message.c_str()); };
  return reporter;
}

//! The choices of an enum parameter.
QStringList choices(const std::vector<std::string>& names)
{
  QStringList list;
  for (const std::string& name : names)
    list << QString::fromStdString(name);
  return list;
}

//! The flow's filter of a plugin filter id, if it is one.
std::optional<sdflow::MeshlabFilter> flow_filter(const int id)
{
  switch (id) {
  case FilterSdflowPlugin::FP_SURFACE_DIFFUSION: return sdflow::MeshlabFilter::surface_diffusion;
  case FilterSdflowPlugin::FP_ANISOTROPIC_DIFFUSION: return sdflow::MeshlabFilter::anisotropic;
  case FilterSdflowPlugin::FP_SUBSTRATE_DIFFUSION: return sdflow::MeshlabFilter::substrate;
  }
  return std::nullopt;
}

//! Adds to `parameters`, as MeshLab's, the dialog of a filter that runs the flow, with defaults for
//! a mesh of `mean_edge_length`: diffusion_parameters (toolbox_bridge.h) derives them from sdflow's
//! schema of run parameters (the isotropic filter's; the anisotropic one's adds the surface
//! energy's; the substrate one's adds the substrate's and the energy's, and has no FixedBoundary).
void add_diffusion_parameters(RichParameterList& parameters, double mean_edge_length, sdflow::MeshlabFilter filter)
{
  using Kind = sdflow::meshlab::DialogParameter::Kind;
  for (const sdflow::meshlab::DialogParameter& d : sdflow::meshlab::diffusion_parameters(mean_edge_length, filter)) {
    const QString name = QString::fromStdString(d.name), label = QString::fromStdString(d.label),
                  help = QString::fromStdString(d.help);
    switch (d.kind) {
    case Kind::integer:
      parameters.addParam(RichInt(name, static_cast<int>(d.number), label, help));
      break;
    case Kind::real:
      parameters.addParam(RichFloat(name, static_cast<float>(d.number), label, help));
      break;
    case Kind::boolean:
      parameters.addParam(RichBool(name, d.flag, label, help));
      break;
    case Kind::choice:
      parameters.addParam(RichEnum(name, d.choice, choices(d.choices), label, help));
      break;
    case Kind::text:
      parameters.addParam(RichString(name, QString::fromStdString(d.text), label, help));
      break;
    }
  }
}

sdflow::meshlab::DiffusionSettings diffusion_settings(const RichParameterList& parameters, sdflow::MeshlabFilter filter)
{
  using Kind = sdflow::meshlab::DialogParameter::Kind;
  sdflow::meshlab::DiffusionSettings settings;
  for (const sdflow::meshlab::DialogParameter& d : sdflow::meshlab::diffusion_parameters(0, filter)) {
    const QString name = QString::fromStdString(d.name);
    sdflow::meshlab::DialogValue& value = settings[d.name];
    switch (d.kind) {
    case Kind::integer: value.number = parameters.getInt(name); break;
    case Kind::real: value.number = sdflow::meshlab::intended_double(parameters.getFloat(name)); break;
    case Kind::boolean: value.flag = parameters.getBool(name); break;
    case Kind::choice: value.choice = parameters.getEnum(name); break;
    case Kind::text: value.text = parameters.getString(name).toStdString(); break;
    }
  }
  return settings;
}

sdflow::meshlab::RetriangulationSettings retriangulation_settings(const RichParameterList& parameters)
{
  sdflow::meshlab::RetriangulationSettings s;
  s.edge_length = sdflow::meshlab::intended_double(parameters.getFloat("EdgeLength"));
  s.remesh_iterations = parameters.getInt("RemeshIterations");
  s.always_rebuild = parameters.getBool("AlwaysRebuild");
  s.fill_holes = parameters.getBool("FillHoles");
  s.min_component_faces = parameters.getInt("MinComponentFaces");
  return s;
}

} // namespace

FilterSdflowPlugin::FilterSdflowPlugin()
{
  // In the enum's order: meshlabserver 2020.09 crashed running a script's filter when they differed.
  typeList << FP_SURFACE_DIFFUSION << FP_RETRIANGULATE << FP_ANISOTROPIC_DIFFUSION << FP_SUBSTRATE_DIFFUSION;
  for (FilterIDType type : types())
    actionList << new QAction(filterName(type), this);
}

QString FilterSdflowPlugin::pluginName() const { return "FilterSdflow"; }

QString FilterSdflowPlugin::filterName(FilterIDType filter) const
{
  if (const auto flow = flow_filter(filter))
    return sdflow::meshlab_filter_name(*flow);
  if (filter == FP_RETRIANGULATE)
    return "Surface diffusion: re-triangulate";
  return {};
}

QString FilterSdflowPlugin::filterInfo(FilterIDType filter) const
{
  switch (filter) {
  case FP_SURFACE_DIFFUSION:
    return "Evolves the surface by <b>surface diffusion flow</b>: every point moves along the normal with "
           "speed V<sub>N</sub> = -&Delta;H, the negative surface Laplacian of the mean curvature. The flow "
           "keeps the enclosed volume and lowers the area, rounding a closed surface of genus 0 into a "
           "sphere; it is the motion of a solid surface by atom migration (sintering, void and pore "
           "evolution).<br>"
           "Each step solves the semi-implicit scheme (I + &tau;&beta;&Delta;&sup2;) w = &Delta;H, "
           "X &larr; X - &tau; w N, with the cotangent/Voronoi Laplace-Beltrami operator, normals by Max's "
           "weights and by default the cotangent mean curvature H = &frac12; N&middot;&Delta;X, which converges "
           "to the exact flow (the paper's integral of normal curvatures is an option, as are the vertex areas "
           "and a second-order extrapolated step), exactly as the "
           "<i>sdflow</i> command line does (<tt>sdflow run</tt> gives the same surface for the same "
           "parameters).<br>"
           "With <i>re-triangulate</i> on, the surface is re-triangulated between steps whenever it intersects "
           "itself (a pinch-off, a hole closing, bodies touching) or its triangles degrade, by the pipeline of "
           "<i>Surface diffusion: re-triangulate</i> (<tt>sdflow run --retriangulate</tt>).<br>"
           "The result replaces the current mesh, all connected components together in this layer. "
           "Per-vertex <b>quality holds the mean curvature H</b> (a sphere of radius R has H = -1/R) and "
           "per-vertex normals hold N, so <i>Colorize by vertex quality</i> shows the curvature.<br>"
           "The mesh must be a manifold, consistently oriented triangle mesh; otherwise the filter stops and "
           "the log lists every problem found. It refuses, before any step, what <tt>sdflow run</tt> refuses: "
           "bodies that overlap (join them first with <i>Surface diffusion: re-triangulate</i>), a vertex far "
           "from the others, a surface too coarse to re-triangulate at the edge length given (with the edge "
           "length 0 a surface too coarse at its mean edge length is refined first, exactly, as "
           "<tt>sdflow run</tt> does).<br><br>"
           "See: <i>Efremenko</i>, <b>\"On semi-implicit numerical method for surface diffusion equation "
           "for triangulated surfaces\"</b>; <i>M. Meyer, M. Desbrun, P. Schr&ouml;der, A. H. Barr</i>, "
           "<b>\"Discrete differential-geometry operators for triangulated 2-manifolds\"</b>, "
           "Visualization and Mathematics III, 2003.";
  case FP_ANISOTROPIC_DIFFUSION:
    return "<i>Surface diffusion N steps</i> with a surface energy &int; &gamma;(n) dA that depends on the "
           "direction of the normal (a crystal's): the flow lowers it toward the <b>Wulff shape</b> of "
           "&gamma; instead of the sphere. <i>Surface energy</i> chooses &gamma;: isotropic (&gamma; = 1, the "
           "other filter's flow), ellipsoidal (&gamma; = &radic;(g1 nx&sup2; + g2 ny&sup2; + g3 nz&sup2;), whose "
           "Wulff shape is the ellipsoid of semi-axes &prop; &radic;g), a sum of rotated ellipsoidal terms "
           "(cubic-like anisotropies) or a formula in nx, ny, nz, exactly as <tt>sdflow run --energy</tt> "
           "does. The other parameters, the result and the checks are those of <i>Surface diffusion N "
           "steps</i>.<br><br>"
           "See: <i>J. W. Barrett, H. Garcke, R. N&uuml;rnberg</i>, J. Comput. Phys. 227, 2008 (the "
           "ellipsoidal forms of &gamma;).";
  case FP_SUBSTRATE_DIFFUSION:
    return "<i>Surface diffusion N steps</i> for a film or an island on a flat rigid <b>substrate</b>, the plane "
           "z = z<sub>0</sub> (solid-state dewetting): the mesh is open, and each of its boundary loops is a "
           "<b>contact line</b> on the plane. No material crosses a contact line; it moves in the plane toward "
           "Young's angle &theta;<sub>Y</sub>, at the speed &eta; (cos &theta;<sub>Y</sub> - cos &theta;) along its "
           "outward normal for the current angle &theta;. The volume enclosed with the substrate is kept (to first "
           "order in &tau;, exactly with <i>Conserve volume</i>), and an island relaxes to the spherical cap of "
           "angle &theta;<sub>Y</sub> (with an anisotropic <i>surface energy</i>, cos &theta;<sub>Y</sub> is "
           "&sigma; = &gamma;<sub>VS</sub> - &gamma;<sub>FS</sub> in &gamma;'s units, and the equilibrium is the Winterbottom shape). With <i>re-triangulate</i> on, the "
           "substrate's topology changes happen too: a film touching down opens a hole, contact lines that meet "
           "join, as <tt>sdflow run --boundary substrate</tt> does (the same surface for the same parameters). "
           "The other parameters, the result and the checks are those of <i>Anisotropic surface diffusion N "
           "steps</i>; besides, a mesh with a boundary loop off the plane, or a vertex below it, is refused before "
           "any step, and the log names the loop or the vertex.<br><br>"
           "See: <i>Y. Wang, W. Jiang, W. Bao</i>, 2015, and in three dimensions <i>Q. Zhao, W. Jiang, W. Bao</i>, "
           "SIAM J. Sci. Comput., 2020 (the relaxed contact-line law); sdflow's docs/method.md, \"Substrate\".";
  case FP_RETRIANGULATE:
    return "Re-triangulates the surface by the pipeline of section 3.2.1 of the paper, the one <i>Surface "
           "diffusion N steps</i> applies between steps: components that intersect each other are joined into the "
           "boundary of their union; the surface is remeshed isotropically to the target edge length; "
           "self-intersecting faces are removed and, if there were any, the surface is rebuilt from its points "
           "(jet normals oriented along a minimum spanning tree, advancing-front reconstruction) and its holes "
           "are filled; small or flat debris components are dropped. <tt>sdflow retriangulate</tt> gives the same "
           "surface for the same parameters.<br>"
           "The result replaces the current mesh, all connected components together in this layer, with "
           "per-vertex normals N and <b>quality = mean curvature H</b>.<br>"
           "The mesh must be a manifold, consistently oriented triangle mesh; otherwise, or when nothing would be "
           "left, the filter stops, the mesh stays unchanged and the log gives the reason.<br><br>"
           "See: <i>Efremenko</i>, <b>\"On semi-implicit numerical method for surface diffusion equation for "
           "triangulated surfaces\"</b>, section 3.2.1 and Appendix B.";
  }
  return {};
}

MeshFilterInterface::FilterClass FilterSdflowPlugin::getClass(QAction* action)
{
  switch (ID(action)) {
  case FP_SURFACE_DIFFUSION:
  case FP_ANISOTROPIC_DIFFUSION:
  case FP_SUBSTRATE_DIFFUSION:
  case FP_RETRIANGULATE:
    // A curvature-driven fairing flow: it belongs beside MeshLab's Laplacian, Taubin and HC
    // smoothing filters; its re-triangulation stays next to it.
    return MeshFilterInterface::Smoothing;
  }
  return MeshFilterInterface::Generic;
}

MeshFilterInterface::FILTER_ARITY FilterSdflowPlugin::filterArity(QAction*) const { return SINGLE_MESH; }

int FilterSdflowPlugin::getPreConditions(QAction*) const { return MeshModel::MM_FACENUMBER; }

int FilterSdflowPlugin::postCondition(QAction*) const
{
  return MeshModel::MM_VERTCOORD | MeshModel::MM_VERTNORMAL | MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR |
         MeshModel::MM_VERTNUMBER | MeshModel::MM_FACEVERT | MeshModel::MM_FACENORMAL | MeshModel::MM_FACENUMBER;
}

void FilterSdflowPlugin::initParameterSet(QAction* action, MeshModel& model, RichParameterList& parameters)
{
  const double mean_edge_length = sdflow::meshlab::mean_edge_length(sdflow::meshlab::to_surface(model.cm));
  if (const auto flow = flow_filter(ID(action))) {
    add_diffusion_parameters(parameters, mean_edge_length, *flow);
    return;
  }
  if (ID(action) == FP_RETRIANGULATE) {
    const sdflow::meshlab::RetriangulationSettings defaults = sdflow::meshlab::default_retriangulation_settings();
    parameters.addParam(RichFloat("EdgeLength", static_cast<float>(mean_edge_length), "Target edge length ℓ",
                                  "Edge length the surface is remeshed to (≥ 0; 0: the mesh's mean edge length). "
                                  "The default is this mesh's mean edge length; a smaller ℓ gives more triangles."));
    parameters.addParam(RichInt("RemeshIterations", defaults.remesh_iterations, "Remesh iterations",
                                "Rounds of isotropic remeshing towards ℓ (edge splits, collapses, flips and "
                                "tangential smoothing); 0 keeps the triangles as they are."));
    parameters.addParam(RichBool("AlwaysRebuild", defaults.always_rebuild, "Always rebuild from points",
                                 "On: rebuild the surface from its points (jet normals, advancing front) and fill "
                                 "its holes even when nothing intersects. Off: rebuild only when the remeshed "
                                 "surface intersects itself, otherwise keep it."));
    parameters.addParam(RichBool("FillHoles", defaults.fill_holes, "Fill holes",
                                 "Fill the holes a rebuild from points leaves: every hole of a closed surface; on "
                                 "an open one, the loops shorter than half its shortest boundary. Off: leave them "
                                 "open."));
    parameters.addParam(RichInt("MinComponentFaces", defaults.min_component_faces, "Minimum component faces",
                                "Connected components with fewer triangles are dropped as debris (≥ 1); closed "
                                "components enclosing almost no volume are dropped too."));
  }
}

bool FilterSdflowPlugin::applyFilter(QAction* action, MeshDocument& document, const RichParameterList& parameters,
                                     vcg::CallBackPos* progress)
{
  MeshModel* model = document.mm();
  const QString name = filterName(action);
  try {
    if (!model)
      throw sdflow::InvalidParameter("there is no current mesh");
    const sdflow::meshlab::Surface input = sdflow::meshlab::to_surface(model->cm);
    const auto reporter = reporter_for(*this, progress);
    const std::string label = (model->fullName().isEmpty() ? model->label() : model->fullName()).toStdString();
    sdflow::meshlab::ShadedSurface result;
    if (const auto flow = flow_filter(ID(action)))
      result = sdflow::meshlab::surface_diffusion(input, label, *flow, diffusion_settings(parameters, *flow), reporter);
    else if (ID(action) == FP_RETRIANGULATE)
      result = sdflow::meshlab::retriangulate_surface(input, label, retriangulation_settings(parameters), reporter);
    else
      throw std::logic_error("unknown filter " + name.toStdString());
    // Only a complete result touches the user's mesh.
    sdflow::meshlab::replace_mesh(model->cm, result);
    model->updateDataMask(MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTNORMAL);
    Log("%s: %d vertices, %d faces; vertex quality = mean curvature H", qUtf8Printable(name), model->cm.vn,
        model->cm.fn);
    return true;
  } catch (const std::exception& e) {
    // meshlabserver does not print errorMessage: the log carries the reason too.
    errorMessage = QString("%1 failed: %2").arg(name, QString::fromUtf8(e.what()));
    Log(GLLogStream::WARNING, errorMessage.toStdString());
    return false;
  }
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterSdflowPlugin)
