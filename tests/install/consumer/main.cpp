// Evaluates the force field on one stretched tetrahedron through the installed headers and library;
// exits non-zero unless the forces are non-trivial and sum to zero.
#include <fastcorot/fem/corotational_force_field.h>

#include <iostream>

int main() {
  using namespace fastcorot;
  auto mesh = std::make_shared<TetMesh>(4, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  const std::vector<Vec3<double>> rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  CorotationalForceField<double> field(mesh, rest, {});
  std::vector<Vec3<double>> x = rest, f(4, Vec3<double>::Zero());
  x[1].x() = 1.2;
  field.add_force(x, f);
  const Vec3<double> sum = f[0] + f[1] + f[2] + f[3];
  std::cout << "force on vertex 1: " << f[1].transpose() << "\n";
  return (f[1].x() < 0 && sum.norm() < 1e-9) ? 0 : 1;
}
