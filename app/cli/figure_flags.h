// Command-line flags about figures (the render library's formats); not in io.h, which the
// launcher's commands use without the renderer.
#pragma once

#include <CLI/CLI.hpp>
#include <vector>

#include "render/figure.h"

namespace app {

// --formats LIST on a command that writes several figures: "png,svg,pdf" or a subset (default
// png). The parsed list is checked at parse time (exit 2 for an unknown name).
void AddFormatsFlag(CLI::App* command, std::vector<render::FigureFormat>* formats);

}  // namespace app
