// Every file tfmb-loads reads or writes goes through here, so a change in another stage's
// layout (formats/model.md, flow.md, structure.md, flowmesh.md) is adapted in one place.
// Readers validate the file against its schema first (formats::open_checked) and throw
// BadInput "<file>: <path>: <what>".
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "displace.hpp"
#include "mapping.hpp"
#include "trace.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/model.hpp"

namespace tfmb::loads {

// A flap of the model: formats' type as it is (name, material, thickness, width, beam nodes, the
// reference line at full resolution, inner and outer walls).
using ModelFlap = formats::Flap;

struct Model {
  std::filesystem::path file;
  formats::Header header;
  std::vector<ModelFlap> flaps;  // sorted by name
};

Model read_model(const std::filesystem::path& file);

// Wall traces of flap walls (/walls/<b> whose /mesh/boundaries/<b> has a `flap` attribute),
// oriented with the flow mesh: the fluid lies on the side of the mesh cell that owns each
// trace edge. Traces of walls that belong to no flap are skipped.
struct FlowTraces {
  formats::Header header;
  std::vector<WallTrace> traces;
  std::vector<std::string> skipped;  // wall traces without a flap
};
// With `reference_mesh` (the undeformed flowmesh of a two-way run, same topology), the trace
// points are taken at their nodes' reference positions: the loads of a deformed wall are mapped
// onto the undeformed beam, where tfmb-beam applies them (as follower loads).
FlowTraces read_flow_traces(const std::filesystem::path& file,
                            const std::filesystem::path& reference_mesh = {});

// Wall points of flap walls from a mesh-bearing file (flowmesh or flow): per boundary with a
// `flap` attribute, its nodes in edge order.
struct MeshWall {
  std::string name, flap, side;
  std::vector<std::int64_t> nodes;
  std::vector<Vec2> points;
};
std::vector<MeshWall> read_mesh_walls(const std::filesystem::path& file);

struct StructureFlap {
  std::vector<Vec2> points;  // beam node reference positions, in order [m]
  BeamMotion motion;
};
struct Structure {
  formats::Header header;
  std::map<std::string, StructureFlap> flaps;
};
Structure read_structure(const std::filesystem::path& file);

struct LoadsFile {
  formats::Header header;
  Method method = Method::conservative;
  std::string load_basis;
  struct Flap {
    std::string name;
    double width = 0.0;
    std::vector<std::string> traces;
    std::vector<Vec2> nodes;  // beam node reference positions [m]
    FlapLoads loads;
  };
  std::vector<Flap> flaps;
};
void write_loads(const std::filesystem::path& file, const LoadsFile& loads,
                 const formats::Provenance& provenance);

struct WallDisplacement {
  std::string name, flap, side;
  std::vector<std::int64_t> nodes;  // mesh nodes, if the points came from a mesh
  std::vector<Vec2> points;
  std::vector<Vec2> displacement;
};
void write_walldisp(const std::filesystem::path& file, const formats::Header& header,
                    const std::string& wall_source, const std::vector<WallDisplacement>& walls,
                    const formats::Provenance& provenance);

}  // namespace tfmb::loads
