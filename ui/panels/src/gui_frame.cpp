#include "partreg/ui/gui_frame.hpp"

#include <imgui.h>

#include <cfloat>
#include <cstdint>

#include "partreg/render/overlay.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/scene_builder.hpp"

namespace partreg::ui {
namespace {

// ImGui's draw data as the overlay renderer's plain lists (ImDrawVert has the same layout).
std::vector<render::OverlayList> overlay_lists(const ImDrawData& data) {
  static_assert(sizeof(ImDrawVert) == sizeof(render::OverlayVertex), "ImDrawVert layout");
  std::vector<render::OverlayList> lists;
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& source = *data.CmdLists[n];
    render::OverlayList list;
    list.vertices.resize(static_cast<std::size_t>(source.VtxBuffer.Size));
    for (int v = 0; v < source.VtxBuffer.Size; ++v) {
      const ImDrawVert& in = source.VtxBuffer[v];
      list.vertices[static_cast<std::size_t>(v)] = {in.pos.x - data.DisplayPos.x,
                                                    in.pos.y - data.DisplayPos.y, in.uv.x, in.uv.y, in.col};
    }
    list.indices.assign(source.IdxBuffer.begin(), source.IdxBuffer.end());
    for (const ImDrawCmd& command : source.CmdBuffer) {
      if (command.UserCallback) continue;  // the panels use none
      render::OverlayDraw draw;
      draw.texture = static_cast<unsigned>(reinterpret_cast<std::uintptr_t>(command.TextureId));
      draw.clip = {command.ClipRect.x - data.DisplayPos.x, command.ClipRect.y - data.DisplayPos.y,
                   command.ClipRect.z - data.DisplayPos.x, command.ClipRect.w - data.DisplayPos.y};
      draw.first_index = command.IdxOffset;
      draw.index_count = command.ElemCount;
      draw.vertex_offset = command.VtxOffset;
      list.draws.push_back(draw);
    }
    lists.push_back(std::move(list));
  }
  return lists;
}

}  // namespace

struct GuiFrame::Impl {
  std::unique_ptr<render::Renderer> renderer;
  std::unique_ptr<render::OverlayRenderer> overlay;
  ImGuiContext* imgui = nullptr;
  bool animating = false;
};

GuiFrame::GuiFrame(const Viewport& viewport, render::Antialiasing antialiasing)
    : impl_(std::make_unique<Impl>()) {
  render::RenderSettings settings;
  settings.width = viewport.width;
  settings.height = viewport.height;
  settings.antialiasing = antialiasing;
  impl_->renderer = std::make_unique<render::Renderer>(settings);
  impl_->overlay = std::make_unique<render::OverlayRenderer>();
  impl_->imgui = ImGui::CreateContext();
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // layouts come from code, never from a file next to the executable
  io.BackendRendererName = "partreg_render";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;
  ImGui::StyleColorsLight();
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  const unsigned texture = impl_->overlay->create_texture(pixels, width, height);
  io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(texture)));
}

GuiFrame::~GuiFrame() { ImGui::DestroyContext(impl_->imgui); }

void GuiFrame::draw(AppState& state, double seconds, std::vector<Command>& emitted,
                    render::FrameQuality quality) {
  ImGui::SetCurrentContext(impl_->imgui);
  advance_animation(state, seconds);
  const Viewport& viewport = state.viewport;
  if (viewport.width != width() || viewport.height != height())
    impl_->renderer->resize(viewport.width, viewport.height);
  impl_->renderer->draw(build_scene(state), render_camera(state), quality);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(viewport.width), static_cast<float>(viewport.height));
  io.DeltaTime = static_cast<float>(seconds > 0.0 ? seconds : 1.0 / 60.0);
  ImGui::NewFrame();
  if (state.show_panels) draw_panels(state, panel_, emitted);
  ImGui::Render();
  impl_->animating = ImGui::IsAnyItemActive() || state.shapes.animated_space >= 0;
  impl_->overlay->draw(framebuffer(), width(), height(), overlay_lists(*ImGui::GetDrawData()));
}

render::Image GuiFrame::read_pixels() const { return impl_->renderer->read_pixels(); }
unsigned GuiFrame::framebuffer() const { return impl_->renderer->resolved_framebuffer(); }
int GuiFrame::width() const { return impl_->renderer->settings().width; }
int GuiFrame::height() const { return impl_->renderer->settings().height; }
bool GuiFrame::animating() const { return impl_->animating; }
bool GuiFrame::wants_mouse() const {
  ImGui::SetCurrentContext(impl_->imgui);
  return ImGui::GetIO().WantCaptureMouse;
}

}  // namespace partreg::ui
