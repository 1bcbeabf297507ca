#pragma once
// Small building blocks shared by the render-graph tests: descriptions, a swapchain-like import
// and passes that do nothing when executed (the tests look at what the graph decided).
#include <string>
#include <vector>

#include "engine/render/graph/render_graph.hpp"

namespace bounce::rg::test {

inline TextureDesc color(Format format = Format::RGBA16F) { return TextureDesc{64, 64, 1, 1, 1, format, false}; }
inline TextureDesc depth() { return TextureDesc{64, 64, 1, 1, 1, Format::D32F, false}; }

// An acquired swapchain image: no content, the acquire semaphore is waited on at colour output.
inline constexpr ResourceState kAcquired{Layout::Undefined, Stage::ColorAttachmentOutput, Access::None};
// A resource nobody touched recently (its last use was fenced): nothing to wait for.
inline constexpr ResourceState kIdle{Layout::Undefined, Stage::None, Access::None};

inline Handle<Texture> importBackbuffer(RenderGraph& g, PhysicalId physical = 100) {
  auto h = g.importTexture("backbuffer", color(Format::BGRA8_UNORM), kAcquired, physical);
  return h;
}

struct NoOp {
  template <typename Data>
  void operator()(const Data&, const PassResources&, CommandContext&) const {}
};

struct Tex {
  Handle<Texture> t;
};
struct Tex2 {
  Handle<Texture> a, b;
};
struct Buf {
  Handle<Buffer> b;
};

// A pass reading `inputs` (sampled in a fragment shader) and writing a new transient colour
// target `output` created with `desc`. Returns the written handle.
inline Handle<Texture> colorPass(RenderGraph& g, const std::string& name, std::vector<Handle<Texture>> inputs,
                                 const std::string& output, const TextureDesc& desc = color()) {
  return g.addPass<Tex>(
             name,
             [&](Builder& b, Tex& d) {
               for (auto in : inputs) b.read(in, Usage::SampledFragment);
               d.t = b.write(b.create<Texture>(output, desc), Usage::ColorAttachment);
             },
             NoOp{})
      .t;
}

// A pass reading `inputs` and writing `target` (e.g. the backbuffer). Returns the new version.
inline Handle<Texture> drawInto(RenderGraph& g, const std::string& name, std::vector<Handle<Texture>> inputs,
                                Handle<Texture> target) {
  return g.addPass<Tex>(
             name,
             [&](Builder& b, Tex& d) {
               for (auto in : inputs) b.read(in, Usage::SampledFragment);
               d.t = b.write(target, Usage::ColorAttachment);
             },
             NoOp{})
      .t;
}

// Whether `message` contains every one of `parts`.
inline bool mentions(const std::string& message, std::initializer_list<const char*> parts) {
  for (const char* p : parts)
    if (message.find(p) == std::string::npos) return false;
  return true;
}

}  // namespace bounce::rg::test
