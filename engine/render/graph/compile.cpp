// The compile stages of the render graph, in the order compile() runs them.
#include <algorithm>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/render/graph/render_graph.hpp"

namespace bounce::rg {

const GraphStats& RenderGraph::compile() {
  cull();
  checkOrder();
  allocateTransients();
  deriveBarriers();

  stats_ = GraphStats{};
  for (const auto& p : passes_)
    if (p.culled) stats_.culledPasses.push_back(p.name);
  for (std::size_t pos = 0; pos < order_.size(); ++pos) {
    stats_.executedPasses.push_back(passes_[order_[pos]].name);
    stats_.barriers.push_back({passes_[order_[pos]].name, passBarriers_[pos]});
  }
  stats_.finalBarriers = finalBarriers_;
  for (const auto& r : resources_) {
    if (r.slot < 0) continue;
    (r.kind == ResourceKind::Texture ? stats_.transientTextures : stats_.transientBuffers)++;
  }
  for (const auto& s : slots_) (s.kind == ResourceKind::Texture ? stats_.physicalTextures : stats_.physicalBuffers)++;
  compiled_ = true;
  return stats_;
}

// Stage 1. A pass survives when a sink needs it: it has a side effect, it produced the final
// version of an output, or it produced a version a surviving pass reads or writes over (a
// write keeps the earlier content, see Builder::write). Everything else is culled, so dropping
// a pass also drops producers that only it needed.
void RenderGraph::cull() {
  std::vector<std::uint32_t> stack;
  for (std::uint32_t p = 0; p < passes_.size(); ++p) {
    passes_[p].culled = cullingEnabled_;
    if (!cullingEnabled_ || passes_[p].sideEffect) stack.push_back(p);
  }
  for (const auto& r : resources_)
    if (r.output && r.producers.back() >= 0) stack.push_back(static_cast<std::uint32_t>(r.producers.back()));
  while (!stack.empty()) {
    std::uint32_t p = stack.back();
    stack.pop_back();
    if (!passes_[p].culled && cullingEnabled_) continue;  // already reached
    passes_[p].culled = false;
    for (const auto& a : passes_[p].accesses) {
      std::int32_t producer = resources_[a.resource].producers[a.version];
      if (producer >= 0 && passes_[producer].culled) stack.push_back(static_cast<std::uint32_t>(producer));
    }
  }
  order_.clear();
  for (std::uint32_t p = 0; p < passes_.size(); ++p)
    if (!passes_[p].culled) order_.push_back(p);
}

// Stage 2. Declaration order is the execution order. It is a valid topological order because
// a pass can only name a version an earlier pass produced; this checks that invariant.
void RenderGraph::checkOrder() const {
  for (std::uint32_t p : order_)
    for (const auto& a : passes_[p].accesses) {
      std::int32_t producer = resources_[a.resource].producers[a.version];
      if (producer >= static_cast<std::int32_t>(p))
        throw InternalError("render graph: pass '" + passes_[p].name + "' depends on pass '" +
                            passes_[producer].name + "', which is not declared before it");
    }
}

// Stage 3. Lifetimes are positions in the execution order; two transients share a slot when
// their descriptions are identical and one's last use comes strictly before the other's first
// (a pass using both needs both at once). Greedy in order of first use: the earliest-created
// free slot wins, which keeps the assignment deterministic.
void RenderGraph::allocateTransients() {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> first(resources_.size(), kUnused), last(resources_.size(), 0);
  std::vector<UsageSet> usages(resources_.size());
  for (std::uint32_t pos = 0; pos < order_.size(); ++pos)
    for (const auto& a : passes_[order_[pos]].accesses) {
      first[a.resource] = std::min(first[a.resource], pos);
      last[a.resource] = pos;
      usages[a.resource].add(a.usage);
    }
  std::vector<std::uint32_t> transients;
  for (std::uint32_t r = 0; r < resources_.size(); ++r) {
    resources_[r].slot = -1;
    if (!resources_[r].imported && first[r] != kUnused) transients.push_back(r);
  }
  std::stable_sort(transients.begin(), transients.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return first[a] < first[b]; });
  slots_.clear();
  for (std::uint32_t r : transients) {
    ResourceNode& res = resources_[r];
    auto fits = [&](const Slot& s) {
      if (s.kind != res.kind || s.busyUntil >= first[r]) return false;
      return res.kind == ResourceKind::Texture ? s.texture == res.texture : s.buffer == res.buffer;
    };
    auto it = std::find_if(slots_.begin(), slots_.end(), fits);
    if (it == slots_.end()) {
      slots_.push_back(Slot{res.kind, res.texture, res.buffer, {}, {}, 0});
      it = slots_.end() - 1;
    }
    it->usages.add(usages[r]);
    it->occupants.push_back(r);
    it->busyUntil = last[r];
    res.slot = static_cast<std::int32_t>(it - slots_.begin());
  }
}

// The combined state a pass needs for one resource it declared (possibly more than once, e.g.
// StorageRead + StorageWrite); layouts were checked compatible at declaration.
ResourceState RenderGraph::passState(const PassNode& pass, std::uint32_t resource) const {
  const ResourceNode& r = resources_[resource];
  ResourceState merged;
  bool firstAccess = true;
  for (const auto& a : pass.accesses) {
    if (a.resource != resource) continue;
    ResourceState s = stateFor(a.usage, r.kind, a.write && keepsContents(r, a.version));
    if (firstAccess || s.layout == Layout::DepthReadOnly) merged.layout = s.layout;
    merged.stages |= s.stages;
    merged.access |= s.access;
    firstAccess = false;
  }
  return merged;
}

namespace {

// What the barrier derivation knows about one resource between passes.
struct Track {
  bool touched = false;  // false: a transient not used yet (its memory holds nothing of it)
  Layout layout = Layout::Undefined;
  Stage writeStages = Stage::None;  // stages of the last write (or layout transition)
  Access writeAccess = Access::None;
  Stage readStages = Stage::None;  // stages already synchronised with that write, and reading
  Access readAccess = Access::None;
};

}  // namespace

// Stage 4. Walk the passes in order, tracking each resource's state, and emit a barrier when:
//  - a transient is used the first time: Undefined -> needed layout (for an image), waiting for
//    the previous occupant of its slot when it aliases one;
//  - the pass writes: wait for the last write and every read since (write-after-read needs an
//    execution dependency, write-after-write a memory dependency);
//  - the layout changes;
//  - the pass reads in stages or with accesses that have not been synchronised with the last
//    write yet. A read in the same layout by stages already synchronised needs nothing.
void RenderGraph::deriveBarriers() {
  std::vector<Track> tracks(resources_.size());
  for (std::size_t i = 0; i < resources_.size(); ++i) {
    const ResourceNode& r = resources_[i];
    if (!r.imported) continue;
    Track& t = tracks[i];
    t.touched = true;
    t.layout = r.initial.layout;
    if (writeAccesses(r.initial.access) != Access::None) {
      t.writeStages = r.initial.stages;
      t.writeAccess = writeAccesses(r.initial.access);
    } else {
      t.readStages = r.initial.stages;
      t.readAccess = r.initial.access;
    }
  }

  auto transition = [&](std::uint32_t index, const ResourceState& s, std::vector<Barrier>& out) {
    Track& t = tracks[index];
    const ResourceNode& r = resources_[index];
    const bool image = r.kind == ResourceKind::Texture;
    const bool writes = writeAccesses(s.access) != Access::None;
    const bool relayout = image && t.touched && s.layout != t.layout;
    Barrier b{index, r.kind, 0, {}, s};
    bool emit = false;
    if (!t.touched) {
      const auto& occupants = slots_[r.slot].occupants;
      auto self = std::find(occupants.begin(), occupants.end(), index);
      if (self != occupants.begin()) {
        const Track& prev = tracks[*(self - 1)];
        b.before = {Layout::Undefined, prev.writeStages | prev.readStages, prev.writeAccess};
      }
      emit = image || b.before.stages != Stage::None;
    } else if (writes || relayout) {
      b.before = {t.layout, t.writeStages | t.readStages, t.writeAccess};
      emit = relayout || b.before.stages != Stage::None;
    } else {
      bool synchronised = (s.stages & Stage(~static_cast<std::uint32_t>(t.readStages))) == Stage::None &&
                          (s.access & Access(~static_cast<std::uint32_t>(t.readAccess))) == Access::None;
      b.before = {t.layout, t.writeStages, t.writeAccess};
      emit = !synchronised && b.before.stages != Stage::None;
    }
    if (emit) out.push_back(b);

    if (writes || !t.touched) {
      t.writeStages = s.stages;
      t.writeAccess = writeAccesses(s.access);
      t.readStages = Stage::None;
      t.readAccess = Access::None;
    } else if (relayout) {
      // The transition acts as a write ordered before s.stages: later readers chain through them.
      t.writeStages |= s.stages;
      t.readStages = s.stages;
      t.readAccess = s.access;
    } else {
      t.readStages |= s.stages;
      t.readAccess |= s.access;
    }
    t.layout = image ? s.layout : Layout::Undefined;
    t.touched = true;
  };

  passBarriers_.assign(order_.size(), {});
  for (std::size_t pos = 0; pos < order_.size(); ++pos) {
    const PassNode& pass = passes_[order_[pos]];
    std::vector<std::uint32_t> seen;
    for (const auto& a : pass.accesses) {
      if (std::find(seen.begin(), seen.end(), a.resource) != seen.end()) continue;
      seen.push_back(a.resource);
      transition(a.resource, passState(pass, a.resource), passBarriers_[pos]);
    }
  }
  finalBarriers_.clear();
  for (std::uint32_t i = 0; i < resources_.size(); ++i)
    if (resources_[i].output)
      transition(i, stateFor(resources_[i].outputUsage, resources_[i].kind, true), finalBarriers_);
  for (std::size_t i = 0; i < resources_.size(); ++i) {
    const Track& t = tracks[i];
    resources_[i].finalState = {t.layout, t.writeStages | t.readStages, t.writeAccess | t.readAccess};
  }
}

}  // namespace bounce::rg
