// RAII for gmsh's process-wide state, shared by the stages that call gmsh (tfmb-input reads CAD
// curves with it, tfmb-mesh meshes with it). Only in the tfmb_gmsh library, which exists where
// libgmsh-dev is installed.
#pragma once

namespace tfmb {

// Initialises gmsh quietly (no terminal output) and finalises it on scope exit.
class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

}  // namespace tfmb
