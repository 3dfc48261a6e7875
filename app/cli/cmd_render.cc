// `topoplan render`, `topoplan heatmap` and `topoplan diff`: offscreen images of scene files,
// writhe heatmaps of chain files, and the snapshot image diff.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/io.h"
#include "app/cli/robot_flags.h"
#include "render/diff.h"
#include "render/figure.h"
#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/renderer.h"
#include "topology/polyline.h"
#include "topology/writhe.h"
#include "topology/writhe_stream.h"
#include "visualize/figures.h"
#include "visualize/scene_builder.h"
#include "visualize/scene_file.h"

namespace app {
namespace {

namespace fs = std::filesystem;

struct RenderArgs {
  std::string input, output, size, camera, gl, q, pose;
  planning::RobotInputOptions robot_input;
  int msaa = 0;
  bool no_shadows = false;
};

struct HeatmapArgs {
  std::string a_path, b_path, output, size = "640x480", title, row_label, col_label;
  double clim = 0.0;
  bool unsigned_variant = false, mark_peak = false;
  int max_cells = 256, threads = 0;
};

struct DiffArgs {
  std::string expected, actual, output;
  double threshold = 0.1;
  long max_pixels = -1;
};

// What `render` can draw. Dispatch is by extension and content so that other inputs can be
// added here: a scene file (JSON object with "shapes"/"camera"/...); issue 4 adds URDF robots
// (".urdf") and scenario files (JSON with a "robot" key).
visualize::SceneDocument LoadRenderInput(const std::string& path, const std::string& q,
                                         const RenderArgs& a) {
  if (!fs::is_regular_file(path)) throw std::invalid_argument(path + ": file not found");
  const std::string ext = fs::path(path).extension().string();
  if (planning::IsRobotSceneFile(path))
    return visualize::RobotSceneDocument(path, q, a.pose, a.robot_input);
  if (!a.pose.empty()) throw std::invalid_argument("--pose: only for a robot or scenario input");
  if (!q.empty()) throw std::invalid_argument("--q: only for a robot .urdf or scenario input");
  if (ext == ".json") return visualize::LoadSceneFile(path);
  throw std::invalid_argument(
      path + ": don't know how to render '" + ext +
      "' files (expected a scene .json, a robot .urdf or a scenario .json)");
}

std::string Stem(const std::string& path) { return fs::path(path).stem().string(); }

}  // namespace

void AddRenderCommands(CLI::App* root, CommandList* commands) {
  // render -----------------------------------------------------------------------------------
  auto ra = std::make_shared<RenderArgs>();
  CLI::App* render_cmd =
      root->add_subcommand("render", "Render a scene file offscreen (OSMesa/llvmpipe) to a PNG");
  render_cmd
      ->add_option("SCENE", ra->input,
                   "scene .json (format: README, section Rendering), robot .urdf, or "
                   "scenario .json with a \"robot\" key")
      ->required();
  render_cmd->add_option("-o,--output", ra->output, "output PNG")->required();
  render_cmd
      ->add_option("--q", ra->q,
                   "robot configuration v1,v2,... in the `fk` joint order (robot .urdf or "
                   "scenario input; default: the scenario's q, else zeros)")
      ->check(NonEmpty());
  AddRobotInputFlags(render_cmd, &ra->robot_input, &ra->pose);
  render_cmd
      ->add_option("--size", ra->size,
                   "image size WxH (default: the file's \"size\", else 640x480)")
      ->check(NonEmpty());
  render_cmd
      ->add_option("--camera", ra->camera,
                   "ex,ey,ez,tx,ty,tz,fovy_deg: eye, target and vertical field of view "
                   "(overrides the file's camera; up stays +z or the file's)")
      ->check(NonEmpty());
  render_cmd->add_option("--msaa", ra->msaa, "multisample anti-aliasing samples (0, 2 or 4)")
      ->check(CLI::IsMember({0, 2, 4}));
  render_cmd->add_flag("--no-shadows", ra->no_shadows, "disable the shadow of the key light");
  render_cmd
      ->add_option("--gl", ra->gl, "GL backend osmesa|egl (default: $TOPOPLAN_GL, else osmesa)")
      ->check(NonEmpty());
  render_cmd->footer(
      "Renders are deterministic: the same file and options give byte-identical PNGs.\n"
      "Exit codes: 0 ok, 2 bad scene/flags (the message names the JSON path), 3 no GL.");
  commands->push_back(
      {render_cmd, [ra]() {
         base::CheckOutputFile(ra->output, "-o", {ra->input});
         visualize::SceneDocument doc = LoadRenderInput(ra->input, ra->q, *ra);
         ReportWarnings(doc.warnings);
         int width = doc.width > 0 ? doc.width : 640, height = doc.height > 0 ? doc.height : 480;
         if (!ra->size.empty()) visualize::ParseImageSize(ra->size, "--size", &width, &height);
         if (!ra->camera.empty()) {
           const std::vector<double> c = base::ParseNumberList(ra->camera, "--camera", 7, 1e6);
           doc.camera.eye = Eigen::Vector3d(c[0], c[1], c[2]).cast<float>();
           doc.camera.target = Eigen::Vector3d(c[3], c[4], c[5]).cast<float>();
           doc.camera.fovy_deg = static_cast<float>(c[6]);
           if (!(c[6] > 0.0 && c[6] < 180.0)) {
             throw std::invalid_argument("--camera: fovy_deg must be in (0, 180)");
           }
           if ((doc.camera.target - doc.camera.eye).norm() == 0.0f) {
             throw std::invalid_argument("--camera: eye and target must differ");
           }
         }
         const render::GlBackend backend =
             ra->gl.empty() ? render::GlBackend::kAuto : render::ParseGlBackend(ra->gl, "--gl");
         render::OffscreenContext context(backend);
         render::Renderer renderer(context.proc_loader());
         render::RenderOptions options;
         options.msaa_samples = ra->msaa;
         options.shadows = !ra->no_shadows;
         const render::Image image = renderer.Render(doc.scene, doc.camera, width, height, options);
         render::WritePng(ra->output, image);
         Note("wrote %s (%dx%d, %s)", ra->output.c_str(), width, height,
              render::GlBackendName(context.backend()));
         return kExitOk;
       }});

  // heatmap ----------------------------------------------------------------------------------
  auto ha = std::make_shared<HeatmapArgs>();
  CLI::App* heatmap = root->add_subcommand(
      "heatmap", "Writhe-matrix heatmap of two chains as a figure (PNG, SVG or PDF)");
  heatmap->add_option("A", ha->a_path, "first chain CSV (rows)")->required();
  heatmap->add_option("B", ha->b_path, "second chain CSV (columns)")->required();
  heatmap->add_option("-o,--output", ha->output, "output figure: .png, .svg or .pdf")->required();
  heatmap
      ->add_option("--size", ha->size,
                   "largest figure size WxH (default 640x480; the canvas follows the "
                   "matrix's aspect)")
      ->check(NonEmpty());
  heatmap->add_option("--title", ha->title, "title (default: chain names and total writhe)")
      ->check(NonEmpty());
  heatmap
      ->add_option("--clim", ha->clim,
                   "colour limit V: colours span [-V, V] (unsigned: [0, V]); default: the "
                   "matrix's max |value|")
      ->check(FiniteIn(1e-300, 1e300));
  heatmap->add_option("--row-label", ha->row_label, "row axis caption (default: Segment of A)")
      ->check(NonEmpty());
  heatmap->add_option("--col-label", ha->col_label, "column axis caption (default: Segment of B)")
      ->check(NonEmpty());
  heatmap->add_flag("--mark-peak", ha->mark_peak,
                    "outline the entry of largest |value| and name it under the axis");
  heatmap->add_flag("--unsigned", ha->unsigned_variant,
                    "unsigned solid-angle variant (sequential viridis colours)");
  IntIn(heatmap->add_option("--max-cells", ha->max_cells,
                            "most cells per axis (default 256): a longer chain is block-summed, "
                            "each cell the sum over its block of segment pairs"),
        1, 4096);
  AddStreamThreadsFlag(heatmap, &ha->threads);
  heatmap->footer(
      "Signed writhe uses a diverging blue-white-red map with limits symmetric about 0;\n"
      "cells are whole pixels in PNG, one <rect> each in SVG; text is real text in SVG/PDF.\n"
      "Chains of more than --max-cells segments (default 256) are block-summed without storing\n"
      "the matrix (any length, bounded memory, progress, Ctrl-C): axis ticks count segments,\n"
      "the colour bar is the summed writhe per block, and the cells still sum to the total.");
  commands->push_back(
      {heatmap, [ha]() {
         int width = 0, height = 0;
         visualize::ParseImageSize(ha->size, "--size", &width, &height);
         base::CheckOutputFile(ha->output, "-o", {ha->a_path, ha->b_path});
         render::FigureFormatForPath(ha->output, "-o");  // the format, checked before the work
         const topology::Chain a = topology::ReadChainCsv(ha->a_path);
         const topology::Chain b = topology::ReadChainCsv(ha->b_path);
         topology::WritheStreamOptions options;
         if (ha->unsigned_variant) {
           options.writhe.variant = topology::WritheVariant::kUnsignedSolidAngle;
         }
         visualize::WritheFigureOptions f;
         Eigen::MatrixXd w;
         if (a.cols() - 1 <= ha->max_cells && b.cols() - 1 <= ha->max_cells) {
           w = topology::WritheMatrix(a, b, options.writhe);
         } else {  // block sums, streamed: at most max_cells² cells in memory
           const StopCheck stop(0.0);
           options.threads = ha->threads;
           options.progress = PairProgress("heatmap", stop);
           topology::WritheBlockSums s =
               topology::BlockWritheSums(a, b, ha->max_cells, ha->max_cells, options);
           EndProgress();
           w = std::move(s.sums);
           f.row_block = s.row_block;
           f.col_block = s.col_block;
         }
         f.width = width;
         f.height = height;
         f.title = ha->title;
         f.signed_values = !ha->unsigned_variant;
         f.row_label = ha->row_label;
         f.col_label = ha->col_label;
         f.limit = ha->clim;
         f.mark_peak = ha->mark_peak;
         render::WriteFigure(ha->output,
                             visualize::WritheFigure(w, Stem(ha->a_path), Stem(ha->b_path), f));
         if (f.row_block > 1 || f.col_block > 1) {
           Note("wrote %s (%ldx%ld blocks of %dx%d segments, total %.6f)", ha->output.c_str(),
                static_cast<long>(w.rows()), static_cast<long>(w.cols()), f.row_block, f.col_block,
                w.sum());
         } else {
           Note("wrote %s (%ldx%ld writhe matrix, total %.6f)", ha->output.c_str(),
                static_cast<long>(w.rows()), static_cast<long>(w.cols()), w.sum());
         }
         return kExitOk;
       }});

  // diff -------------------------------------------------------------------------------------
  auto da = std::make_shared<DiffArgs>();
  CLI::App* diff = root->add_subcommand(
      "diff", "Compare two PNGs with the snapshot tolerance (perceptual YIQ, AA excluded)");
  diff->add_option("A", da->expected, "expected PNG")->required();
  diff->add_option("B", da->actual, "actual PNG")->required();
  diff->add_option("-o,--output", da->output,
                   "write a diff image (differing pixels red, anti-aliasing yellow)");
  diff->add_option("--threshold", da->threshold, "YIQ threshold in [0,1] (default 0.1)")
      ->check(FiniteIn(0.0, 1.0));
  IntIn(diff->add_option("--max-pixels", da->max_pixels,
                         "allowed differing pixels (default max(10, 0.005% of the pixels))"),
        0, 1000000000);
  diff->footer(
      "Exit codes: 0 within tolerance, 1 images differ, 2 bad input (missing file, not "
      "a PNG, sizes differ).");
  commands->push_back(
      {diff, [da, diff]() {
         if (diff->count("-o") > 0) {
           base::CheckOutputFile(da->output, "-o", {da->expected, da->actual});
         }  // "" is refused
         const render::Image a = render::ReadPng(da->expected);
         const render::Image b = render::ReadPng(da->actual);
         render::DiffOptions options;
         options.threshold = da->threshold;
         options.max_diff_pixels = da->max_pixels;
         const render::DiffResult r = render::CompareImages(a, b, options);
         if (!da->output.empty()) render::WritePng(da->output, r.visual);
         if (r.identical) {
           std::printf("identical (%dx%d)\n", a.width, a.height);
         } else {
           std::printf(
               "%ld differing pixels (allowed %ld; %ld anti-aliasing, %ld changed, max "
               "channel delta %d)\n",
               r.diff_pixels, r.allowed, r.aa_pixels, r.changed_pixels, r.max_channel_delta);
         }
         return r.passed ? kExitOk : kExitFailed;
       }});
}

}  // namespace app
