// topoplan: topology-based motion planning and grasp transfer, with offscreen rendering.
#include "app/cli/cli.h"

int main(int argc, char** argv) { return app::RunCommandLine(argc, argv); }
