// Graphviz DOT dump of the compiled graph: `dot -Tsvg graph.dot -o graph.svg`.
#include <set>
#include <sstream>
#include <utility>

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
// Culled passes, and versions only they produce, are dashed and grey. Versions no edge touches are
// left out; a legend cluster explains the notation.
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
  // Only versions an edge touches are drawn: an imported resource's version 0 that its first pass
  // overwrites without reading, for example, would float unconnected in the picture.
  std::set<std::pair<std::uint32_t, std::uint32_t>> connected;
  for (const PassNode& pass : passes_)
    for (const auto& a : pass.accesses) {
      connected.insert({a.resource, a.write ? a.version + 1 : a.version});
      if (a.write && keepsContents(resources_[a.resource], a.version)) connected.insert({a.resource, a.version});
    }
  for (std::uint32_t r = 0; r < resources_.size(); ++r) {
    const ResourceNode& res = resources_[r];
    std::string detail = res.kind == ResourceKind::Texture ? describe(res.texture) : describe(res.buffer);
    for (std::uint32_t v = 0; v < res.producers.size(); ++v) {
      std::int32_t producer = res.producers[v];
      bool culled = producer >= 0 && passes_[producer].culled;
      if (!connected.count({r, v})) continue;
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
  // What the shapes, colours and line styles mean.
  out << "  subgraph cluster_legend {\n    label=\"legend\"; fontname=\"Helvetica\"; color=grey70;\n"
      << "    legend_pass [label=\"pass\", shape=box, style=filled, fillcolor=lightblue];\n"
      << "    legend_side [label=\"pass with side effects\", shape=box, style=filled, fillcolor=lightsalmon];\n"
      << "    legend_culled [label=\"culled pass\", shape=box, style=\"dashed\", color=grey60, fontcolor=grey60];\n"
      << "    legend_version [label=\"resource version\\n(bold: imported,\\ndouble: output)\", shape=ellipse];\n"
      << "    legend_written [label=\"new version\", shape=ellipse];\n"
      << "    legend_version -> legend_pass [label=\"read\", color=darkgreen];\n"
      << "    legend_pass -> legend_written [label=\"write\", color=red];\n"
      << "    legend_version -> legend_side [label=\"kept under a write\", style=dotted];\n"
      << "  }\n";
  out << "}\n";
  return out.str();
}

}  // namespace bounce::rg
