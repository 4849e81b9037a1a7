# Re-triangulation (docs/design.md §3): the pipeline and the stages that only it composes.
target_sources(sdflow_toolbox PRIVATE
  sdflow/retri/components.cpp
  sdflow/retri/corefine.cpp
  sdflow/retri/curvature_targets.cpp
  sdflow/retri/input_checks.cpp
  sdflow/retri/fixed_rim.cpp
  sdflow/retri/local_surgery.cpp
  sdflow/retri/open_orientation.cpp
  sdflow/retri/remove_intersections.cpp
  sdflow/retri/surface_repair.cpp
  sdflow/retri/surface_union.cpp
  sdflow/retri/surgery_patch.cpp
  sdflow/retri/untangle.cpp
  sdflow/retri/zip_loops.cpp
  sdflow/retri/pipeline.cpp)
