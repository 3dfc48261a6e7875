// Pieces of the demo's page (app/cli/cmd_demo.cc): frame listings, side-by-side images and the
// provenance table.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/image.h"

namespace app {

// The PNG files in `dir` whose names start with `prefix`, sorted by name; empty when `dir` cannot
// be read.
std::vector<std::filesystem::path> SortedPngs(const std::filesystem::path& dir,
                                              const std::string& prefix);

// Pastes `b` to the right of `a` on a white canvas of width a.width + b.width and the larger
// height (each vertically centred).
render::Image SideBySideImages(const render::Image& a, const render::Image& b);

// Where the page came from, as an HTML table: topoplan's version and commit, this process's
// command line, the date (UTC), the system, the CPU model, the number of cores and the memory.
std::string DemoProvenanceHtml();

}  // namespace app
