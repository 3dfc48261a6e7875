#include "app/viewer/imgui_overlay.h"

#include <cstring>

namespace app::ui {

void BuildFontAtlas(render::Image* atlas) {
  ImGuiIO& io = ImGui::GetIO();
  unsigned char* pixels = nullptr;
  int w = 0, h = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  *atlas = render::Image(w, h);
  std::memcpy(atlas->rgba.data(), pixels, static_cast<size_t>(w) * h * 4);
  io.Fonts->SetTexID(static_cast<ImTextureID>(atlas));
}

void ToOverlay(const ImDrawData& draw_data, const render::Image* atlas, render::Overlay* overlay) {
  overlay->vertices.clear();
  overlay->indices.clear();
  overlay->commands.clear();
  overlay->texture = atlas;
  overlay->texture_revision = 1;
  const ImVec2 origin = draw_data.DisplayPos;
  const ImVec2 scale = draw_data.FramebufferScale;
  for (int n = 0; n < draw_data.CmdListsCount; ++n) {
    const ImDrawList* list = draw_data.CmdLists[n];
    const auto vertex_base = static_cast<std::uint32_t>(overlay->vertices.size());
    const auto index_base = static_cast<std::uint32_t>(overlay->indices.size());
    for (const ImDrawVert& v : list->VtxBuffer) {
      overlay->vertices.push_back(
          {(v.pos.x - origin.x) * scale.x, (v.pos.y - origin.y) * scale.y, v.uv.x, v.uv.y, v.col});
    }
    for (const ImDrawIdx i : list->IdxBuffer) overlay->indices.push_back(i);
    for (const ImDrawCmd& c : list->CmdBuffer) {
      if (c.UserCallback != nullptr) continue;  // no custom callbacks are used
      overlay->commands.push_back(
          {index_base + c.IdxOffset, c.ElemCount, vertex_base + c.VtxOffset,
           (c.ClipRect.x - origin.x) * scale.x, (c.ClipRect.y - origin.y) * scale.y,
           (c.ClipRect.z - origin.x) * scale.x, (c.ClipRect.w - origin.y) * scale.y});
    }
  }
}

}  // namespace app::ui
