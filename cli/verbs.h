#pragma once
//! \file verbs.h
//! \brief The sdflow command's verbs. Each file `verb_NAME.cpp` adds one subcommand: it parses
//! options into the toolbox's option structs, calls the toolbox, and reports. No numerics here.

#include <CLI/CLI.hpp>

namespace sdflow::cli {

void add_fill_holes_verb(CLI::App& app);
void add_normals_verb(CLI::App& app);
void add_plot_verb(CLI::App& app);
void add_reconstruct_verb(CLI::App& app);
void add_remesh_verb(CLI::App& app);
void add_render_verb(CLI::App& app);
void add_retriangulate_verb(CLI::App& app);
void add_run_verb(CLI::App& app);
void add_shape_verb(CLI::App& app);
void add_stats_verb(CLI::App& app);
void add_repair_verb(CLI::App& app);
void add_intersections_verb(CLI::App& app);
void add_components_verb(CLI::App& app);
void add_axisymmetric_verb(CLI::App& app);
void add_union_verb(CLI::App& app);

} // namespace sdflow::cli
