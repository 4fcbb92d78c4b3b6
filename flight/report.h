#pragma once
// Reports of recordings: summary.json (summary.h) and the plots, which a matplotlib script
// draws (flight/plots/recording_plots.py, compiled into the program at build time so a moved
// build still has it). The script runs in a child process: `PYTHON SCRIPT report DIR`.
// Without python3 or matplotlib there are no plots and the error says which is missing —
// nothing is faked.

#include <filesystem>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::flight {

// The plot files `report` writes into a recording directory.
const std::vector<std::string>& reportPlotNames();  // frame_time.png, geometric_load.png, streaming_memory.png

// The embedded script's text (generated from flight/plots/recording_plots.py).
const char* plotScriptText();

// The interpreters to try, in order: $VEGSTREAM_PYTHON alone when set and not empty; else
// "python3" on PATH, then /usr/bin/python3 (where Debian's python3-matplotlib lives, when PATH
// leads to another Python such as pyenv's). The first that can import matplotlib draws.
std::vector<std::string> defaultPythons();

// Draws the plots of a recording directory that has frames.csv and summary.json.
// Errors: ErrorKind::Unsupported when the interpreter or matplotlib is missing (the message
// says which and how to install it); ErrorKind::Io when the script fails otherwise.
Status makePlots(const std::filesystem::path& dir, const std::vector<std::string>& pythons);

// The overlay plot of two recordings (frame time and terrain triangles over flight time).
Status makeComparePlot(const std::filesystem::path& dirA, const std::filesystem::path& dirB,
                       const std::filesystem::path& outPng, const std::vector<std::string>& pythons);

}  // namespace vegstream::flight
