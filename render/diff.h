// Perceptual image difference for snapshot tests and `topoplan diff`, and the golden-image check
// the tests share.
//
// Metric (after pixelmatch, Kotsarenko & Ramos 2010): for each pixel whose RGBA differs, the
// squared YIQ distance d = 0.5053 dY^2 + 0.299 dI^2 + 0.1957 dQ^2 (colours blended over white by
// their alpha) is compared against 35215 * threshold^2 (35215 is the largest possible d). A pixel
// over the threshold counts as different unless it is anti-aliased in either image (Vysniauskas
// 2009: at most 2 identical neighbours, both a darker and a brighter neighbour, and that darkest
// or brightest neighbour has >= 3 identical neighbours in both images). On the reference machine
// this gives 0 counted pixels for rasteriser noise (llvmpipe vs softpipe) and 38 for a removed
// 4-pixel bead.
#pragma once

#include <cstdint>
#include <string>

#include "render/image.h"

namespace render {

struct DiffOptions {
  double threshold = 0.1;     // YIQ threshold in [0, 1]; smaller is stricter
  bool include_aa = false;    // count anti-aliased pixels too
  long max_diff_pixels = -1;  // allowed count; < 0: DefaultAllowedDiffPixels(w, h)
};

struct DiffResult {
  long diff_pixels = 0;       // pixels over the threshold, not anti-aliasing
  long aa_pixels = 0;         // pixels over the threshold but classified as anti-aliasing
  long changed_pixels = 0;    // pixels whose RGBA bytes differ at all
  long allowed = 0;           // the count that was allowed
  int max_channel_delta = 0;  // largest |difference| of one channel, 0..255
  bool identical = false;     // byte-identical pixels
  bool passed = false;        // diff_pixels <= allowed
  // Visualisation: a faded grey copy of `expected`, counted pixels red, anti-aliased ones yellow.
  Image visual;
};

// max(10, ceil(0.005 % of the pixels)): 10 px at 320x240, 15 at 640x480, 47 at 1280x720.
long DefaultAllowedDiffPixels(int width, int height);

// Compares two images of the same size. Throws std::invalid_argument (naming both sizes) when
// the sizes differ.
DiffResult CompareImages(const Image& expected, const Image& actual,
                         const DiffOptions& options = {});

// |expected - actual| per channel times `gain` (clamped to 255) on black, alpha 255: makes
// 1-level differences visible.
Image AmplifiedDifference(const Image& expected, const Image& actual, int gain = 10);

// Outcome of CheckSnapshot.
struct SnapshotResult {
  bool passed = false;
  bool updated = false;  // UPDATE_SNAPSHOTS=1 rewrote the golden
  DiffResult diff;
  std::string message;  // one line for the test log: counts, artefact paths, or what to do
};

// Compares `actual` with the golden PNG at `golden_path`.
//  - UPDATE_SNAPSHOTS=1 in the environment: (re)writes the golden when its pixels differ and
//    passes.
//  - Golden missing: writes the candidate to artefact_dir/<stem>.png and fails, with a hint to
//    run with UPDATE_SNAPSHOTS=1.
//  - Otherwise compares with CompareImages; on failure (or a size mismatch) writes
//    <stem>.png (actual), <stem>-expected.png, <stem>-diff.png (visual) and <stem>-absdiff.png
//    (AmplifiedDifference) into artefact_dir (created when needed).
SnapshotResult CheckSnapshot(const Image& actual, const std::string& golden_path,
                             const std::string& artefact_dir, const DiffOptions& options = {});

}  // namespace render
