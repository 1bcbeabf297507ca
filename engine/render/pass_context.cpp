#include "engine/render/pass_context.hpp"

#include <memory>

namespace bounce::render {

VkImageView PassContext::frameView(gpu::Image& image, VkImageViewType type, std::uint32_t baseLayer,
                                   std::uint32_t layers) const {
  auto view = std::make_shared<gpu::ImageView>(image.createView(type, 0, 1, baseLayer, layers, image.name() + ".view"));
  VkImageView handle = view->handle();
  frames->deferDelete([view]() mutable { view->reset(); });
  return handle;
}

}  // namespace bounce::render
