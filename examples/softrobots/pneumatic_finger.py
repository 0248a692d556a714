"""A pneumatic soft finger written for SofaPython3 (our own scene, after the physics of SoftRobots'
pneumatic tutorials): a silicone block 80 × 20 × 20 mm held at its base, with a box-shaped cavity
in its upper half whose walls are 2 mm squares (a SurfacePressureConstraint on quads mapped into
the block). A controller raises the cavity's volume growth by 0.1 cm³ per step up to 8 cm³: the top
lengthens and the finger bends down. Units: metres, kilograms, seconds.

    fastcorot run examples/softrobots/pneumatic_finger.py --steps 100 --png out   (or `view`)
    PYTHONPATH=build/python python3 examples/softrobots/pneumatic_finger.py      (prints the growth)
"""

import Sofa
import Sofa.Simulation

CAVITY = ((0.005, 0.075), (0.010, 0.017), (0.004, 0.016))  # x, y and z extents
STEP = 0.002  # the cavity walls' squares


def box_surface(extents, step):
    """Points and quads (normals facing out) of a box's surface cut into squares of about `step`."""
    (x0, x1), (y0, y1), (z0, z1) = extents
    points, index, quads = [], {}, []

    def cuts(a, b):
        n = max(1, round((b - a) / step))
        return [a + (b - a) * k / n for k in range(n + 1)]

    xs, ys, zs = cuts(x0, x1), cuts(y0, y1), cuts(z0, z1)

    def point(p):
        key = tuple(round(c, 9) for c in p)
        if key not in index:
            index[key] = len(points)
            points.append(list(p))
        return index[key]

    def face(us, vs, at, flip):
        for i in range(len(us) - 1):
            for j in range(len(vs) - 1):
                corners = [point(at(us[i], vs[j])), point(at(us[i + 1], vs[j])),
                           point(at(us[i + 1], vs[j + 1])), point(at(us[i], vs[j + 1]))]
                quads.append(corners[::-1] if flip else corners)

    face(xs, ys, lambda u, v: (u, v, z1), False)  # +z
    face(xs, ys, lambda u, v: (u, v, z0), True)   # -z
    face(ys, zs, lambda u, v: (x1, u, v), False)  # +x
    face(ys, zs, lambda u, v: (x0, u, v), True)   # -x
    face(zs, xs, lambda u, v: (v, y1, u), False)  # +y
    face(zs, xs, lambda u, v: (v, y0, u), True)   # -y
    return points, quads


class Inflate(Sofa.Core.Controller):
    """Raises the commanded volume growth by `rate` each step up to `target`, as SoftRobots'
    controllers do per key press."""

    def __init__(self, *args, **kwargs):
        Sofa.Core.Controller.__init__(self, *args, **kwargs)
        self.cavity, self.rate, self.target = kwargs["cavity"], kwargs["rate"], kwargs["target"]

    def onAnimateBeginEvent(self, event):
        self.cavity.value = [min(self.cavity.value.value[0] + self.rate, self.target)]


def createScene(root):
    root.dt = 0.02
    root.gravity = [0, -9.81, 0]
    root.addObject("FreeMotionAnimationLoop")
    root.addObject("BlockGaussSeidelConstraintSolver", maxIterations=100, tolerance=1e-12)
    finger = root.addChild("finger")
    finger.addObject("EulerImplicitSolver", rayleighMass=0.1, rayleighStiffness=0.1)
    finger.addObject("SparseLDLSolver")
    finger.addObject("RegularGridTopology", n=[17, 5, 5], min=[0, 0, 0], max=[0.08, 0.02, 0.02])
    finger.addObject("MechanicalObject", name="dofs")
    finger.addObject("UniformMass", totalMass=0.03)
    finger.addObject("TetrahedronFEMForceField", youngModulus=1e5, poissonRatio=0.45, method="large")
    finger.addObject("BoxROI", name="base", box=[-0.001, -0.001, -0.001, 0.001, 0.021, 0.021])
    finger.addObject("RestShapeSpringsForceField", points="@base.indices", stiffness=1e8)
    finger.addObject("LinearSolverConstraintCorrection")
    points, quads = box_surface(CAVITY, STEP)
    cavity = finger.addChild("cavity")
    cavity.addObject("MeshTopology", name="surface", position=points, quads=quads)
    cavity.addObject("MechanicalObject", name="points")
    pressure = cavity.addObject("SurfacePressureConstraint", name="pressure", quads="@surface.quads",
                                valueType="volumeGrowth", value=0.0)
    cavity.addObject("BarycentricMapping")
    root.addObject(Inflate(name="inflate", cavity=pressure, rate=1e-7, target=8e-6))
    return root


def main():
    root = Sofa.Core.Node("root")
    createScene(root)
    Sofa.Simulation.init(root)
    pressure = root.finger.cavity.pressure
    for step in range(1, 101):
        Sofa.Simulation.animate(root, root.dt.value)
        if step % 20 == 0:
            print(f"step {step}: volume growth {pressure.volumeGrowth.value * 1e6:.3f} cm³, "
                  f"pressure {pressure.pressure.value / root.dt.value:.1f} Pa")


if __name__ == "__main__":
    main()
