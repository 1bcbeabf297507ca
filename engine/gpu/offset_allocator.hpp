#pragma once
// Offset allocation inside one memory block: pure arithmetic, no Vulkan, tested on its own.
//
// Best fit over a coalesced free list: an allocation takes the free range that leaves the least
// space after it (ties → lowest offset), which keeps large holes intact for large resources.
//
// bufferImageGranularity (Vulkan spec 12.7 "Resource Memory Association"): a linear resource
// (buffer, linear image) and a non-linear one (optimal-tiling image) must not share a
// "page" of `granularity` bytes. Invariant kept here: no two allocations of different kinds
// touch the same page. Checking only the two immediate neighbours is enough: anything further
// away that shares our page would share it with the neighbour too, which then has its kind.
#include <cstdint>
#include <map>
#include <optional>

namespace bounce::gpu {

class OffsetAllocator {
 public:
  enum class Kind : std::uint8_t { Linear, Optimal };

  // `granularity` is bufferImageGranularity (a power of two; 1 disables the rule).
  explicit OffsetAllocator(std::uint64_t capacity, std::uint64_t granularity = 1);

  // Offset of a new range of `size` bytes aligned to `alignment` (a power of two), or nullopt
  // when no free range fits. Throws InternalError for size 0 or a non-power-of-two alignment.
  std::optional<std::uint64_t> allocate(std::uint64_t size, std::uint64_t alignment, Kind kind = Kind::Linear);

  // Frees the allocation starting at `offset`; throws InternalError when there is none
  // (a double free or a foreign offset is a bug, not something to ignore).
  void free(std::uint64_t offset);

  std::uint64_t capacity() const { return capacity_; }
  std::uint64_t usedBytes() const { return used_bytes_; }
  std::uint64_t largestFreeRange() const;
  std::size_t freeRangeCount() const { return free_.size(); }
  std::size_t allocationCount() const { return used_.size(); }
  bool empty() const { return used_.empty(); }

 private:
  struct Used {
    std::uint64_t size;
    Kind kind;
  };
  // Where an allocation of (size, alignment, kind) would start inside the free range
  // [begin, end), or nullopt when it does not fit there.
  std::optional<std::uint64_t> placeIn(std::uint64_t begin, std::uint64_t end, std::uint64_t size,
                                       std::uint64_t alignment, Kind kind) const;
  std::uint64_t page(std::uint64_t offset) const { return offset / granularity_; }

  std::uint64_t capacity_;
  std::uint64_t granularity_;
  std::uint64_t used_bytes_ = 0;
  std::map<std::uint64_t, std::uint64_t> free_;  // offset → size, coalesced (no two adjacent)
  std::map<std::uint64_t, Used> used_;           // offset → allocation
};

}  // namespace bounce::gpu
