#include "app/viewer_layout.hpp"

#include <algorithm>
#include <cmath>

namespace lp::app {

ViewerViewport viewerViewport(int framebufferWidth, int framebufferHeight, float windowWidth, bool panelShown,
                              float panelWidth) {
    ViewerViewport v;
    const int fbWidth = std::max(1, framebufferWidth);
    const float scale = windowWidth > 0.0f ? float(fbWidth) / windowWidth : 1.0f;
    const int panel = panelShown ? int(std::lround(std::max(0.0f, panelWidth) * scale)) : 0;
    v.x = std::clamp(panel, 0, fbWidth - 1);
    v.y = 0;
    v.width = fbWidth - v.x;
    v.height = std::max(1, framebufferHeight);
    return v;
}

bool insideViewport(const ViewerViewport& viewport, int framebufferWidth, int framebufferHeight, float windowWidth,
                    float windowHeight, double x, double y) {
    const double sx = windowWidth > 0.0f ? double(framebufferWidth) / windowWidth : 1.0;
    const double sy = windowHeight > 0.0f ? double(framebufferHeight) / windowHeight : 1.0;
    const double px = x * sx, py = y * sy;  // from the top left, as the cursor
    const double top = double(framebufferHeight) - double(viewport.y + viewport.height);
    return px >= viewport.x && px < viewport.x + viewport.width && py >= top && py < top + viewport.height;
}

}  // namespace lp::app
