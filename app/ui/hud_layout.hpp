#pragma once
// HUD panels docked at the window's edges: each panel is stacked in its corner (below or above
// the panels docked there before it in the frame), so the layout follows the window size and a
// panel that grows or collapses moves its neighbours. Dragging a panel by its title undocks it
// (it stays where dropped); "dock panels" in the Settings panel docks them all again. Which
// panels are undocked is saved with ImGui's own settings (`[VTouchingPanel][NAME]` entries in
// the ini file, when the ImGuiLayer has one). Main thread only, inside an ImGui frame; the
// state belongs to the one ImGui context of the process.

namespace vt::ui {

/// The corner a docked panel stacks in.
enum class DockCorner { TopLeft, TopRight, BottomRight };

/// Registers the ini entries on the current ImGui context (once per context; later calls do
/// nothing). Call before the context's first frame so saved entries are read.
void installHudLayout();
/// Call right before ImGui::Begin(name): places a docked panel at its slot in `corner` and,
/// the first time the panel appears with no saved state, collapses it when `collapsed`.
void dockNextPanel(const char* name, DockCorner corner, bool collapsed = false);
/// Call right after ImGui::Begin of a panel placed by dockNextPanel: reserves its height.
void endDockedPanel();
/// Docks every panel again at its corner.
void dockAllPanels();
/// The current font size over ImGui's default 13 px (renderer::textScaleForHeight: the text
/// grows with the window): what the HUD multiplies its sizes laid out at 13 px by.
float hudScale();

}  // namespace vt::ui
