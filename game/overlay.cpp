#include "game/overlay.hpp"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/timestamps.hpp"

namespace bounce::game {

namespace {

void checkImgui(VkResult r) { gpu::check(r, "imgui vulkan backend"); }

VkRenderPass makeRenderPass(gpu::Context& ctx, VkFormat format) {
  // Draws over what tonemapping (or a debug view) left: load, store, no layout change. The
  // caller transitions the image into COLOR_ATTACHMENT_OPTIMAL with a full barrier first, and the
  // presenter transitions it out, so the implicit external dependencies suffice.
  VkAttachmentDescription color{};
  color.format = format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  VkRenderPass pass = VK_NULL_HANDLE;
  gpu::check(vkCreateRenderPass(ctx.device(), &info, nullptr, &pass), "vkCreateRenderPass (overlay)");
  ctx.setName(VK_OBJECT_TYPE_RENDER_PASS, pass, "overlay");
  return pass;
}

// A coloured row of the panel: green for what is on, grey for what is off.
void onOff(const char* label, bool on) {
  if (on)
    ImGui::TextColored(ImVec4(0.45f, 0.95f, 0.45f, 1.0f), "%s", label);
  else
    ImGui::TextDisabled("%s", label);
}

// Run-time technique settings (OverlayInfo's hook): DNRT's mode and VLM's per-tag overrides
// (§3.5, thesis Fig. 5.5: intensity in stops, hue rotation, colour). SL and RTF add their block
// here when they land (see OverlayInfo). `vlm` is the caller's copy, edited in place so the
// second layout of the frame shows the change.
void layoutTechniques(const OverlayInfo& info, int& dnrtMode, VlmControl& vlm, OverlayActions& actions) {
  if (!info.dnrtRuns && vlm.tags.empty()) return;
  if (!ImGui::CollapsingHeader("techniques", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (info.dnrtRuns) {
    int mode = dnrtMode;
    const char* modes[] = {"each object's own", "full-screen (paper)", "clustered"};
    ImGui::SetNextItemWidth(150.0f);
    if (ImGui::Combo("dnrt mode (M)", &mode, modes, IM_ARRAYSIZE(modes)) && mode != dnrtMode) {
      dnrtMode = mode;
      actions.dnrtMode = dnrtMode;
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("own: each object's outer cube is drawn (or its level \"mode\");\n"
                        "full-screen: the paper's pass per object, for comparison (same image, more cost);\n"
                        "clustered: one pass, each pixel visits the objects over its tile (same image)");
  }
  for (const std::uint32_t tag : vlm.tags) {
    scene::VlmOverride o;
    if (auto it = vlm.overrides.find(int(tag)); it != vlm.overrides.end()) o = it->second;
    ImGui::PushID(int(tag));
    ImGui::Text("vlm tag %u", tag);
    ImGui::SameLine();
    float ev = std::log2(o.intensity);
    bool changed = false;
    ImGui::SetNextItemWidth(90.0f);
    if (ImGui::SliderFloat("EV", &ev, std::log2(kVlmIntensityMin), std::log2(kVlmIntensityMax), "%+.1f"))
      o.intensity = std::exp2(ev), changed = true;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(70.0f);
    changed |= ImGui::SliderFloat("hue", &o.hueDeg, 0.0f, 360.0f, "%.0f");
    ImGui::SameLine();
    changed |= ImGui::ColorEdit3("colour", &o.color.x, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel);
    if (changed && setVlmOverride(vlm, int(tag), o)) actions.vlmOverride = std::pair{int(tag), vlm.overrides[int(tag)]};
    ImGui::PopID();
  }
}

// The panel's controls write into `actions`; `exposure` and `view` are the values shown (the
// caller's, updated by this frame's first layout so the second shows the change).
void layoutPanel(const OverlayInfo& info, const std::vector<float>& frameMs, float& exposure,
                 render::DebugView& view, int& dnrtMode, VlmControl& vlm, OverlayActions& actions) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
  // Never taller than the window: the rest scrolls (640x360 shows the header and the first rows).
  ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(std::max(display.x - 16.0f, 64.0f),
                                                                  std::max(display.y - 16.0f, 64.0f)));
  ImGui::SetNextWindowBgAlpha(0.65f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  const std::string title = info.title + "###bounce";  // the id stays when the title changes
  if (!ImGui::Begin(title.c_str(), nullptr, flags)) {  // collapsed: only the title bar
    ImGui::End();
    return;
  }
  const double fps = info.cpuFrameMs > 0.0 ? 1000.0 / info.cpuFrameMs : 0.0;
  ImGui::Text("frame %.2f ms (%.0f fps)  %ux%u", info.cpuFrameMs, fps, info.extent.width, info.extent.height);
  if (!frameMs.empty())
    ImGui::PlotLines("##frame", frameMs.data(), int(frameMs.size()), 0, "CPU frame ms (0-100)", 0.0f, kGraphMaxMs,
                     ImVec2(260.0f, 36.0f));
  if (ImGui::CollapsingHeader("GPU ms", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (info.gpuWindow == 0) {
      ImGui::TextDisabled("first timings arrive in a frame or two");
    } else {
      ImGui::TextDisabled("median of %zu frame%s", info.gpuWindow, info.gpuWindow == 1 ? "" : "s");
      if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_SizingFixedFit)) {
        for (const auto& [name, ms] : info.passes) {
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          // Per-object rows ("dnrt/<entity>", "vlm/<entity>") indented under their pass.
          if (const auto slash = name.find('/'); slash != std::string::npos)
            ImGui::TextDisabled("  %s", name.substr(slash + 1).c_str());
          else
            ImGui::TextUnformatted(name.c_str());
          ImGui::TableNextColumn();
          ImGui::Text("%7.2f", ms);
        }
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted("total");
        ImGui::TableNextColumn();
        ImGui::Text("%7.2f", info.gpuTotalMs);
        ImGui::EndTable();
      }
    }
    if (!info.vlmOverflow.empty()) ImGui::TextUnformatted(info.vlmOverflow.c_str());
  }
  if (ImGui::CollapsingHeader("effects (keys 1-9)", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (int i = 0; i < scene::kEffectCount; ++i) {
      const auto e = scene::Effect(i);
      const std::string_view name = scene::effectName(e);
      char label[32];
      std::snprintf(label, sizeof label, "%d %.*s", i + 1, int(name.size()), name.data());
      if (i % 3) ImGui::SameLine(float(i % 3) * 90.0f + 8.0f);
      // A checkbox per effect, as its key; disabled (with the table's note as tooltip) when the
      // level cannot build that effect, so nothing turns on that will not run.
      bool on = info.effects.has(e);
      const std::string& why = info.effectWhyOff[std::size_t(i)];
      if (!why.empty()) ImGui::BeginDisabled();
      if (ImGui::Checkbox(label, &on)) actions.toggleEffect = e;
      if (!why.empty()) {
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", why.c_str());
      }
    }
  }
  if (ImGui::CollapsingHeader("view", ImGuiTreeNodeFlags_DefaultOpen)) {
    int v = int(view);
    const char* names[int(render::DebugView::EntityId) + 1];
    for (int i = 0; i <= int(render::DebugView::EntityId); ++i) names[i] = render::debugViewName(render::DebugView(i));
    ImGui::SetNextItemWidth(120.0f);
    if (ImGui::Combo("view (F1-F6)", &v, names, IM_ARRAYSIZE(names))) view = render::DebugView(v), actions.debugView = view;
    float ev = std::log2(exposure);
    ImGui::SetNextItemWidth(120.0f);
    if (ImGui::SliderFloat("exposure EV (+/-)", &ev, -10.0f, 10.0f, "%+.2f"))
      exposure = std::exp2(ev), actions.exposure = exposure;
    onOff(info.vsync ? "vsync on" : "vsync off", info.vsync);
    ImGui::SameLine();
    onOff(info.culling ? "culling on" : "culling off", info.culling);
    if (info.paused) {
      ImGui::SameLine();
      ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "PAUSED");
    }
    if (ImGui::Button("screenshot (F12)")) actions.screenshot = true;
    ImGui::TextDisabled(info.flying ? "flying (R resets the camera)" : "WASD/QE move, right mouse looks, left drags orbit");
    if (!info.vlm.empty()) ImGui::TextUnformatted(info.vlm.c_str());  // per-tag VLM overrides (T, ]/[, H)
    if (!info.animation.empty()) ImGui::TextUnformatted(info.animation.c_str());  // clip and time (L, K)
  }
  layoutTechniques(info, dnrtMode, vlm, actions);
  ImGui::End();
}

}  // namespace

Overlay::Overlay(gpu::Context& ctx, VkFormat targetFormat, std::uint32_t framesInFlight, GLFWwindow* window)
    : ctx_(ctx), format_(targetFormat), window_(window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing written next to the user's files
  io.LogFilename = nullptr;
  if (!window_) io.ConfigFlags |= ImGuiConfigFlags_NoMouse;
  io.ConfigFlags |= ImGuiConfigFlags_NoMouseCursorChange;  // keyboard navigation stays off: keys are play's
  ImGui::StyleColorsDark();
  // The mouse through GLFW; install_callbacks chains the callbacks play set (keys, wheel).
  if (window_ && !ImGui_ImplGlfw_InitForVulkan(window_, true)) throw InternalError("overlay: ImGui_ImplGlfw_InitForVulkan failed");

  renderPass_ = makeRenderPass(ctx, format_);
  // The backend allocates one set: the font texture's combined image sampler.
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pi.maxSets = 1;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  gpu::check(vkCreateDescriptorPool(ctx.device(), &pi, nullptr, &descriptorPool_), "vkCreateDescriptorPool (overlay)");

  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = ctx.instance();
  init.PhysicalDevice = ctx.physicalDevice();
  init.Device = ctx.device();
  init.QueueFamily = ctx.queueFamily();
  init.Queue = ctx.queue();
  init.DescriptorPool = descriptorPool_;
  init.Subpass = 0;
  // The backend cycles ImageCount vertex/index buffers, one per RenderDrawData call. record()
  // calls it at most once per frame, so a buffer comes back only after framesInFlight frames,
  // by which time FrameRing::begin() has waited on the frame that used it.
  init.MinImageCount = 2;
  init.ImageCount = std::max<std::uint32_t>(2, framesInFlight);
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = checkImgui;
  if (!ImGui_ImplVulkan_Init(&init, renderPass_)) throw InternalError("overlay: ImGui_ImplVulkan_Init failed");
  gpu::submitAndWait(ctx, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

Overlay::~Overlay() {
  ctx_.waitIdle();  // the last frames may still read the backend's buffers
  ImGui_ImplVulkan_Shutdown();
  if (window_) ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(ctx_.device(), descriptorPool_, nullptr);
  vkDestroyRenderPass(ctx_.device(), renderPass_, nullptr);
}

OverlayActions Overlay::build(const OverlayInfo& info, double dtSeconds) {
  if (dtSeconds > 0.0) {
    frameMs_.push_back(float(dtSeconds * 1000.0));
    if (frameMs_.size() > kFrameGraphLength) frameMs_.erase(frameMs_.begin());
  }
  OverlayActions actions;
  float exposure = info.exposure;
  render::DebugView view = info.debugView;
  int dnrtMode = info.dnrtMode;
  VlmControl vlm = info.vlmControl;
  // Twice: the first layout measures (auto-size, table columns), the second is drawn.
  for (int pass = 0; pass < 2; ++pass) {
    if (window_) ImGui_ImplGlfw_NewFrame();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(info.extent.width), float(info.extent.height));
    io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
    io.DeltaTime = pass == 0 && dtSeconds > 0.0 ? float(dtSeconds) : 1e-4f;  // ImGui asserts on 0
    ImGui_ImplVulkan_NewFrame();
    ImGui::NewFrame();
    layoutPanel(info, frameMs_, exposure, view, dnrtMode, vlm, actions);
    actions.wantsMouse = actions.wantsMouse || io.WantCaptureMouse;
    if (pass == 0) ImGui::EndFrame();
  }
  ImGui::Render();
  built_ = true;
  return actions;
}

void Overlay::record(gpu::FrameRing& frames, gpu::Image& target) {
  if (!built_) return;
  built_ = false;
  if (target.format() != format_)
    throw InternalError("overlay: target format differs from the one the overlay pipeline was built for");
  ImDrawData* draw = ImGui::GetDrawData();
  if (!draw || draw->DisplaySize.x != float(target.desc().width) || draw->DisplaySize.y != float(target.desc().height))
    return;  // laid out for another size (the frame a resize happens): skip one frame
  gpu::Frame& frame = frames.current();
  VkCommandBuffer cmd = frame.cmd;
  gpu::GpuScope scope(ctx_, *frame.timestamps, cmd, "overlay");
  gpu::transition(cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);

  VkImageView view = target.view();
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fi.renderPass = renderPass_;
  fi.attachmentCount = 1;
  fi.pAttachments = &view;
  fi.width = target.desc().width;
  fi.height = target.desc().height;
  fi.layers = 1;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  gpu::check(vkCreateFramebuffer(ctx_.device(), &fi, nullptr, &framebuffer), "vkCreateFramebuffer (overlay)");
  frames.deferDelete([device = ctx_.device(), framebuffer] { vkDestroyFramebuffer(device, framebuffer, nullptr); });

  VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  bi.renderPass = renderPass_;
  bi.framebuffer = framebuffer;
  bi.renderArea = {{0, 0}, {fi.width, fi.height}};
  vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(draw, cmd);
  vkCmdEndRenderPass(cmd);
  target.setLayout(VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
}

bool OverlayPresenter::present(gpu::FrameRing& frames, gpu::Image& source) {
  if (overlay_) overlay_->record(frames, source);
  return inner_.present(frames, source);
}

}  // namespace bounce::game
