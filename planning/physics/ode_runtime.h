// The process-wide ODE library lifetime: the single place that calls dInitODE2 / dCloseODE.
#pragma once

namespace planning::physics {

// RAII guard for ODE's global state. Create exactly one in `main` (or in a test fixture) before
// any GraspSimulation and keep it alive while simulations exist; every simulation takes a
// `const OdeRuntime&` as proof that ODE is initialised. The constructor calls dInitODE2(0),
// allocates ODE's per-thread data for the calling thread, installs error/debug handlers that turn
// ODE errors into C++ exceptions (std::runtime_error) instead of abort(), and checks that the
// library is the double-precision build with the libccd cylinder colliders (throws
// std::runtime_error otherwise). The destructor calls dCloseODE(). Only one OdeRuntime may exist
// at a time (a second one throws std::logic_error); it is not copyable or movable.
class OdeRuntime {
 public:
  OdeRuntime();
  ~OdeRuntime();
  OdeRuntime(const OdeRuntime&) = delete;
  OdeRuntime& operator=(const OdeRuntime&) = delete;

  // ODE's configuration string (dGetConfiguration), e.g. "ODE ODE_double_precision ...".
  const char* configuration() const;
};

}  // namespace planning::physics
