"""SofaImGui: SofaPython3 scripts import it to pick the ImGui viewer; with fastcorot,
Sofa.Gui.GUIManager opens fastcorot's own viewer (`fastcorot view`), whatever the GUI name."""
