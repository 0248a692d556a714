"""A pneumatic soft gripper written for SofaPython3 (our own scene, after the physics of SoftRobots'
PneunetGripper tutorial): three of pneumatic_finger.py's fingers hang around a ball resting on the
floor, their cavities facing out. A controller inflates the three cavities together (their volume
growth up to 4 cm³), so the fingers curl inwards and close on the ball; then it moves the fingers'
rest positions (which the springs holding their bases follow, as SOFA's RestShapeSpringsForceField
does) up by 40 mm, and the ball is carried off the floor by friction. Contacts: triangles of the
fingers' surfaces against the ball, a rigid sphere, under FreeMotionAnimationLoop
(FrictionContactConstraint, mu 0.8). Units: metres, kilograms, seconds.

    fastcorot run examples/softrobots/pneumatic_gripper.py --steps 200 --png out   (or `view`)
    PYTHONPATH=build/python python3 examples/softrobots/pneumatic_gripper.py      (prints the ball's height)
"""

import math
import os
import sys

import numpy as np

import Sofa
import Sofa.Simulation

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pneumatic_finger import CAVITY, STEP, box_surface  # noqa: E402  (the finger's cavity, shared)

FINGER = ((0.0, 0.08), (0.0, 0.02), (0.0, 0.02))  # the finger's block, x along its length
GRID = [17, 5, 5]
BALL_RADIUS = 0.02
TOP = 0.09           # height of the fingers' bases: their tips 10 mm above the floor
RADIUS = 0.036       # distance of the fingers' axes from the gripper's
INFLATE_STEPS, HOLD_STEPS, LIFT_STEPS = 60, 20, 40
LIFT_PER_STEP = 0.001
PRESSURE = 2e5       # Pa, reached over the inflation


def finger_frame(angle):
    """Rotation and base of the finger at `angle` about the vertical axis: its length (local x) hangs
    down, its cavity's side (local +y) faces out, so that inflating curls it inwards."""
    c, s = math.cos(angle), math.sin(angle)
    rotation = np.array([[0.0, c, -s], [-1.0, 0.0, 0.0], [0.0, s, c]])  # columns: local x, y, z in the world
    base = np.array([RADIUS * c, TOP, RADIUS * s])
    return rotation, base


def placed(points, angle):
    """Local finger points (the block's corner at the origin) in the world."""
    rotation, base = finger_frame(angle)
    centred = np.asarray(points, dtype=float) - [0.0, 0.01, 0.01]
    return centred @ rotation.T + base


def grid_points():
    (x0, x1), (y0, y1), (z0, z1) = FINGER
    nx, ny, nz = GRID
    return [[x0 + (x1 - x0) * i / (nx - 1), y0 + (y1 - y0) * j / (ny - 1), z0 + (z1 - z0) * k / (nz - 1)]
            for k in range(nz) for j in range(ny) for i in range(nx)]  # x fastest, as RegularGridTopology


def grid_tetrahedra():
    """The grid's cells each cut into six tetrahedra along its main diagonal (the same cut in every
    cell, so faces match), positively oriented."""
    nx, ny, nz = GRID
    points = np.array(grid_points())
    index = lambda i, j, k: i + nx * (j + ny * k)  # noqa: E731
    tetrahedra = []
    for k in range(nz - 1):
        for j in range(ny - 1):
            for i in range(nx - 1):
                for a, b in ((0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1)):
                    corner = [0, 0, 0]
                    path = [index(i, j, k)]
                    for axis in (a, b, 3 - a - b):
                        corner[axis] = 1
                        path.append(index(i + corner[0], j + corner[1], k + corner[2]))
                    p = points[path]
                    if np.dot(np.cross(p[1] - p[0], p[2] - p[0]), p[3] - p[0]) < 0:
                        path[1], path[2] = path[2], path[1]
                    tetrahedra.append(path)
    return tetrahedra


def triangles_of(quads):
    return [t for q in quads for t in ([q[0], q[1], q[2]], [q[0], q[2], q[3]])]


def sphere_surface(radius, rings=12, segments=24):
    """Points and outward triangles of a UV sphere, for drawing the ball."""
    points = [[0.0, radius, 0.0]]
    for r in range(1, rings):
        phi = math.pi * r / rings
        for k in range(segments):
            theta = 2 * math.pi * k / segments
            points.append([radius * math.sin(phi) * math.cos(theta), radius * math.cos(phi),
                           radius * math.sin(phi) * math.sin(theta)])
    points.append([0.0, -radius, 0.0])
    bottom = len(points) - 1
    ring = lambda r, k: 1 + (r - 1) * segments + k % segments  # noqa: E731
    triangles = [[0, ring(1, k + 1), ring(1, k)] for k in range(segments)]
    for r in range(1, rings - 1):
        for k in range(segments):
            triangles += [[ring(r, k), ring(r, k + 1), ring(r + 1, k + 1)], [ring(r, k), ring(r + 1, k + 1), ring(r + 1, k)]]
    triangles += [[bottom, ring(rings - 1, k), ring(rings - 1, k + 1)] for k in range(segments)]
    return points, triangles


class Grip(Sofa.Core.Controller):
    """Inflates the cavities together, holds, then lifts the fingers by moving their rest positions."""

    def __init__(self, *args, **kwargs):
        Sofa.Core.Controller.__init__(self, *args, **kwargs)
        self.cavities, self.fingers, self.target = kwargs["cavities"], kwargs["fingers"], kwargs["target"]
        self.step = 0

    def onAnimateBeginEvent(self, event):
        self.step += 1
        if self.step <= INFLATE_STEPS:
            for cavity in self.cavities:
                cavity.value = [self.target * self.step / INFLATE_STEPS]
        elif INFLATE_STEPS + HOLD_STEPS < self.step <= INFLATE_STEPS + HOLD_STEPS + LIFT_STEPS:
            for dofs in self.fingers:
                rest = np.array(dofs.rest_position.value)
                rest[:, 1] += LIFT_PER_STEP
                dofs.rest_position.value = rest


def add_finger(root, index, angle):
    finger = root.addChild(f"finger{index}")
    finger.addObject("EulerImplicitSolver", rayleighMass=0.1, rayleighStiffness=0.1)
    finger.addObject("SparseLDLSolver")
    # Tetrahedra of their own rather than a RegularGridTopology: a BarycentricMapping onto a grid maps
    # through the grid's own (unturned) box, as SOFA's does, not through the turned positions.
    finger.addObject("TetrahedronSetTopologyContainer", name="tetrahedra", position=placed(grid_points(), angle),
                     tetrahedra=grid_tetrahedra())
    finger.addObject("MechanicalObject", name="dofs")
    finger.addObject("UniformMass", totalMass=0.03)
    finger.addObject("TetrahedronFEMForceField", youngModulus=1e5, poissonRatio=0.45, method="large")
    finger.addObject("BoxROI", name="base", box=[-0.05, TOP - 0.001, -0.05, 0.05, TOP + 0.001, 0.05])
    finger.addObject("RestShapeSpringsForceField", points="@base.indices", stiffness=1e8)
    finger.addObject("LinearSolverConstraintCorrection")
    points, quads = box_surface(CAVITY, STEP)
    cavity = finger.addChild("cavity")
    cavity.addObject("MeshTopology", name="surface", position=placed(points, angle), quads=quads)
    cavity.addObject("MechanicalObject", name="points")
    pressure = cavity.addObject("SurfacePressureConstraint", name="pressure", quads="@surface.quads",
                                valueType="pressure", value=0.0)
    cavity.addObject("BarycentricMapping")
    skin_points, skin_quads = box_surface(FINGER, 0.005)
    skin = finger.addChild("collision")
    skin.addObject("MeshTopology", name="surface", position=placed(skin_points, angle), triangles=triangles_of(skin_quads))
    skin.addObject("MechanicalObject", name="points")
    skin.addObject("TriangleCollisionModel")
    skin.addObject("LineCollisionModel")
    skin.addObject("PointCollisionModel")
    skin.addObject("BarycentricMapping")
    return finger, pressure


def createScene(root):
    root.dt = 0.02
    root.gravity = [0, -9.81, 0]
    root.addObject("FreeMotionAnimationLoop")
    root.addObject("BlockGaussSeidelConstraintSolver", maxIterations=500, tolerance=1e-6)
    root.addObject("CollisionPipeline")
    root.addObject("BruteForceBroadPhase")
    root.addObject("BVHNarrowPhase")
    root.addObject("MinProximityIntersection", alarmDistance=0.004, contactDistance=0.001)
    root.addObject("CollisionResponse", response="FrictionContactConstraint", responseParams="mu=0.8")
    fingers, cavities = [], []
    for index in range(3):
        finger, pressure = add_finger(root, index, math.pi / 2 + 2 * math.pi * index / 3)
        fingers.append(finger.dofs)
        cavities.append(pressure)
    ball = root.addChild("ball")
    ball.addObject("EulerImplicitSolver", rayleighMass=0.1, rayleighStiffness=0.1)
    ball.addObject("SparseLDLSolver")
    ball.addObject("MechanicalObject", name="dofs", template="Rigid3",
                   position=[0, BALL_RADIUS + 0.001, 0, 0, 0, 0, 1])
    inertia = 2 / 5 * 0.01 * BALL_RADIUS ** 2  # a solid ball of 10 g
    ball.addObject("UniformMass", vertexMass=[0.01, 1, [inertia, 0, 0, 0, inertia, 0, 0, 0, inertia]])
    ball.addObject("LinearSolverConstraintCorrection")
    # Its collision sphere on a point at its centre (a Vec3 sphere: the contact distance is the
    # radius); a SphereCollisionModel on the rigid itself is SOFA's RigidSphereModel, whose contacts
    # keep it a second radius away.
    centre = ball.addChild("collision")
    centre.addObject("MechanicalObject", name="centre", position=[0, 0, 0])
    centre.addObject("SphereCollisionModel", radius=BALL_RADIUS)
    centre.addObject("RigidMapping")
    points, triangles = sphere_surface(BALL_RADIUS)
    visual = ball.addChild("visual")
    visual.addObject("OglModel", position=points, triangles=triangles, color=[0.9, 0.5, 0.1, 1])
    visual.addObject("RigidMapping")
    floor = root.addChild("floor")
    # (MinProximityIntersection takes a sphere over a triangle's inside only: the diagonal stays off the ball.)
    floor.addObject("MeshTopology", position=[[-0.2, 0, -0.2], [0.25, 0, -0.2], [0.25, 0, 0.2], [-0.2, 0, 0.2]],
                    triangles=[[0, 2, 1], [0, 3, 2]])
    floor.addObject("MechanicalObject")
    floor.addObject("TriangleCollisionModel", simulated=False, moving=False)
    # The command in pressure mode is the impulse over a step, SOFA's λ = pressure × dt.
    root.addObject(Grip(name="grip", cavities=cavities, fingers=fingers, target=PRESSURE * root.dt.value))
    return root


def main():
    root = Sofa.Core.Node("root")
    createScene(root)
    Sofa.Simulation.init(root)
    for step in range(1, INFLATE_STEPS + HOLD_STEPS + LIFT_STEPS + 41):
        Sofa.Simulation.animate(root, root.dt.value)
        if step % 20 == 0:
            height = root.ball.dofs.position.value[0][1]
            print(f"step {step}: ball centre {height * 1000:.1f} mm above the floor, "
                  f"volume growth {root.finger0.cavity.pressure.volumeGrowth.value * 1e6:.2f} cm³")


if __name__ == "__main__":
    main()
