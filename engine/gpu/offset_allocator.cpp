#include "engine/gpu/offset_allocator.hpp"

#include <string>

#include "engine/core/error.hpp"

namespace bounce::gpu {
namespace {
bool isPowerOfTwo(std::uint64_t v) { return v != 0 && (v & (v - 1)) == 0; }
std::uint64_t alignUp(std::uint64_t v, std::uint64_t a) { return (v + a - 1) & ~(a - 1); }
}  // namespace

OffsetAllocator::OffsetAllocator(std::uint64_t capacity, std::uint64_t granularity)
    : capacity_(capacity), granularity_(granularity) {
  if (!isPowerOfTwo(granularity_))
    throw InternalError("OffsetAllocator: granularity " + std::to_string(granularity) + " is not a power of two");
  if (capacity_ > 0) free_.emplace(0, capacity_);
}

std::optional<std::uint64_t> OffsetAllocator::placeIn(std::uint64_t begin, std::uint64_t end, std::uint64_t size,
                                                      std::uint64_t alignment, Kind kind) const {
  std::uint64_t start = alignUp(begin, alignment);
  // The allocation ending at `begin` (free ranges are coalesced, so anything adjacent is used).
  if (begin > 0) {
    auto prev = used_.lower_bound(begin);
    if (prev != used_.begin()) {
      --prev;
      std::uint64_t prevLast = prev->first + prev->second.size - 1;
      if (prev->second.kind != kind && page(prevLast) == page(start)) start = alignUp(start, granularity_);
    }
  }
  if (start < begin || start > end || end - start < size) return std::nullopt;
  auto next = used_.find(end);
  if (next != used_.end() && next->second.kind != kind && page(start + size - 1) == page(end)) return std::nullopt;
  return start;
}

std::optional<std::uint64_t> OffsetAllocator::allocate(std::uint64_t size, std::uint64_t alignment, Kind kind) {
  if (size == 0) throw InternalError("OffsetAllocator: zero-size allocation");
  if (!isPowerOfTwo(alignment))
    throw InternalError("OffsetAllocator: alignment " + std::to_string(alignment) + " is not a power of two");
  std::optional<std::uint64_t> best;
  std::uint64_t bestRange = 0, bestLeft = 0;
  for (auto [offset, rangeSize] : free_) {
    if (rangeSize < size) continue;
    auto start = placeIn(offset, offset + rangeSize, size, alignment, kind);
    if (!start) continue;
    std::uint64_t left = rangeSize - size;  // padding counts as waste too
    if (!best || left < bestLeft) {
      best = start;
      bestRange = offset;
      bestLeft = left;
    }
  }
  if (!best) return std::nullopt;
  std::uint64_t rangeEnd = bestRange + free_[bestRange];
  free_.erase(bestRange);
  if (*best > bestRange) free_.emplace(bestRange, *best - bestRange);
  if (*best + size < rangeEnd) free_.emplace(*best + size, rangeEnd - (*best + size));
  used_.emplace(*best, Used{size, kind});
  used_bytes_ += size;
  return best;
}

void OffsetAllocator::free(std::uint64_t offset) {
  auto it = used_.find(offset);
  if (it == used_.end())
    throw InternalError("OffsetAllocator: free of offset " + std::to_string(offset) + " which is not allocated");
  std::uint64_t begin = offset, end = offset + it->second.size;
  used_bytes_ -= it->second.size;
  used_.erase(it);
  // Coalesce with the free neighbours on both sides.
  auto next = free_.find(end);
  if (next != free_.end()) {
    end += next->second;
    free_.erase(next);
  }
  auto prev = free_.lower_bound(begin);
  if (prev != free_.begin()) {
    --prev;
    if (prev->first + prev->second == begin) {
      begin = prev->first;
      free_.erase(prev);
    }
  }
  free_.emplace(begin, end - begin);
}

std::uint64_t OffsetAllocator::largestFreeRange() const {
  std::uint64_t best = 0;
  for (auto [offset, size] : free_) best = size > best ? size : best;
  return best;
}

}  // namespace bounce::gpu
