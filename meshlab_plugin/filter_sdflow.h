#pragma once
//! \file filter_sdflow.h
//! \brief MeshLab filter plugin: surface diffusion flow (V_N = -ΔH) and the re-triangulation of
//! paper §3.2.1 from the sdflow toolbox.
//!
//! A thin adapter: it reads MeshLab's parameters into the toolbox's settings, converts the mesh
//! (convert.h), calls the toolbox through toolbox_bridge.h, and reports. No numerics live here.

#include <common/interfaces.h>

class FilterSdflowPlugin : public QObject, public MeshFilterInterface {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)

public:
  enum { FP_SURFACE_DIFFUSION, FP_RETRIANGULATE, FP_ANISOTROPIC_DIFFUSION, FP_SUBSTRATE_DIFFUSION };

  FilterSdflowPlugin();

  using MeshFilterInterface::filterInfo;
  using MeshFilterInterface::filterName;
  using MeshFilterInterface::initParameterSet;
  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction* action) override;
  FILTER_ARITY filterArity(QAction* action) const override;
  int getPreConditions(QAction* action) const override;
  int postCondition(QAction* action) const override;
  void initParameterSet(QAction* action, MeshModel& model, RichParameterList& parameters) override;
  bool applyFilter(QAction* action, MeshDocument& document, const RichParameterList& parameters,
                   vcg::CallBackPos* progress) override;
};
