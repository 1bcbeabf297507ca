#include "game/overlay.hpp"

#include <imgui.h>
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

void layoutPanel(const OverlayInfo& info) {
  ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f));
  ImGui::SetNextWindowBgAlpha(0.65f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
  ImGui::Begin("bounce", nullptr, flags);
  ImGui::TextUnformatted(info.title.c_str());
  const double fps = info.cpuFrameMs > 0.0 ? 1000.0 / info.cpuFrameMs : 0.0;
  ImGui::Text("frame %.2f ms (%.0f fps)  %ux%u", info.cpuFrameMs, fps, info.extent.width, info.extent.height);
  ImGui::Separator();
  ImGui::Text("GPU ms, median of %zu frames", info.gpuWindow);
  if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_SizingFixedFit)) {
    for (const auto& [name, ms] : info.passes) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
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
  if (!info.vlmOverflow.empty()) ImGui::TextUnformatted(info.vlmOverflow.c_str());
  ImGui::Separator();
  ImGui::TextUnformatted("effects (keys 1-9)");
  for (int i = 0; i < scene::kEffectCount; ++i) {
    const auto e = scene::Effect(i);
    const std::string_view name = scene::effectName(e);
    char label[32];
    std::snprintf(label, sizeof label, "%d %.*s", i + 1, int(name.size()), name.data());
    if (i % 3) ImGui::SameLine(float(i % 3) * 90.0f + 8.0f);
    onOff(label, info.effects.has(e));
  }
  ImGui::Separator();
  ImGui::Text("view %s (F1-F6)", render::debugViewName(info.debugView));
  ImGui::Text("exposure %.3f (%+.2f EV)", info.exposure, std::log2(info.exposure));
  onOff(info.vsync ? "vsync on" : "vsync off", info.vsync);
  ImGui::SameLine();
  onOff(info.culling ? "culling on" : "culling off", info.culling);
  if (info.paused) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "PAUSED");
  }
  ImGui::TextDisabled(info.flying ? "flying (R resets the camera)" : "WASD/QE move, right mouse looks");
  if (!info.vlm.empty()) ImGui::TextUnformatted(info.vlm.c_str());  // per-tag VLM overrides (T, ]/[, H)
  if (!info.animation.empty()) ImGui::TextUnformatted(info.animation.c_str());  // clip and time (L, K)
  ImGui::End();
}

}  // namespace

Overlay::Overlay(gpu::Context& ctx, VkFormat targetFormat, std::uint32_t framesInFlight)
    : ctx_(ctx), format_(targetFormat) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing written next to the user's files
  io.LogFilename = nullptr;
  io.ConfigFlags |= ImGuiConfigFlags_NoMouse | ImGuiConfigFlags_NoMouseCursorChange;
  ImGui::StyleColorsDark();

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
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(ctx_.device(), descriptorPool_, nullptr);
  vkDestroyRenderPass(ctx_.device(), renderPass_, nullptr);
}

void Overlay::build(const OverlayInfo& info, double dtSeconds) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(info.extent.width), float(info.extent.height));
  io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
  io.DeltaTime = dtSeconds > 0.0 ? float(dtSeconds) : 1.0f / 60.0f;  // ImGui asserts on 0
  ImGui_ImplVulkan_NewFrame();
  ImGui::NewFrame();
  layoutPanel(info);
  ImGui::Render();
  built_ = true;
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
