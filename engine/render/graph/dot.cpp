// Graphviz DOT dump of the compiled graph: `dot -Tsvg graph.dot -o graph.svg`.
#include <sstream>

#include "engine/render/graph/render_graph.hpp"

namespace bounce::rg {

namespace {

// Escape a name for a DOT string (quotes and backslashes; "\\n" added by the caller is a line break).
std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string quoted(const std::string& s) { return "\"" + escaped(s) + "\""; }

std::string versionNode(std::uint32_t resource, std::uint32_t version) {
  return "r" + std::to_string(resource) + "_v" + std::to_string(version);
}

}  // namespace

// Passes are boxes p<i> labelled with the exact pass name; each version of a resource is an
// ellipse r<i>_v<v> labelled "name\nvN" (imported ones bold, outputs with a double border).
// Edges: version -> pass for a read, pass -> new version for a write, labelled with the usage;
// a write that keeps earlier content also gets a dotted edge from the version it writes over.
// Culled passes, and versions only they produce, are dashed and grey.
std::string RenderGraph::toDot() {
  if (!compiled_) compile();
  std::ostringstream out;
  out << "digraph render_graph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\"];\n";
  for (std::uint32_t p = 0; p < passes_.size(); ++p) {
    const PassNode& pass = passes_[p];
    out << "  p" << p << " [label=" << quoted(pass.name) << ", shape=box";
    if (pass.culled) out << ", style=\"dashed\", color=grey60, fontcolor=grey60";
    else out << ", style=filled, fillcolor=" << (pass.sideEffect ? "lightsalmon" : "lightblue");
    out << "];\n";
  }
  for (std::uint32_t r = 0; r < resources_.size(); ++r) {
    const ResourceNode& res = resources_[r];
    std::string detail = res.kind == ResourceKind::Texture ? describe(res.texture) : describe(res.buffer);
    for (std::uint32_t v = 0; v < res.producers.size(); ++v) {
      std::int32_t producer = res.producers[v];
      bool culled = producer >= 0 && passes_[producer].culled;
      if (v == 0 && !res.imported) continue;  // a transient's empty version 0 is not data
      out << "  " << versionNode(r, v) << " [label=" << "\"" << escaped(res.name) << "\\nv" << v << "\\n" << detail << "\""
          << ", shape=ellipse";
      if (culled) out << ", style=\"dashed\", color=grey60, fontcolor=grey60";
      else if (res.imported) out << ", style=bold";
      if (res.output && v + 1 == res.producers.size()) out << ", peripheries=2";
      out << "];\n";
    }
  }
  for (std::uint32_t p = 0; p < passes_.size(); ++p)
    for (const auto& a : passes_[p].accesses) {
      std::string usage = quoted(usageName(a.usage));
      const bool culled = passes_[p].culled;
      std::string style = culled ? ", style=dashed, color=grey60" : (a.write ? ", color=red" : ", color=darkgreen");
      if (a.write) {
        out << "  p" << p << " -> " << versionNode(a.resource, a.version + 1) << " [label=" << usage << style << "];\n";
        if (keepsContents(resources_[a.resource], a.version))
          out << "  " << versionNode(a.resource, a.version) << " -> p" << p << " [style=dotted];\n";
      } else {
        out << "  " << versionNode(a.resource, a.version) << " -> p" << p << " [label=" << usage << style << "];\n";
      }
    }
  out << "}\n";
  return out.str();
}

}  // namespace bounce::rg
