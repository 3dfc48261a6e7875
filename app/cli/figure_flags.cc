#include "app/cli/figure_flags.h"

#include <stdexcept>
#include <string>

namespace app {

void AddFormatsFlag(CLI::App* command, std::vector<render::FigureFormat>* formats) {
  *formats = {render::FigureFormat::kPng};
  command
      ->add_option_function<std::string>(
          "--formats",
          [formats](const std::string& list) {
            *formats = render::ParseFigureFormats(list, "--formats");
          },
          "figure formats, a comma-separated subset of png,svg,pdf (default png)")
      ->check([](const std::string& list) {
        try {
          render::ParseFigureFormats(list, "--formats");
        } catch (const std::invalid_argument& e) {
          return std::string(e.what()).substr(std::string("--formats: ").size());
        }
        return std::string();
      });
}

}  // namespace app
