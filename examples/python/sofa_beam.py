"""The cantilever beam of examples/cantilever_beam_40x10x10.scn written for SofaPython3, unchanged
for fastcorot: `fastcorot run examples/python/sofa_beam.py` (or `view`) calls createScene(root);
`PYTHONPATH=build/python python3 examples/python/sofa_beam.py` runs main(), which steps it with a
controller printing the tip's height. It gives bit for bit the trajectory of the .scn file."""

import Sofa
import Sofa.Simulation


class TipReporter(Sofa.Core.Controller):
    """Prints the lowest point of the free end every 50 steps."""

    def __init__(self, *args, **kwargs):
        Sofa.Core.Controller.__init__(self, *args, **kwargs)
        self.state = kwargs.get("state")
        self.steps = 0

    def onAnimateEndEvent(self, event):
        self.steps += 1
        if self.steps % 50 == 0:
            x = self.state.position.array()
            tip = x[x[:, 0] > 15.9]
            print(f"t = {self.getContext().time.value:.2f}: tip at y = {tip[:, 1].min():.4f}")


def createScene(root):
    root.dt = 0.01
    root.gravity = [0, -9, 0]
    root.addObject("RequiredPlugin", pluginName="Sofa.Component.SolidMechanics.FEM.Elastic")
    root.addObject("DefaultAnimationLoop")
    beam = root.addChild("beam")
    beam.addObject("EulerImplicitSolver", rayleighStiffness=0.1, rayleighMass=0.1)
    beam.addObject("CGLinearSolver", iterations=20, tolerance=1e-6, threshold=1e-6)
    beam.addObject("RegularGridTopology", name="grid", n=[40, 10, 10], min=[0, 6, -2], max=[16, 10, 2])
    state = beam.addObject("MechanicalObject", name="state", template="Vec3d")
    beam.addObject("TetrahedronSetTopologyContainer", name="tetrahedra")
    beam.addObject("Hexa2TetraTopologicalMapping", input="@grid", output="@tetrahedra", swapping=True)
    beam.addObject("DiagonalMass", totalMass=50)
    beam.addObject("FastTetrahedralCorotationalForceField", name="FEM", youngModulus=2000, poissonRatio=0.3,
                   method="large")
    beam.addObject("BoxROI", name="clamp", box=[-0.1, 5, -3, 0.1, 11, 3])
    beam.addObject("FixedProjectiveConstraint", indices="@clamp.indices")
    beam.addObject(TipReporter(name="tip", state=state))
    return root


def main():
    root = Sofa.Core.Node("root")
    createScene(root)
    Sofa.Simulation.init(root)
    for _ in range(100):
        Sofa.Simulation.animate(root, root.dt.value)


if __name__ == "__main__":
    main()
