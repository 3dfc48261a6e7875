#include "app/cli/demo_page.h"

#include <sys/utsname.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <optional>
#include <thread>

#include "app/cli/io.h"
#include "app/present/reports.h"
#include "base/numbers.h"
#include "base/version.h"

namespace app {

namespace fs = std::filesystem;

std::vector<fs::path> SortedPngs(const fs::path& dir, const std::string& prefix) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (e.path().extension() == ".png" && n.rfind(prefix, 0) == 0) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

render::Image SideBySideImages(const render::Image& a, const render::Image& b) {
  const int h = std::max(a.height, b.height);
  render::Image out(a.width + b.width, h, 255, 255, 255);
  auto paste = [&](const render::Image& img, int x0) {
    const int y0 = (h - img.height) / 2;
    for (int y = 0; y < img.height; ++y) {
      std::copy_n(img.at(0, y), 4 * img.width, out.at(x0, y0 + y));
    }
  };
  paste(a, 0);
  paste(b, a.width);
  return out;
}

std::string DemoProvenanceHtml() {
  std::string cpu = "unknown CPU", memory;
  {
    std::ifstream info("/proc/cpuinfo");
    for (std::string line; std::getline(info, line);) {
      if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
        cpu = line.substr(line.find(':') + 2);
        break;
      }
    }
    std::ifstream mem("/proc/meminfo");
    for (std::string line; std::getline(mem, line);) {
      if (line.rfind("MemTotal:", 0) != 0) continue;
      const size_t first = line.find_first_of("0123456789");
      const size_t last = line.find_first_not_of("0123456789", first);
      const std::optional<long long> kb =
          first == std::string::npos ? std::nullopt
                                     : base::ParseInteger(line.substr(first, last - first));
      if (kb) {
        memory = ", " + base::FormatFixed(static_cast<double>(*kb) / 1048576.0, 1) + " GiB";
      }
      break;
    }
  }
  struct utsname u {};
  const std::string system = ::uname(&u) == 0
                                 ? std::string(u.sysname) + " " + u.release + " " + u.machine
                                 : "unknown system";
  const std::time_t now = std::time(nullptr);
  char date[32] = "";
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return "<table class=\"provenance\"><tr><th>made by</th><td>topoplan " +
         std::string(base::Version()) + " (commit " + base::Commit() +
         ")</td></tr><tr><th>command</th><td><code>" + HtmlEscape(CommandLine()) +
         "</code></td></tr><tr><th>date</th><td>" + date + "</td></tr><tr><th>machine</th><td>" +
         HtmlEscape(system) + ", " + HtmlEscape(cpu) + ", " +
         std::to_string(std::thread::hardware_concurrency()) + " cores" + memory +
         "</td></tr></table>\n";
}

}  // namespace app
