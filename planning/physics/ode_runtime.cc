#include "planning/physics/ode_runtime.h"

#include <ode/ode.h>

#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace planning::physics {
namespace {

std::atomic<bool> g_runtime_alive{false};

std::string FormatOdeMessage(int errnum, const char* msg, va_list ap) {
  char buffer[512];
  std::vsnprintf(buffer, sizeof(buffer), msg, ap);
  return "ODE error " + std::to_string(errnum) + ": " + buffer;
}

// ODE calls abort() if an error handler returns; throwing lets the caller report the failure.
[[noreturn]] void ThrowOdeError(int errnum, const char* msg, va_list ap) {
  throw std::runtime_error(FormatOdeMessage(errnum, msg, ap));
}

// ODE's informational messages (e.g. LCP internal warnings) are not errors; drop them so that
// library code never writes to stderr. Blow-ups are detected from the state instead.
void IgnoreOdeMessage(int, const char*, va_list) {}

// True when the libccd-based cylinder colliders are registered (cylinder–cylinder contact works).
bool CylinderCollidersWork() {
  dGeomID a = dCreateCylinder(nullptr, 0.05, 0.2);
  dGeomID b = dCreateCylinder(nullptr, 0.05, 0.2);
  dGeomSetPosition(a, 0, 0, 0);
  dGeomSetPosition(b, 0.08, 0, 0);
  dContactGeom contacts[4];
  const int n = dCollide(a, b, 4, contacts, sizeof(dContactGeom));
  dGeomDestroy(a);
  dGeomDestroy(b);
  return n > 0;
}

}  // namespace

OdeRuntime::OdeRuntime() {
  if (g_runtime_alive.exchange(true)) {
    throw std::logic_error("OdeRuntime: only one instance may exist at a time");
  }
  dInitODE2(0);
  dAllocateODEDataForThread(dAllocateMaskAll);
  dSetErrorHandler(&ThrowOdeError);
  dSetDebugHandler(&ThrowOdeError);
  dSetMessageHandler(&IgnoreOdeMessage);
  std::string problem;
  if (!dCheckConfiguration("ODE_double_precision")) {
    problem = "ODE is not the double-precision build (need libode-dev with precision=dDOUBLE)";
  } else if (!CylinderCollidersWork()) {
    problem = "ODE was built without the libccd cylinder colliders";
  }
  if (!problem.empty()) {
    dCloseODE();
    g_runtime_alive = false;
    throw std::runtime_error(problem);
  }
}

OdeRuntime::~OdeRuntime() {
  dCloseODE();
  g_runtime_alive = false;
}

const char* OdeRuntime::configuration() const { return dGetConfiguration(); }

}  // namespace planning::physics
