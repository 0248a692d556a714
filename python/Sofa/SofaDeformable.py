"""Sofa.SofaDeformable: SofaPython3 registers bindings of this family of components here; with fastcorot the
components are reached through their objects (see docs/python.md), so importing it is all it takes."""
