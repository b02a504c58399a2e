#pragma once
// Where the viewer puts the image: beside the panel, which is docked at the window's left edge, in
// the rest of the window (all of it with the panel hidden). The camera's aspect is the viewport's.

namespace lp::app {

struct ViewerViewport {
    int x = 0, y = 0;           // lower-left corner in framebuffer pixels (GL's origin: bottom left)
    int width = 1, height = 1;  // the size the frame is rendered at
};

// `panelWidth` in window coordinates (ImGui's), converted with the framebuffer's scale to pixels; the
// image keeps at least one pixel whatever the panel's width.
ViewerViewport viewerViewport(int framebufferWidth, int framebufferHeight, float windowWidth, bool panelShown,
                              float panelWidth);

// Whether a point in window coordinates (origin top left, as GLFW's cursor) is on the image.
bool insideViewport(const ViewerViewport& viewport, int framebufferWidth, int framebufferHeight, float windowWidth,
                    float windowHeight, double x, double y);

}  // namespace lp::app
