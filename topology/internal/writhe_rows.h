// Internal to the topology module: the row driver of the writhe kernel, shared by the dense
// matrix (topology/writhe.h) and the streaming sums (topology/writhe_stream.h), so that both
// evaluate exactly the same closed-form segment-pair formula (Klenin & Langowski 2000).
#pragma once

#include "topology/polyline.h"
#include "topology/writhe.h"

namespace topology::internal {

// Receives one computed row of W: row index i, the cols values W[i][0..cols), and the kernel's
// atan2 arguments (x, y) of every pair (W[i][j] = −atan2(y_j, x_j)/(2π); degenerate pairs have
// exactly x = 1, y = 0). The pointers are valid only during the call.
class WritheRowSink {
 public:
  virtual ~WritheRowSink() = default;
  virtual void Row(int i, const double* w, const double* x, const double* y, int cols) = 0;
};

// Throws std::invalid_argument for a chain the kernel refuses (fewer than 2 points, a
// non-finite coordinate or one beyond ±kMaxCoordinate); `name` is "A" or "B".
void CheckWritheChain(const Chain& c, const char* name);

// Checks a chain for a linking number (CheckWritheChain, then closed as IsClosedChain says; else
// std::invalid_argument naming `name`) and returns it, or *copy with its last point moved exactly
// onto its first when it was closed only within the gap.
const Chain& CheckClosedSnapped(const Chain& c, const char* name, Chain* copy);

// Rows [row_begin, row_end) of W(A, B) (values only, no gradient), handed to `sink` in order.
// The chains must have been checked. Allocation-free once `ws` has the sizes of B.
void WritheRows(const Chain& a, const Chain& b, const WritheOptions& options, int row_begin,
                int row_end, WritheWorkspace* ws, WritheRowSink* sink);

}  // namespace topology::internal
