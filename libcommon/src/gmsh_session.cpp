#include "tfmb/common/gmsh_session.hpp"

#include <gmsh.h>

namespace tfmb {

GmshSession::GmshSession() {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 0);
}

GmshSession::~GmshSession() {
  try {
    gmsh::finalize();
  } catch (...) {
    // A destructor must not throw; gmsh's state is process-wide and gone with the process.
  }
}

}  // namespace tfmb
