#include "engine/render/graph/backend.hpp"

namespace bounce::rg {

PhysicalId RecordingBackend::createTexture(const TextureDesc& desc, UsageSet usages, std::string_view name) {
  PhysicalId id = next_++;
  events.push_back("create texture " + std::to_string(id) + " " + std::string(name) + " " + describe(desc));
  createdUsages.push_back(usages);
  ++live;
  return id;
}

PhysicalId RecordingBackend::createBuffer(const BufferDesc& desc, UsageSet usages, std::string_view name) {
  PhysicalId id = next_++;
  events.push_back("create buffer " + std::to_string(id) + " " + std::string(name) + " " + describe(desc));
  createdUsages.push_back(usages);
  ++live;
  return id;
}

void RecordingBackend::destroyTexture(PhysicalId id) {
  events.push_back("destroy texture " + std::to_string(id));
  --live;
}

void RecordingBackend::destroyBuffer(PhysicalId id) {
  events.push_back("destroy buffer " + std::to_string(id));
  --live;
}

void RecordingBackend::barrier(CommandContext&, std::span<const Barrier> barriers) {
  events.push_back("barrier " + std::to_string(barriers.size()));
  barrierBatches.emplace_back(barriers.begin(), barriers.end());
}

void RecordingBackend::beginPass(CommandContext&, std::string_view name) {
  events.push_back("begin " + std::string(name));
}

void RecordingBackend::endPass(CommandContext&) { events.push_back("end"); }

}  // namespace bounce::rg
