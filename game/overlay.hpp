#pragma once
// The play overlay: a Dear ImGui panel (Debian libimgui-dev with its Vulkan backend) drawn onto
// the renderer's 8-bit display image after tonemapping, so it shows in the window and in a
// `--overlay on` screenshot but never touches the HDR image captures measure.
//
//   Overlay overlay(ctx, VK_FORMAT_R8G8B8A8_UNORM, framesInFlight);
//   OverlayPresenter presenter(swapchain, overlay);
//   each frame: overlay.build(info, extent);  session.render(presenter, settings);
//
// OverlayPresenter wraps the real presenter: the renderer hands it the display image once the
// graph has executed, it records the overlay (timestamp scope "overlay", so its GPU cost shows
// with the passes) and forwards the image. Given the window, the panel takes the mouse through
// ImGui's GLFW backend (its callbacks chain to play's): it can be moved, collapsed, and its
// exposure / debug-view controls and screenshot button used (build() returns what changed).
//
// Layout: build() lays the panel out twice per frame and draws only the second, so an
// auto-sized window and its table columns are measured before they are drawn — the first frame,
// and the first after the pass list changes, are right (ImGui otherwise sizes a frame late).
//
// ImGui 1.86's Vulkan backend draws inside a VkRenderPass (the engine otherwise uses dynamic
// rendering), so the overlay owns one: a single colour attachment, load and store, in
// COLOR_ATTACHMENT_OPTIMAL. Framebuffers are made per frame and deleted when the frame retires,
// which survives resizes without tracking the display image's identity.
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/gpu/context.hpp"
#include "engine/gpu/frames.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/presenter.hpp"
#include "engine/render/renderer.hpp"
#include "engine/scene/effects.hpp"
#include "game/play_controls.hpp"

struct GLFWwindow;

namespace bounce::game {

// What the panel shows; filled by `bounce play` each frame.
struct OverlayInfo {
  std::string title;                                   // the level's name
  double cpuFrameMs = 0.0;                             // median wall time per frame
  std::vector<std::pair<std::string, double>> passes;  // GPU ms per pass (medians)
  double gpuTotalMs = 0.0;
  std::size_t gpuWindow = 0;                           // frames the medians cover
  scene::EffectSet effects;                            // shown green: named AND running (Session::runningEffects)
  std::array<std::string, scene::kEffectCount> effectWhyOff;  // non-empty: the checkbox is disabled, this is its tooltip
  render::DebugView debugView = render::DebugView::None;
  float exposure = 1.0f;
  bool vsync = true, paused = false, culling = true, flying = false;
  VkExtent2D extent{0, 0};
  std::string vlm;  // vlmControlText(): the selected VLM tag and its overrides; empty: no VLM
  std::string vlmOverflow;  // gi::vlm::formatOverflow() when the VLM node runs, else empty
  std::string animation;    // animationText(): the selected character's clip and clip time; empty: none
  // Technique settings that change at run time (the panel's "techniques" section), each shown
  // only while its technique runs. THE HOOK for the next ones: SL and RTF (issues 13, 14) add
  // their fields here, their edits to OverlayActions and their block to layoutTechniques() in
  // overlay.cpp once their runtimes have settings; until then they show nothing.
  bool dnrtRuns = false;        // the DNRT node runs (Session::runs(dnrt))
  int dnrtMode = 0;             // PlayState::dnrtMode: 0 each object's own, 1 full-screen, 2 clustered
  VlmControl vlmControl;        // tags (empty: no VLM runs) and live overrides, as the T ]/[ H keys
};

// What the user changed in the panel this frame (empty optionals: nothing).
struct OverlayActions {
  std::optional<float> exposure;
  std::optional<render::DebugView> debugView;
  bool screenshot = false;   // the panel's screenshot button (as F12)
  std::optional<scene::Effect> toggleEffect;  // an effect checkbox was clicked (as its key 1-9)
  std::optional<int> dnrtMode;  // the DNRT mode chosen (as key M), OverlayInfo::dnrtMode's numbering
  std::optional<std::pair<int, scene::VlmOverride>> vlmOverride;  // a tag's override edited (setVlmOverride)
  bool wantsMouse = false;   // the mouse is over the panel: play must not orbit or look with it
};

// Frame-time graph length (frames) and its fixed scale: 0..kGraphMaxMs.
inline constexpr std::size_t kFrameGraphLength = 120;
inline constexpr float kGraphMaxMs = 100.0f;

class Overlay {
 public:
  // `targetFormat`: the format of the image record() draws on (the renderer's display image).
  // `window`: the GLFW window whose mouse the panel reads (null: a panel without input).
  Overlay(gpu::Context& ctx, VkFormat targetFormat, std::uint32_t framesInFlight, GLFWwindow* window = nullptr);
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;

  // Lays out this frame's panel for a target of `extent` pixels. Call once per frame, before
  // the frame is rendered; record() draws what the last build() laid out, once.
  OverlayActions build(const OverlayInfo& info, double dtSeconds);
  // Records the panel onto `target` (mip 0; COLOR_ATTACHMENT usage) in the current frame of
  // `frames`. Leaves `target` in COLOR_ATTACHMENT_OPTIMAL (its tracked layout says so).
  void record(gpu::FrameRing& frames, gpu::Image& target);

 private:
  gpu::Context& ctx_;
  VkFormat format_;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
  GLFWwindow* window_ = nullptr;
  bool built_ = false;
  std::vector<float> frameMs_;  // CPU frame times, oldest first, at most kFrameGraphLength
};

// A presenter that draws the overlay onto the finished image, then hands it to `inner`.
class OverlayPresenter : public gpu::Presenter {
 public:
  explicit OverlayPresenter(gpu::Presenter& inner) : inner_(inner) {}
  // nullptr (or never set) draws nothing: screenshots without the overlay.
  void setOverlay(Overlay* overlay) { overlay_ = overlay; }
  VkExtent2D extent() const override { return inner_.extent(); }
  bool present(gpu::FrameRing& frames, gpu::Image& source) override;

 private:
  gpu::Presenter& inner_;
  Overlay* overlay_ = nullptr;
};

}  // namespace bounce::game
