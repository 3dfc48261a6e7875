// `topoplan writhe` and `topoplan winding`: topology features of chain CSV files.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "render/figure.h"
#include "topology/polyline.h"
#include "topology/winding.h"
#include "topology/writhe.h"
#include "topology/writhe_stream.h"
#include "visualize/figures.h"

namespace app {
namespace {

nlohmann::json MatrixToJson(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    rows.push_back(std::move(row));
  }
  return rows;
}

void PrintTable(const Eigen::MatrixXd& w, double total, bool unsigned_variant) {
  std::printf("writhe matrix %ldx%ld (%s), rows = segments of A\n", static_cast<long>(w.rows()),
              static_cast<long>(w.cols()),
              unsigned_variant ? "unsigned solid angle, radians" : "signed, /4pi");
  if (w.size() <= 20 * 20) {
    std::printf("      ");
    for (Eigen::Index j = 0; j < w.cols(); ++j) std::printf(" %9ld", static_cast<long>(j));
    std::printf("\n");
    for (Eigen::Index i = 0; i < w.rows(); ++i) {
      std::printf("%5ld ", static_cast<long>(i));
      for (Eigen::Index j = 0; j < w.cols(); ++j) std::printf(" %+9.5f", w(i, j));
      std::printf("\n");
    }
  } else {
    std::printf("(matrix too large to print; use --json)\n");
  }
  std::printf("total %.12g\n", total);
}

struct WritheArgs {
  std::string a_path, b_path, heatmap_path, heatmap_size = "640x480";
  bool json = false, total_only = false, unsigned_variant = false, row_sums = false;
  int threads = 0;
};

struct WindingArgs {
  std::string chain_path, axis_text;
  bool json = false, unsigned_variant = false, per_segment = false;
};

// --total (and --row-sums) without the matrix: O(N) memory, any N.
int StreamTotal(const topology::Chain& a, const topology::Chain& b, const WritheArgs& wa) {
  const StopCheck stop(0.0);
  topology::WritheStreamOptions options;
  if (wa.unsigned_variant) options.writhe.variant = topology::WritheVariant::kUnsignedSolidAngle;
  options.threads = wa.threads;
  options.row_sums = wa.row_sums;
  options.progress = PairProgress("writhe --total", stop);
  const topology::WritheSums s = topology::StreamWritheSums(a, b, options);
  EndProgress();
  const Eigen::VectorXd& r = s.row_sums;
  if (wa.json) {
    nlohmann::ordered_json j;
    j["rows"] = s.rows;
    j["cols"] = s.cols;
    j["total"] = s.total;
    if (wa.row_sums) j["row_sums"] = std::vector<double>(r.data(), r.data() + r.size());
    std::cout << j.dump() << "\n";
  } else {
    std::printf("rows %d cols %d total %.17g\n", s.rows, s.cols, s.total);
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      std::printf("row %ld %.17g\n", static_cast<long>(i), r(i));
    }
  }
  return kExitOk;
}

}  // namespace

void AddTopologyCommands(CLI::App* root, CommandList* commands) {
  // writhe ---------------------------------------------------------------------------------------
  auto wa = std::make_shared<WritheArgs>();
  CLI::App* writhe = root->add_subcommand(
      "writhe", "Writhe matrix of two chains (Gauss linking integral per segment pair)");
  writhe->add_option("A", wa->a_path, "first chain CSV (x,y,z per line); rows of the matrix")
      ->required();
  writhe->add_option("B", wa->b_path, "second chain CSV; columns of the matrix")->required();
  writhe->add_flag("--json", wa->json,
                   "print {\"rows\",\"cols\",\"total\",\"matrix\"} with full double precision");
  writhe->add_flag("--total", wa->total_only,
                   "print only rows, cols and the total; streamed (no matrix is stored, any "
                   "length, both cores, progress and Ctrl-C)");
  writhe->add_flag("--row-sums", wa->row_sums,
                   "with --total: also each row's sum (one per segment of A), streamed");
  AddStreamThreadsFlag(writhe, &wa->threads);
  writhe->add_flag("--unsigned", wa->unsigned_variant,
                   "unsigned solid angle Omega* in [0, 2pi) per entry (the thesis code's variant)");
  writhe->add_option("--heatmap", wa->heatmap_path,
                     "also write the matrix as a heatmap figure (.png, .svg or .pdf; see "
                     "`topoplan heatmap`)");
  writhe->add_option("--heatmap-size", wa->heatmap_size, "heatmap size WxH (default 640x480)")
      ->check(NonEmpty());
  writhe->footer(
      "Entry (i,j) = 1/(4pi) * double integral over segment i of A and segment j of B of\n"
      "(a-b).(da x db)/|a-b|^3. For two closed polygons the total is their linking number\n"
      "(`topoplan linking` rounds it when its error bound allows). Without --total the matrix\n"
      "is stored (at most 25,000,000 pairs); --total has no limit.");
  commands->push_back(
      {writhe, [wa, writhe]() -> int {
         const topology::Chain a = topology::ReadChainCsv(wa->a_path);
         const topology::Chain b = topology::ReadChainCsv(wa->b_path);
         if (wa->row_sums && !wa->total_only) {
           throw std::invalid_argument("--row-sums: needs --total");
         }
         if (wa->total_only && wa->heatmap_path.empty()) return StreamTotal(a, b, *wa);
         CheckWrithePairs(a.cols(), b.cols());
         int width = 0, height = 0;
         if (writhe->count("--heatmap") > 0) {  // "" is refused
           visualize::ParseImageSize(wa->heatmap_size, "--heatmap-size", &width, &height);
           base::CheckOutputFile(wa->heatmap_path, "--heatmap", {wa->a_path, wa->b_path});
           render::FigureFormatForPath(wa->heatmap_path, "--heatmap");
         }
         topology::WritheOptions options;
         if (wa->unsigned_variant) options.variant = topology::WritheVariant::kUnsignedSolidAngle;
         const Eigen::MatrixXd w = topology::WritheMatrix(a, b, options);
         const double total = w.sum();
         if (wa->json) {
           nlohmann::ordered_json j;
           j["rows"] = w.rows();
           j["cols"] = w.cols();
           j["total"] = total;
           if (!wa->total_only) j["matrix"] = MatrixToJson(w);
           std::cout << j.dump() << "\n";
         } else if (wa->total_only) {
           std::printf("rows %ld cols %ld total %.17g\n", static_cast<long>(w.rows()),
                       static_cast<long>(w.cols()), total);
         } else {
           PrintTable(w, total, wa->unsigned_variant);
         }
         if (!wa->heatmap_path.empty()) {
           const auto stem = [](const std::string& p) {
             return std::filesystem::path(p).stem().string();
           };
           visualize::WritheFigureOptions f;
           f.width = width;
           f.height = height;
           f.signed_values = !wa->unsigned_variant;
           render::WriteFigure(wa->heatmap_path,
                               visualize::WritheFigure(w, stem(wa->a_path), stem(wa->b_path), f),
                               "--heatmap");
           std::fprintf(stderr, "wrote %s\n", wa->heatmap_path.c_str());
         }
         return kExitOk;
       }});

  // winding --------------------------------------------------------------------------------------
  auto na = std::make_shared<WindingArgs>();
  CLI::App* winding =
      root->add_subcommand("winding", "Winding number of a chain about an oriented axis");
  winding->add_option("CHAIN", na->chain_path, "chain CSV (x,y,z per line)")->required();
  winding
      ->add_option("--axis", na->axis_text,
                   "axis point and direction px,py,pz,dx,dy,dz (angles counter-clockwise about d)")
      ->required();
  winding->add_flag("--json", na->json, "print {\"winding\": w}");
  winding->add_flag("--unsigned", na->unsigned_variant,
                    "sum of unsigned arccos angles (Eq. 4 of Ivan et al. 2013)");
  winding->add_flag("--segments", na->per_segment, "also print the per-segment contributions");
  commands->push_back(
      {winding, [na]() {
         // Coordinates up to 1e6 keep |direction|² and the chain's offsets finite.
         const std::vector<double> ax = base::ParseNumberList(na->axis_text, "--axis", 6, 1e6);
         topology::Axis axis{{ax[0], ax[1], ax[2]}, {ax[3], ax[4], ax[5]}};
         if (!(axis.direction.norm() >= 1e-9)) {
           throw std::invalid_argument("--axis: direction dx,dy,dz must be non-zero (|d| >= 1e-9)");
         }
         const topology::Chain chain = topology::ReadChainCsv(na->chain_path);
         topology::WindingOptions options;
         if (na->unsigned_variant) options.variant = topology::WindingVariant::kUnsignedArccos;
         const double w = topology::WindingNumber(chain, axis, options);
         if (na->json) {
           nlohmann::ordered_json j;
           j["winding"] = w;
           if (na->per_segment) {
             const Eigen::VectorXd s = topology::SegmentWindings(chain, axis, options);
             j["segments"] = std::vector<double>(s.data(), s.data() + s.size());
           }
           std::cout << j.dump() << "\n";
         } else {
           std::printf("winding %.12g turns (%.6g deg)\n", w, 360.0 * w);
           if (na->per_segment) {
             const Eigen::VectorXd s = topology::SegmentWindings(chain, axis, options);
             for (Eigen::Index i = 0; i < s.size(); ++i) {
               std::printf("segment %ld %+.9f\n", static_cast<long>(i), s(i));
             }
           }
         }
         return kExitOk;
       }});
}

}  // namespace app
