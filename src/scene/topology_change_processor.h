// Internal to the scene builder: SOFA's TopologicalChangeProcessor as a TopologyScript
// (fastcorot/sim/topology_script.h), from its data (useDataInputs, timeToRemove, interval,
// tetrahedraToRemove) or from its file of timed changes (filename; docs/cutting.md gives the format).
#pragma once

#include "scene_data.h"

#include "fastcorot/sim/topology_script.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace fastcorot::scene_detail {

TopologyScript build_topology_script(SceneData& data, Component& processor, std::shared_ptr<TetMesh> mesh);

// Reads a TopologicalChangeProcessor file: blocks "T= time" each followed by "REMOVE= N" and N
// tetrahedron indices and/or "ADD= Tetrahedra N" and 4N point indices. Throws fastcorot::Error
// naming the file and line for anything else.
std::vector<TopologyEvent> read_topology_changes(const std::filesystem::path& path);

}  // namespace fastcorot::scene_detail
