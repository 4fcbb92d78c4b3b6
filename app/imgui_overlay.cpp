#include "app/imgui_overlay.h"

#include <atomic>
#include <cfloat>
#include <cstdint>
#include <filesystem>

#include <imgui.h>

namespace vegstream::app {
namespace {
constexpr const char* kMonoFont = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf";

uint64_t nextAtlasId() {
  static std::atomic<uint64_t> id{1};
  return id++;
}
}  // namespace

ImGuiOverlay::ImGuiOverlay() {
  ImGuiContext* previous = ImGui::GetCurrentContext();
  context_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 0.72f;
  ImGui::GetStyle().Colors[ImGuiCol_TextDisabled] = ImVec4(0.72f, 0.74f, 0.78f, 1.0f);  // notes, readable over terrain

  // DejaVu Sans Mono (Debian's fonts-dejavu-core) when installed: aligned columns and the em
  // dash the HUD prints for absent counts; ImGui's built-in font otherwise (drawHud adapts).
  static const ImWchar kRanges[] = {0x0020, 0x00FF, 0x2014, 0x2014, 0};
  if (std::filesystem::exists(kMonoFont)) {
    ImFontConfig config;
    config.OversampleH = 1;
    if (!io.Fonts->AddFontFromFileTTF(kMonoFont, 13.0f, &config, kRanges)) io.Fonts->AddFontDefault();
  } else {
    io.Fonts->AddFontDefault();
  }
  unsigned char* pixels = nullptr;
  int w = 0, h = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  auto atlas = std::make_shared<render::OverlayImage>();
  atlas->id = nextAtlasId();
  atlas->width = static_cast<uint32_t>(w);
  atlas->height = static_cast<uint32_t>(h);
  atlas->rgba.assign(pixels, pixels + static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
  // One texture: the renderer binds it for every command, so the id only has to be non-null.
  io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(1)));
  atlas_ = std::move(atlas);
  ImGui::SetCurrentContext(previous);
}

ImGuiOverlay::~ImGuiOverlay() { ImGui::DestroyContext(context_); }

void ImGuiOverlay::begin(float width, float height, double dtS, const OverlayPointer& pointer) {
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(width, height);
  io.DeltaTime = dtS > 1e-6 ? static_cast<float>(dtS) : 1e-3f;
  // ImGui 1.86 (Debian's) reads the mouse state from io each frame; -FLT_MAX is its "no mouse".
  io.MousePos = pointer.present ? ImVec2(pointer.x, pointer.y) : ImVec2(-FLT_MAX, -FLT_MAX);
  io.MouseDown[0] = pointer.present && pointer.leftDown;
  ImGui::NewFrame();
}

const render::OverlayDrawData& ImGuiOverlay::end() {
  ImGui::SetCurrentContext(context_);
  ImGui::Render();
  const ImDrawData* dd = ImGui::GetDrawData();
  data_.width = dd->DisplaySize.x;
  data_.height = dd->DisplaySize.y;
  data_.vertices.clear();
  data_.indices.clear();
  data_.commands.clear();
  data_.texture = atlas_;
  for (int l = 0; l < dd->CmdListsCount; ++l) {
    const ImDrawList* list = dd->CmdLists[l];
    const auto vertexBase = static_cast<uint32_t>(data_.vertices.size());
    const auto indexBase = static_cast<uint32_t>(data_.indices.size());
    for (const ImDrawVert& v : list->VtxBuffer) data_.vertices.push_back({v.pos.x, v.pos.y, v.uv.x, v.uv.y, v.col});
    for (const ImDrawIdx idx : list->IdxBuffer) data_.indices.push_back(idx);
    for (const ImDrawCmd& c : list->CmdBuffer) {
      if (c.UserCallback != nullptr || c.ElemCount == 0) continue;  // the HUD uses no callbacks
      render::OverlayCommand oc;
      oc.firstIndex = indexBase + c.IdxOffset;
      oc.indexCount = c.ElemCount;
      oc.vertexOffset = static_cast<int32_t>(vertexBase + c.VtxOffset);
      oc.clipX0 = c.ClipRect.x - dd->DisplayPos.x;
      oc.clipY0 = c.ClipRect.y - dd->DisplayPos.y;
      oc.clipX1 = c.ClipRect.z - dd->DisplayPos.x;
      oc.clipY1 = c.ClipRect.w - dd->DisplayPos.y;
      data_.commands.push_back(oc);
    }
  }
  return data_;
}

}  // namespace vegstream::app
