// The force fields of a MechanicalSystem as their concrete classes, for tests that read their
// parameters (the system holds them behind the ForceField interface).
#pragma once

#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/fem/tetrahedron_fem_force_field.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

namespace fastcorot::testing {

template <class Field, class Real>
Field& field_as(const std::shared_ptr<ForceField<Real>>& field) {
  auto* concrete = dynamic_cast<Field*>(field.get());
  if (!concrete) throw std::logic_error("the force field is a " + field->component());
  return *concrete;
}

template <class Real>
CorotationalForceField<Real>& corotational(const std::shared_ptr<ForceField<Real>>& field) {
  return field_as<CorotationalForceField<Real>>(field);
}

}  // namespace fastcorot::testing
