#pragma once
//! \file gnuplot.h
//! \brief Running gnuplot for the verbs that draw (plot, render): script literals and a shell-free
//! invocation.

#include <filesystem>
#include <string>

namespace sdflow::cli {

//! A string literal for a gnuplot script (single quotes, a quote doubled, in which gnuplot expands
//! nothing). Throws InvalidParameter for text with a control character (a newline would end the
//! string and the command, and the rest would run as gnuplot commands).
std::string gnuplot_quoted(const std::string& text);

//! Run `gnuplot SCRIPT` without a shell (any character may appear in the path); its stderr goes to
//! `log` and into the message of the std::runtime_error thrown when it cannot start or fails.
void run_gnuplot(const std::filesystem::path& script, const std::filesystem::path& log);

} // namespace sdflow::cli
