// VisualSurface: a visual model of SOFA (an OglModel in a child node of a simulated object) whose
// points follow the object's points through a mapping: BarycentricMapping (onto the tetrahedra, or,
// when the object's first topology is a RegularGridTopology, trilinearly onto its cells, as SOFA
// chooses) or IdentityMapping. Display only: the physics never reads it. PointMapping is the
// mapping in one form for all three (mapping/point_mapping.h).
#pragma once

#include "fastcorot/core/types.h"
#include "fastcorot/mapping/mechanical_mapping.h"
#include "fastcorot/mapping/point_mapping.h"
#include "fastcorot/mapping/rigid_points.h"

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace fastcorot {

struct VisualSurface {
  std::string path;                      // the visual model: node path / name
  std::vector<Vec3<double>> rest_points;  // the model's points as loaded and placed
  std::vector<Triangle> triangles;
  std::array<float, 4> color{0.8f, 0.8f, 0.8f, 1.0f};
  std::string mapping;  // "BarycentricMapping (tetrahedra)", ... for messages and docs
  PointMapping<double> map;
  // Set for a visual model under a RigidMapping: its points follow rigid bodies (map is unused).
  std::optional<RigidPoints<double>> rigid;
  // Set for a visual model below a SubsetMultiMapping, or below points that several rigids carry:
  // map reads the points `through` gives (from the object's blocks starting at through_offset,
  // the part's first block once objects are merged), not the object's.
  std::shared_ptr<const MechanicalMapping<double>> through;
  Index through_offset = 0;

  // The surface's points for the object's positions x.
  std::vector<Vec3<double>> points(std::span<const Vec3<double>> x) const;
};

}  // namespace fastcorot
